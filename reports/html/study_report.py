"""report.html of `gradem study`: the verdict in plain sentences, the kind's own figures, the
study's tables and its runs. Input: study.json (schema gradem-study/1) of the study's output
folder. The figures of kind K are made by the module study_K.py (one per kind, loaded by the
kind's name): its TITLE (the study's question), add_figures(page, data, cases, path) and,
optionally, cards(study, data) in place of the run cards; the `data` it reads is written by
calibrate/study/kinds/K.cpp. A module draws a fixed number of figures, whatever the data, so
the page's check stays simple.
"""

import importlib
import os

from inputs import InputError, field, finite, read_json, require
from page import Page, fmt
from study_common import all_runs, clock, np

WRITER = "gradem study"


def kind_module(kind, path):
    """The figures module of `kind` (study_<kind>.py beside this file)."""
    if not kind.isidentifier() or not os.path.exists(os.path.join(os.path.dirname(os.path.abspath(__file__)), f"study_{kind}.py")):
        raise InputError(f"{path}: kind '{kind}': no figures for it (reports/html/study_{kind}.py)")
    return importlib.import_module(f"study_{kind}")


def build(out_dir):
    path = require(out_dir, "study.json", WRITER)
    study = read_json(path)
    if study.get("schema") != "gradem-study/1":
        raise InputError(f"{path}: schema '{study.get('schema')}': expected gradem-study/1")
    kind = field(study, "kind", path, str)
    module = kind_module(kind, path)
    data = field(study, "data", path, dict)
    verdict = field(study, "verdict", path, list)
    tables = field(study, "tables", path, list)
    cases = field(study, "cases", path, list)

    page = Page(f"gradem study report: {kind} ({os.path.basename(str(study.get('study_file', '?')))})",
                f"calibration(s) {', '.join(study.get('calibrations') or [])}; packing seeds {study.get('seeds')}; "
                f"code {study.get('code_version', '?')}; folder {os.path.abspath(out_dir)}")
    if study.get("representative_lab_data"):
        page.banner("the lab results the calibration was fitted to are representative, not measurements: the answer below "
                    "says what the model does with them, not what the real sands do.")
    page.section("Answer", f"The study's question: {module.TITLE}")
    page.notes([str(v).replace(" -> ", " → ") for v in verdict] or ["the study gave no verdict (no successful runs?)"])
    page.cards(module.cards(study, data) if hasattr(module, "cards") else run_cards(study, cases))

    module.add_figures(page, data, cases, path)

    for t in tables:
        header, rows = field(t, "header", path, list), field(t, "rows", path, list)
        page.section(str(t.get("title", "table")))
        cells = [[str(c) for c in r] for r in rows]
        long_columns = tuple(k for k in range(len(header)) if any(len(r[k]) > 40 for r in cells if k < len(r)))
        page.table([str(h) for h in header], cells, text_columns=tuple(range(len(header))), wrap_columns=long_columns)
    runs_section(page, cases)
    return page.render()


# ----------------------------------------------------------------------------- runs

def run_cards(study, cases):
    runs = study.get("runs") or {}
    failed = int(runs.get("failed", 0))
    return [("DEM runs", f"{int(runs.get('executed_now', 0)) + int(runs.get('from_ledger', 0))}",
             f"{runs.get('executed_now', 0)} run now, {runs.get('from_ledger', 0)} from the ledger", ""),
            ("failed runs", f"{failed}", "listed under Runs", "bad" if failed else "good"),
            ("cases", f"{len(cases)}", f"{len(study.get('seeds') or [])} packing seeds per sand", ""),
            ("wall time", clock(study.get("wall_seconds")), f"ledger {os.path.basename(str(study.get('ledger', '?')))}", "")]


def runs_section(page, cases):
    runs = list(all_runs(cases))
    if not runs:
        page.section("Runs")
        page.paragraph("This study ran no cube test: it compares finished calibrations (their runs are in their own reports).")
        return
    page.section("Runs", f"{len(runs)} cube tests in study.json (every case × sand × seed); each row of runs.csv is one of them.")
    failed = [(c, s, r) for c, s, r in runs if r.get("status") != "ok"]
    if failed:
        page.table(["case", "sand", "seed", "status", "reason"],
                   [[c, s, str(r.get("seed")), str(r.get("status")), str(r.get("reason") or "–")] for c, s, r in failed],
                   caption="Runs that failed, with the reason the runner gave; their cases use the remaining seeds.",
                   text_columns=(0, 1, 3, 4), bad_rows=range(len(failed)))
    else:
        page.paragraph("No run failed.")
    groups = {}
    for c, s, r in runs:
        g = groups.setdefault((c, s), {"n": 0, "ok": 0, "particles": [], "wall": []})
        g["n"] += 1
        g["ok"] += r.get("status") == "ok"
        g["particles"].append(finite(r.get("particles")))
        g["wall"].append(finite(r.get("wall_seconds")))
    rows = [[c, s, str(g["n"]), str(g["ok"]), fmt(np.nanmean(g["particles"]), 6), fmt(np.nansum(g["wall"]), 3)]
            for (c, s), g in groups.items()]
    page.table(["case", "sand", "runs", "ok", "particles (mean)", "wall s (sum)"], rows,
               caption="Runs per case and sand; wall time is that of the cube tests (0 for runs read from the ledger "
               "or made by the closed-form stand-in).", text_columns=(0, 1))
