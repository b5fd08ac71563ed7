"""Fixtures of the Python module's tests: the command line beside the module, a tiny cube config
and a tiny analytic calibration problem, each written into the test's temporary folder."""

import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("GRADEM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("GRADEM_CLI", str(SOURCE / "build" / "app" / "gradem"))
SANDS = ("pre-blended", "Van Buren")


def tiny_cube_text(max_strain=0.004):
    """A cube of ~200 grains (0.4-1.0 mm in a 3 mm cube), its test stopped at `max_strain`
    (0.4 %: about a second of simulation, before the peak)."""
    return (f'[specimen]\nsieve_csv = "{SOURCE}/lab_data/datasets/study/sieve_pre_blended.csv"\n'
            "[size_rule]\nmin_diameter_mm = 0.4\nmax_diameter_mm = 1.0\n"
            "[genesis]\nedge_mm = 3.0\ntarget_solid_fraction = 0.55\n"
            f"[test]\nmax_strain = {max_strain}\n"
            '[output]\ndir = "out"\ncache_dir = "cache"\n')


@pytest.fixture
def tiny_cube(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(tiny_cube_text())
    return path


def lab_results(targets):
    """lab_results.json of {sand: (modulus MPa, peak MPa, strain at peak)}, 3 % std."""
    sands = []
    for name, (e, s, eps) in targets.items():
        stat = lambda v: {"n": 3, "mean": v, "std": 0.03 * v}  # noqa: E731
        sands.append({"name": name, "chord_modulus_mpa": stat(e), "peak_stress_mpa": stat(s), "strain_at_peak": stat(eps)})
    return {"schema": "gradem-lab-results/1", "representative_data": True, "note": "synthetic targets", "sands": sands}


def write_problem(folder, targets, max_runs=30, seeds=(1, 2), calibration_keys=""):
    """An analytic-stand-in calibration problem of the four default free parameters
    (`calibration_keys`: more lines of its [calibration] table)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "lab_results.json").write_text(json.dumps(lab_results(targets)))
    (folder / "problem.toml").write_text(
        f'[calibration]\nbase = "{SOURCE}/experiments/configs/calibration_cube.toml"\nmodel = "analytic"\n'
        f"seeds = {list(seeds)}\n{calibration_keys}"
        '[targets]\nlab_results = "lab_results.json"\n'
        f'[solver]\nmax_runs = {max_runs}\n[output]\ndir = "out"\n')
    return folder / "problem.toml"


@pytest.fixture
def analytic_problem(tmp_path):
    return write_problem(tmp_path / "problem",
                         {"pre-blended": (15000.0, 30.0, 0.003), "Van Buren": (13000.0, 25.0, 0.0031)})


def run_cli(*args, cwd, expect=0):
    """`gradem <args>` in `cwd` (report.html left out: its python is a missing one); the
    completed process, its exit status checked."""
    env = dict(os.environ, GRADEM_PYTHON="/nonexistent/python3", OMP_NUM_THREADS="1")
    p = subprocess.run([CLI, *map(str, args)], cwd=cwd, env=env, capture_output=True, text=True)
    assert p.returncode == expect, f"gradem {' '.join(map(str, args))}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
    return p
