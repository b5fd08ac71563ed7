"""Calibrations, studies, run ledgers, and a calibration problem as a function for other optimizers.

calibrate() and study() run what `gradem calibrate` and `gradem study` run, write the same files
(summary.json, ..., the ledger) and return the summary document as a dict. Model maps a dict
of the problem's free parameters to the cube tests of every sand and seed, through the
problem's ledger: a point run before (by Model, `gradem calibrate` or calibrate()) costs
nothing. Ctrl-C stops after the runs in flight, which stay in the ledger.
"""

import os

import numpy as np

from . import _gradem


def calibrate(problem, max_runs=None, workers=None, out=None, progress=None, log=None, report=False):
    """A calibration (calibrate/README.md): writes its outputs and returns summary.json as a dict.

    progress(p) gets a dict after every run (runs_used, max_runs, from_ledger, evaluations,
    elapsed_s, mean_run_s, sand_mean_run_s: per sand in the problem's order, 0 before its first
    run, best_objective, workers, and the command line's ETA in seconds: eta_s, and eta_max_s from
    the budget, NaN while no run has been timed); log(line) every milestone line; report
    makes report.html too (python3-matplotlib).
    """
    return _gradem.calibrate(os.fspath(problem), max_runs, workers, os.fspath(out) if out else "", progress, log, report)


def study(path, workers=None, out=None, log=None, report=False):
    """A parameter study (experiments/README.md "Studies"): writes its outputs, returns study.json as a dict."""
    return _gradem.study(os.fspath(path), workers, os.fspath(out) if out else "", log, report)


class Ledger:
    """A run ledger (SQLite, read-only): meta (problem, fingerprint, code version) and every run.

    Each run is a dict of the ledger's columns (SI units: modulus_pa, peak_pa, ...), its
    parameters (config units) as a dict, and its thinned curve as numpy arrays.
    """

    def __init__(self, path):
        self.path = os.fspath(path)
        d = _gradem.read_ledger(self.path)
        self.meta = d["meta"]
        self.runs = d["runs"]

    def __len__(self):
        return len(self.runs)

    def __iter__(self):
        return iter(self.runs)

    def __getitem__(self, k):
        return self.runs[k]

    def table(self, status=None):
        """The runs as columns (numpy arrays; each parameter a column of its own), e.g. for
        pandas.DataFrame(ledger.table()). status="ok" keeps the successful runs only."""
        runs = [r for r in self.runs if status is None or r["status"] == status]
        parameters = sorted({p for r in runs for p in r["parameters"]})
        columns = ["sequence", "sand", "seed", "status", "modulus_pa", "peak_pa", "strain_at_peak", "poisson",
                   "particles", "bonds", "steps", "wall_seconds", "rank", "host"]
        table = {c: np.array([r[c] for r in runs]) for c in columns}
        for p in parameters:
            table[p] = np.array([r["parameters"].get(p, np.nan) for r in runs], dtype=float)
        return table

    def __repr__(self):
        return f"Ledger({self.path!r}, {len(self)} runs)"


class Model:
    """A calibration problem's cube tests as a function of its free parameters.

        model = gradem.Model("problem.toml")
        model.names, model.bounds, model.start      # the free parameters, config units
        out = model({"effective_modulus_gpa": 10, "tensile_strength_mpa": 9})
        out["pre-blended"]["peak_stress_mpa"]      # one value per packing seed (numpy)
        r = model.residuals(params)                 # the calibration's residuals w (y_sim/y_lab - 1)

    Every sand of the problem runs on every seed; runs go to `workers` threads (default: the
    problem's [run] workers), and every run is looked up in and recorded into the problem's
    ledger (or `ledger`), so a repeated point is free. A parameter outside its bounds in the
    problem, a missing or unknown one is a ValueError.
    """

    def __init__(self, problem, workers=None, ledger=None, log=None):
        self._impl = _gradem.Model(os.fspath(problem), workers, os.fspath(ledger) if ledger else "", log)

    @property
    def parameters(self):
        """The free parameters: name, start, lower, upper, log_scale, unit, role."""
        return self._impl.parameters

    @property
    def names(self):
        return [p["name"] for p in self.parameters]

    @property
    def bounds(self):
        """[(lower, upper), ...] in the order of names (scipy.optimize's bounds)."""
        return [(p["lower"], p["upper"]) for p in self.parameters]

    @property
    def start(self):
        return {p["name"]: p["start"] for p in self.parameters}

    @property
    def sands(self):
        return self._impl.sands

    @property
    def seeds(self):
        return self._impl.seeds

    @property
    def targets(self):
        """The lab targets per sand and quantity: mean, std, n (display units)."""
        return self._impl.targets

    @property
    def residual_labels(self):
        """(sand, quantity) of each residual."""
        return self._impl.residual_labels

    @property
    def ledger(self):
        return self._impl.ledger

    @property
    def runs_executed(self):
        """Cube tests run by this Model (not served from the ledger)."""
        return self._impl.runs_executed

    @property
    def runs_from_ledger(self):
        return self._impl.runs_from_ledger

    def params(self, x):
        """A dict of the free parameters from a vector in the order of names."""
        return dict(zip(self.names, (float(v) for v in x)))

    def evaluate(self, points, progress=None):
        """Several points at once (their runs share the workers): for each, a dict of
        results (per sand), residuals, objective, failed and failure."""
        return self._impl.evaluate([dict(p) for p in points], progress)

    def __call__(self, params, progress=None):
        """The cube tests at `params`: per sand, chord_modulus_mpa, peak_stress_mpa,
        strain_at_peak, poisson_ratio (and tensile_strength_mpa when the problem fits it) per
        seed (NaN for a failed run), with seeds, status and failure."""
        return self.evaluate([params], progress)[0]["results"]

    def residuals(self, params):
        """The calibration's residual vector at `params` (labels: residual_labels)."""
        return self.evaluate([params])[0]["residuals"]

    def objective(self, params):
        """The calibration's objective J = sum of squared residuals."""
        return self.evaluate([params])[0]["objective"]

    def __repr__(self):
        return f"Model({self._impl.problem!r}: {', '.join(self.names)} -> {', '.join(self.sands)} x seeds {self.seeds})"
