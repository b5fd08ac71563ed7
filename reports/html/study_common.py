"""What the study report's pages share (reports/html/study_report.py and the kinds' figure
modules, study_<kind>.py): the quantities, colours, the runs of study.json and a clock."""

import numpy as np  # noqa: F401  (the kind modules take it from here too)

from inputs import field, finite

QUANTITIES = [("modulus", "chord modulus", "MPa"), ("peak_stress", "peak stress", "MPa"), ("strain_at_peak", "strain at peak", "–")]
RUN_KEYS = {"modulus": "modulus_mpa", "peak_stress": "peak_mpa", "strain_at_peak": "strain_at_peak"}
SIM_COLOR, LAB_COLOR = "#0072B2", "#000000"
MODEL_COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00"]


def all_runs(cases):
    """(case label, sand, run) of every run in study.json's `cases`."""
    for c in cases:
        for s in c.get("sands") or []:
            for r in s.get("runs") or []:
                yield c.get("label", "?"), s.get("sand", "?"), r


def clock(seconds):
    s = finite(seconds)
    if s != s:
        return "–"
    m, sec = divmod(int(round(s)), 60)
    return f"{m}m{sec:02d}s" if m < 60 else f"{m // 60}h{m % 60:02d}m"

def case_series(data, path):
    """{sand: {quantity: (x, mean, std)}} from data.cases, in the order of the sweep."""
    series = {}
    for c in field(data, "cases", path, list):
        x = finite(c.get("x"))
        for s in c.get("sands") or []:
            per = series.setdefault(s.get("sand", "?"), {q: ([], [], []) for q, _, _ in QUANTITIES})
            for q, _, _ in QUANTITIES:
                m = s.get(q) or {}
                for target, v in zip(per[q], (x, finite(m.get("mean")), finite(m.get("std")))):
                    target.append(v)
    return series
