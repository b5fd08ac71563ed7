"""The examples of examples/python/ run on tiny inputs: the tiny cube, the analytic stand-in."""

import os
import subprocess
import sys

import pytest

from conftest import SOURCE, write_problem

EXAMPLES = SOURCE / "examples" / "python"


def run_example(name, *args, cwd):
    p = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=cwd, capture_output=True, text=True,
                       timeout=240, env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert p.returncode == 0, f"{name}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
    return p.stdout


def test_bond_strength_sweep(tiny_cube, tmp_path):
    pytest.importorskip("matplotlib", reason="python3-matplotlib is not installed")
    out = run_example("bond_strength_sweep.py", tiny_cube, tmp_path / "sweep.png", 4, 8, cwd=tmp_path)
    lines = out.splitlines()
    assert [line.split(":")[0] for line in lines] == ["tensile strength 4 MPa", "tensile strength 8 MPa"]
    assert (tmp_path / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_external_optimizer_then_ledger_table(tmp_path):
    # Targets the stand-in meets at one point: the fit gets there.
    problem = write_problem(tmp_path / "p", {"pre-blended": (15000.0, 30.0, 0.003), "Van Buren": (13000.0, 25.0, 0.0031)})
    out = run_example("external_optimizer.py", problem, 40, cwd=tmp_path)
    assert out.startswith("objective J = ") and "effective_modulus_gpa" in out
    assert out.count("simulated") == 6  # 2 sands x 3 quantities

    ledger = tmp_path / "p" / "out" / "ledger.sqlite"
    table = run_example("ledger_table.py", ledger, tmp_path / "runs.csv", cwd=tmp_path)
    runs = int(table.splitlines()[0].split(": ")[-1].split()[0])
    assert runs > 4 and "tensile_strength_mpa" in table.splitlines()[1]
    assert len((tmp_path / "runs.csv").read_text().splitlines()) == runs + 1
