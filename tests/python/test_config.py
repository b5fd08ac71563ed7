"""gradem.CubeConfig: load, typed overrides checked by the config reader, save."""

import re

import pytest

import gradem
from conftest import run_cli, tiny_cube_text

KEY = "material.tensile_strength_mpa"


def message_after_location(text, file):
    """A message without its leading "<file>:<line>: " or "<file>: "."""
    m = re.search(re.escape(str(file)) + r"(:\d+)?: (.*)", text)
    assert m, f"no '{file}:' in {text!r}"
    return m.group(2).strip()


def test_load_reads_the_file_and_defaults(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube)
    assert cfg.genesis.edge_mm == 3.0
    assert cfg.test.max_strain == 0.004
    assert cfg.material.tensile_strength_mpa == 10.0  # the reader's default when the file omits it
    assert cfg.bond_model == "parallel_bond"
    assert "tensile_strength_mpa" in cfg.material.keys()
    row = next(r for r in gradem.material_table() if r["key"] == "tensile_strength_mpa")
    assert row["unit"] == "MPa" and row["range"] == "> 0"


def test_an_override_is_the_key_in_the_file(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube)
    cfg.material.tensile_strength_mpa = 12
    cfg["material.cohesion_mpa"] = 30.5
    assert cfg.material.tensile_strength_mpa == 12.0 and isinstance(cfg.material.tensile_strength_mpa, float)
    assert cfg.overrides == {KEY: "12", "material.cohesion_mpa": "30.5"}
    del cfg.material.cohesion_mpa
    assert cfg.material.cohesion_mpa == gradem.CubeConfig.load(tiny_cube).material.cohesion_mpa  # the default again
    copy = cfg.copy({KEY: 7})
    assert copy.material.tensile_strength_mpa == 7.0 and cfg.material.tensile_strength_mpa == 12.0


@pytest.mark.parametrize("value, shown", [(-3, "-3"), (0, "0"), ("abc", '"abc"'), (float("inf"), "inf")])
def test_a_bad_override_raises_the_readers_message(tiny_cube, tmp_path, value, shown):
    # The same value written into the file: the command line's message, which the override's
    # must repeat after the file name (an override has no line).
    bad = tmp_path / "bad.toml"
    bad.write_text(tiny_cube_text() + f"[material]\ntensile_strength_mpa = {shown}\n")
    cli = run_cli("specimen", bad, "--show", cwd=tmp_path, expect=1)
    assert re.search(r"bad\.toml:\d+: key 'material\.tensile_strength_mpa'", cli.stderr), cli.stderr
    with pytest.raises(gradem.InputError) as loaded:
        gradem.CubeConfig.load(bad)
    assert re.search(r"bad\.toml:\d+: key 'material\.tensile_strength_mpa' = ", str(loaded.value))

    cfg = gradem.CubeConfig.load(tiny_cube)
    with pytest.raises(ValueError) as raised:
        cfg.material.tensile_strength_mpa = value
    assert isinstance(raised.value, gradem.InputError)
    text = str(raised.value)
    assert message_after_location(text, tiny_cube).startswith(message_after_location(cli.stderr, bad))
    assert f"key '{KEY}' = {shown}" in text
    assert "> 0" in text  # the allowed range, from the material table
    assert cfg.material.tensile_strength_mpa == 10.0 and cfg.overrides == {}  # nothing changed


def test_a_refused_set_changes_nothing_and_runs_nothing(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube)
    with pytest.raises(ValueError, match="genesis.edge_mm"):
        cfg.set({KEY: 9.0, "genesis.edge_mm": -1})
    assert cfg.material.tensile_strength_mpa == 10.0
    assert not (tiny_cube.parent / "cache").exists()  # no genesis was started


def test_unknown_and_foreign_keys_are_named(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube)
    with pytest.raises(ValueError, match=r"unknown key 'material.nonsense' \(known: .*tensile_strength_mpa"):
        cfg.material.nonsense = 1
    with pytest.raises(AttributeError, match="belongs to bond model"):
        cfg.material.softening_factor  # a soft-bond key in a parallel-bond config
    cfg.set({"material.model": "soft_bond", "material.softening_factor": 0.2})
    assert cfg.material.softening_factor == 0.2


def test_a_bad_file_names_file_line_and_key(tmp_path):
    bad = tmp_path / "cube.toml"
    bad.write_text(tiny_cube_text() + "[material]\nfriction = 0.5\nfriction_typo = 1\n")
    line = tiny_cube_text().count("\n") + 3
    with pytest.raises(gradem.InputError, match=rf"cube\.toml:{line}: unknown key 'material\.friction_typo'"):
        gradem.CubeConfig.load(bad)
    with pytest.raises(gradem.InputError, match="cannot open file"):
        gradem.CubeConfig.load(tmp_path / "missing.toml")


def test_save_writes_a_config_the_reader_reads_back(tiny_cube, tmp_path):
    cfg = gradem.CubeConfig.load(tiny_cube)
    cfg.material.tensile_strength_mpa = 12
    cfg.genesis.seed = 3
    saved = tmp_path / "elsewhere" / "saved.toml"
    saved.parent.mkdir()
    cfg.save(saved)
    again = gradem.CubeConfig.load(saved)
    assert again.keys() == {**cfg.keys(), "specimen.sieve_csv": cfg["specimen.sieve_csv"],
                            "output.cache_dir": again["output.cache_dir"], "output.dir": again["output.dir"]}
    assert again.material.tensile_strength_mpa == 12.0 and again.genesis.seed == 3
    assert again["output.cache_dir"] == str(tiny_cube.parent / "cache")  # shares the packing cache
