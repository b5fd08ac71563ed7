"""gradem.specimen, compress and tension: the command line's numbers, bitwise, and Ctrl-C."""

import csv
import json
import os
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import gradem
from conftest import run_cli, tiny_cube_text

# macro.json's timings: the only entries a run may change.
TIMINGS = ("wall_seconds", "particle_steps_per_s")


def without_timings(macro):
    m = {k: v for k, v in macro.items() if k != "config"}  # the config's path as given
    m["run"] = {k: v for k, v in m["run"].items() if k not in TIMINGS}
    return m


def test_compress_equals_the_command_line_bitwise(tiny_cube, tmp_path):
    cfg = gradem.CubeConfig.load(tiny_cube)
    cfg.material.effective_modulus_gpa = 14.5  # an override, run by the command line from the saved file
    cfg.material.tensile_strength_mpa = 7.25
    cfg.save(tmp_path / "saved.toml")
    run_cli("compress", "saved.toml", "--out", "cli", "--quiet", cwd=tmp_path)
    cli = json.loads((tmp_path / "cli" / "macro.json").read_text())

    py = gradem.compress(cfg, threads=1, out=tmp_path / "py")
    assert cli["material"]["display"]["tensile_strength_mpa"] == 7.25  # the command line ran the override
    assert without_timings(py.macro) == without_timings(cli)
    for key in ("peak_stress_mpa", "strain_at_peak", "chord_modulus_mpa", "poisson_ratio"):
        assert py.macro[key].hex() == cli[key].hex()
    with open(tmp_path / "cli" / "load_curve.csv") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, rows = rows[0], rows[1:]
    assert len(rows) == len(py.curve["stress_mpa"]) > 10
    stress = header.index(next(h for h in header if h.startswith("stress_mpa") or h == "stress_mpa"))
    np.testing.assert_allclose(py.curve["stress_mpa"], [float(r[stress]) for r in rows], rtol=1e-9)
    # out= writes the command line's files, from the same writer
    assert without_timings(json.loads((tmp_path / "py" / "macro.json").read_text())) == without_timings(cli)
    assert py.provenance["overrides"] == {"material.effective_modulus_gpa": "14.5", "material.tensile_strength_mpa": "7.25"}
    assert py.provenance["threads"] == 1 and py.provenance["packing_cached"]
    assert py.provenance["code_version"] == gradem.code_version


def test_the_thread_count_changes_no_bit(tiny_cube):
    # A couple of thousand steps: 2 threads on a machine whose other core is busy wait at every barrier.
    cfg = gradem.CubeConfig.load(tiny_cube).copy({"test.max_strain": 0.00005})
    one, two = gradem.compress(cfg, threads=1), gradem.compress(cfg, threads=2)
    assert two.provenance["threads"] == 2 and len(two.curve["step"]) > 10
    assert all(np.array_equal(one.curve[k], two.curve[k]) for k in one.curve)
    assert without_timings(one.macro) == without_timings(two.macro)


def test_specimen_is_the_cached_packing(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube)
    first = gradem.specimen(cfg)
    again = gradem.specimen(cfg)
    assert not first.cached and again.cached and os.path.exists(again.path)
    n = len(first)
    assert 100 < n < 400 and first.positions.shape == (n, 3) and first.radii.shape == (n,)
    assert np.array_equal(first.positions, again.positions) and np.array_equal(first.radii, again.radii)
    assert first.families.dtype == np.uint8 and not first.families.any()  # sand grains only
    assert first.radii.min() >= 0.2e-3 * 0.99 and first.radii.max() <= 0.5e-3 * 1.2  # [m], 0.4-1.0 mm grains
    lo, hi = np.array(first.box_lo), np.array(first.box_hi)
    assert (first.positions > lo).all() and (first.positions < hi).all()


def test_tension_and_the_crack_log(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube).copy({"test.max_strain": 0.002})
    r = gradem.tension(cfg, threads=1)
    assert r.test == "direct tension" and r.peak_stress_mpa > 0 and not r.diverged
    c = r.cracks
    assert set(c) >= {"step", "x_m", "shear", "tensile_stress_mpa"}
    assert all(len(v) == len(c["step"]) for v in c.values())


def test_progress_sees_every_point_and_its_exception_stops_the_run(tiny_cube):
    cfg = gradem.CubeConfig.load(tiny_cube).copy({"test.max_strain": 0.0015})
    seen = []
    r = gradem.compress(cfg, threads=1, progress=lambda p: seen.append(p["stress_mpa"]))
    assert len(seen) == len(r.curve["stress_mpa"])

    class Stop(Exception):
        pass

    def stop(p):
        if p["platen_strain"] > 0.0005:
            raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        gradem.compress(cfg, threads=1, progress=stop)


def test_a_run_releases_the_gil(tiny_cube):
    # While a cube test runs on another Python thread, this one keeps running: no long gap.
    cfg = gradem.CubeConfig.load(tiny_cube)
    gradem.specimen(cfg)
    results = []
    worker = threading.Thread(target=lambda: results.append(gradem.compress(cfg, threads=1)))
    start = last = time.monotonic()
    gap = 0.0
    worker.start()
    while worker.is_alive():
        now = time.monotonic()
        gap, last = max(gap, now - last), now
        time.sleep(0.001)
    worker.join()
    assert results and results[0].macro["run"]["wall_seconds"] > 0.3
    assert gap < 0.25 < last - start, (gap, last - start)


def test_ctrl_c_stops_a_run_and_the_module_goes_on(tmp_path):
    (tmp_path / "long.toml").write_text(tiny_cube_text(max_strain=0.03))  # a test of several seconds
    script = textwrap.dedent("""
        import os, signal, threading, time, gradem
        cfg = gradem.CubeConfig.load("long.toml")
        gradem.specimen(cfg)
        threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        start = time.monotonic()
        try:
            gradem.compress(cfg, threads=1)
            print("not interrupted")
        except KeyboardInterrupt:
            print("interrupted after %.2f s" % (time.monotonic() - start))
        r = gradem.compress(cfg.copy({"test.max_strain": 0.0005}), threads=1)
        print("then ran", r.curve["stress_mpa"].size > 0)
    """)
    p = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0].startswith("interrupted after"), p.stdout
    assert float(lines[0].split()[2]) < 1.5  # within a few progress checks of the signal
    assert lines[1] == "then ran True"


def test_bad_arguments_are_value_errors(tiny_cube):
    with pytest.raises(ValueError, match="threads = 0"):
        gradem.compress(tiny_cube, threads=0)
    with pytest.raises(TypeError):
        gradem.compress(42)
