"""gradem.lab.read: `gradem lab`'s lab_results.json, with the curves as numpy arrays."""

import json

import numpy as np
import pytest

import gradem
from conftest import SOURCE, run_cli

STUDY = SOURCE / "lab_data" / "datasets" / "study"


def as_json(x):
    """numpy arrays as lists, the curves left out: what lab_results.json holds."""
    if isinstance(x, dict):
        return {k: as_json(v) for k, v in x.items() if k != "curve"}
    if isinstance(x, list):
        return [as_json(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tolist()
    return x


def test_lab_read_equals_the_command_line(tmp_path):
    run_cli("lab", STUDY, "--out", tmp_path / "lab", "--quiet", cwd=tmp_path)
    cli = json.loads((tmp_path / "lab" / "lab_results.json").read_text())
    lab = gradem.lab.read(STUDY)
    assert as_json(lab) == cli
    assert [s["name"] for s in lab["sands"]] == ["pre-blended", "Van Buren"]
    cube = lab["cubes"][0]["curve"]
    assert isinstance(cube["strain"], np.ndarray) and cube["strain"].shape == cube["stress_mpa"].shape
    assert cube["stress_mpa"].max() == pytest.approx(lab["cubes"][0]["peak_stress_mpa"], rel=1e-9)
    assert isinstance(lab["sands"][0]["gradation"]["percent_passing"], np.ndarray)


def test_a_bad_lab_file_names_file_and_line():
    bad = SOURCE / "tests" / "lab_data" / "fixtures" / "text_in_cell.csv"
    with pytest.raises(gradem.InputError, match=r"text_in_cell.csv:6: column 'load': 'abc' is not a number"):
        gradem.lab.read([bad])
