"""gradem.calibrate, Ledger and Model on the analytic stand-in (calibrate/analytic_model.cpp):
the command line's calibration, a repeated point from the ledger, scipy recovering known
parameters."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import least_squares

import gradem
from conftest import SANDS, run_cli, write_problem

TRUTH = {"effective_modulus_gpa": 20.0, "tensile_strength_mpa": 12.0, "cohesion_ratio": 1.6, "strength_cv": 0.25}
# The summary's entries that name where, when and by which build it ran.
PLACES = ("ledger", "wall_seconds", "code_version")


def without_places(x):
    if isinstance(x, dict):
        return {k: without_places(v) for k, v in x.items() if k not in PLACES}
    if isinstance(x, list):
        return [without_places(v) for v in x]
    return x


def test_calibrate_equals_the_command_line(analytic_problem, tmp_path):
    folder = analytic_problem.parent
    run_cli("calibrate", analytic_problem, "--max-runs", 24, "--out", tmp_path / "cli", "--quiet", cwd=folder)
    seen = []
    summary = gradem.calibrate(analytic_problem, max_runs=24, out=tmp_path / "py", progress=seen.append)
    cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    assert summary == json.loads((tmp_path / "py" / "summary.json").read_text())
    assert without_places(summary) == without_places(cli)
    assert summary["runs"] == cli["runs"] and summary["parameters"] == cli["parameters"]
    assert seen and seen[-1]["runs_used"] <= 24 and all(p["max_runs"] == 24 for p in seen)
    assert len(seen[-1]["sand_mean_run_s"]) == 2 and all(t >= 0.0 for t in seen[-1]["sand_mean_run_s"])  # both sands ran
    # the ETA of the runs still expected, never more than the budget's bound; NaN only while no run was timed
    timed = [p for p in seen if p["mean_run_s"] > 0.0]
    assert timed and all(0.0 <= p["eta_s"] <= p["eta_max_s"] for p in timed)
    assert all(math.isnan(p["eta_s"]) for p in seen if p["mean_run_s"] == 0.0)

    py, cli = gradem.Ledger(tmp_path / "py" / "ledger.sqlite"), gradem.Ledger(tmp_path / "cli" / "ledger.sqlite")
    assert len(py) == len(cli) > 0
    assert py.meta["problem_fingerprint"] == cli.meta["problem_fingerprint"]
    key = lambda r: (r["run_key"], r["sand"], r["seed"])  # noqa: E731
    for a, b in zip(sorted(py, key=key), sorted(cli, key=key)):
        assert (a["parameters"], a["peak_pa"], a["modulus_pa"], a["strain_at_peak"]) == \
               (b["parameters"], b["peak_pa"], b["modulus_pa"], b["strain_at_peak"])
    table = py.table(status="ok")
    assert len(table["sequence"]) == len(py) and np.all(table["effective_modulus_gpa"] > 0)


def test_a_callback_that_raises_stops_the_calibration(analytic_problem, tmp_path):
    def stop(p):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        gradem.calibrate(analytic_problem, max_runs=24, out=tmp_path / "stopped", progress=stop)
    with pytest.raises(ValueError, match="max_runs = 0"):
        gradem.calibrate(analytic_problem, max_runs=0)
    with pytest.raises(gradem.InputError, match="no_such_problem.toml"):
        gradem.calibrate(tmp_path / "no_such_problem.toml")


def test_model_runs_each_point_once(analytic_problem):
    model = gradem.Model(analytic_problem, workers=2)
    assert model.names == list(TRUTH) and model.sands == list(SANDS) and model.seeds == [1, 2]
    out = model(TRUTH)
    assert set(out) == set(SANDS)
    for sand in SANDS:
        for q in ("chord_modulus_mpa", "peak_stress_mpa", "strain_at_peak"):
            assert out[sand][q].shape == (2,) and np.all(out[sand][q] > 0)
        assert out[sand]["status"] == ["ok", "ok"]
    assert model.runs_executed == 4
    again = model(TRUTH)
    assert model.runs_executed == 4  # a repeated point is free
    assert all(np.array_equal(again[s]["peak_stress_mpa"], out[s]["peak_stress_mpa"]) for s in SANDS)
    fresh = gradem.Model(analytic_problem)
    fresh(TRUTH)
    assert fresh.runs_executed == 0 and fresh.runs_from_ledger == 4  # from the problem's ledger
    assert len(gradem.Ledger(model.ledger)) == 4


def test_model_gives_each_sand_its_own_seeds(tmp_path):
    targets = {"pre-blended": (15000.0, 30.0, 0.003), "Van Buren": (13000.0, 25.0, 0.0031)}
    own = gradem.Model(write_problem(tmp_path / "own", targets, calibration_keys='sand_seeds = { "Van Buren" = [1, 2, 3] }\n'))
    plain = gradem.Model(write_problem(tmp_path / "plain", targets))
    out, same = own(TRUTH), plain(TRUTH)
    assert out["pre-blended"]["seeds"] == [1, 2] and out["Van Buren"]["seeds"] == [1, 2, 3]
    assert out["pre-blended"]["peak_stress_mpa"].shape == (2,) and out["Van Buren"]["peak_stress_mpa"].shape == (3,)
    assert own.runs_executed == 5
    # Each sand's values are its own runs': seeds 1 and 2 give what the problem without the key gives.
    for sand in SANDS:
        assert np.array_equal(out[sand]["peak_stress_mpa"][:2], same[sand]["peak_stress_mpa"])
    assert out["Van Buren"]["peak_stress_mpa"][2] not in out["Van Buren"]["peak_stress_mpa"][:2]


def test_model_checks_the_parameters(analytic_problem):
    model = gradem.Model(analytic_problem)
    with pytest.raises(ValueError, match=r"'strength_cv' = 0.9 violates in \[0(\.0)?, 0.5\] \(its bounds in .*problem.toml\)"):
        model({**TRUTH, "strength_cv": 0.9})
    with pytest.raises(ValueError, match="'cohesion_ratio' missing"):
        model({k: v for k, v in TRUTH.items() if k != "cohesion_ratio"})
    with pytest.raises(ValueError, match=r"'friction' is not a parameter of .*problem.toml \(free: effective_modulus_gpa, "):
        model({**TRUTH, "friction": 0.3})
    assert model.runs_executed == 0


def test_scipy_recovers_known_parameters(tmp_path):
    # Targets: the stand-in's seed means at TRUTH (a twin experiment); scipy's least_squares
    # from the problem's start point on the calibration's residuals.
    first = gradem.Model(write_problem(tmp_path / "truth", {s: (1.0, 1.0, 1.0) for s in SANDS}))
    at_truth = first(TRUTH)
    targets = {s: tuple(float(np.mean(at_truth[s][q])) for q in ("chord_modulus_mpa", "peak_stress_mpa", "strain_at_peak"))
               for s in SANDS}
    model = gradem.Model(write_problem(tmp_path / "twin", targets))
    lower, upper = np.array(model.bounds).T
    points = set()

    def residuals(x):
        points.add(tuple(x))
        return model.residuals(model.params(x))

    fit = least_squares(residuals, [model.start[n] for n in model.names],
                        bounds=(lower, upper), x_scale=upper - lower, xtol=1e-10, ftol=1e-12)
    got = model.params(fit.x)
    for name, value in TRUTH.items():
        assert got[name] == pytest.approx(value, rel=1e-3), (name, got)
    assert model.objective(got) < 1e-10
    assert model.runs_executed == 4 * len(points)  # 2 sands x 2 seeds per point, a repeated one free


def test_study_equals_the_command_line(analytic_problem, tmp_path):
    gradem.calibrate(analytic_problem, max_runs=24, out=tmp_path / "cal")
    study = tmp_path / "study.toml"
    study.write_text(f'[study]\nkind = "gradation_effect"\ncalibration = "{tmp_path / "cal" / "summary.json"}"\n'
                     f'seeds = [11, 12, 13]\n[output]\ndir = "study-out"\n')
    run_cli("study", study, "--out", tmp_path / "cli", "--quiet", cwd=tmp_path)
    lines = []
    doc = gradem.study(study, out=tmp_path / "py", log=lines.append)
    cli = json.loads((tmp_path / "cli" / "study.json").read_text())
    assert without_places(doc) == without_places(cli)
    assert doc["kind"] == "gradation_effect" and lines
