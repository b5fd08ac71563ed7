"""A calibration problem solved by scipy's least_squares instead of gradem's own solvers.

gradem.Model maps the problem's free parameters to the cube tests of every sand and seed,
through the problem's ledger (a point run before costs nothing); its residuals are the
calibration's, so the solution is comparable with `gradem calibrate`'s.

    PYTHONPATH=build/python python3 examples/python/external_optimizer.py PROBLEM.toml [MAX_EVALUATIONS]
"""
import sys

import numpy as np
from scipy.optimize import least_squares

import gradem

model = gradem.Model(sys.argv[1])
max_evaluations = int(sys.argv[2]) if len(sys.argv) > 2 else 50
lower, upper = np.array(model.bounds).T
x0 = [model.start[name] for name in model.names]

fit = least_squares(lambda x: model.residuals(model.params(x)), x0, bounds=(lower, upper),
                    x_scale=upper - lower, max_nfev=max_evaluations)
best = model.params(fit.x)
print(f"objective J = {model.objective(best):.3g} after {fit.nfev} evaluations "
      f"({model.runs_executed} cube tests run, {model.runs_from_ledger} from the ledger {model.ledger})")
for p in model.parameters:
    print(f"  {p['name']:24s} {best[p['name']]:10.4g} {p['unit']}")
results = model(best)
for sand, target in model.targets.items():
    for quantity, t in target.items():
        sim = np.nanmean(results[sand][quantity])
        print(f"  {sand:12s} {quantity:18s} simulated {sim:10.4g}  lab {t['mean']:10.4g} ({100 * (sim / t['mean'] - 1):+.1f} %)")
