"""report.html of `gradem study`: the verdict in plain sentences, the kind's own figures, the
study's tables and its runs. Input: study.json (schema gradem-study/1) of the study's output
folder; the `data` shape of each kind is written by calibrate/study/study_kinds.cpp and
calibrate/study/study_analysis.cpp.

Figures per kind (the count is fixed, whatever the data, so the page's check stays simple):
  gradation_effect  2: simulated vs lab difference a − b with 95 % intervals; the seed values per sand
  resolution        1: mean ± seed std against the cube edge, converged edge marked
  fines_truncation  2: error against the particle ratio and against the wall-time ratio
  sensitivity       1: elasticity bars ± standard error, parameter × quantity, per sand
  model_form        3: target errors per model; shape index D simulated vs lab; σc/σt and cost per cube test
"""

import math
import os

import numpy as np
from matplotlib.ticker import MaxNLocator

from figures import message_panel, new_figure, new_grid, sand_color, to_svg
from inputs import InputError, field, finite, read_json, require
from page import Page, fmt, pct

WRITER = "gradem study"
QUANTITIES = [("modulus", "chord modulus", "MPa"), ("peak_stress", "peak stress", "MPa"), ("strain_at_peak", "strain at peak", "–")]
RUN_KEYS = {"modulus": "modulus_mpa", "peak_stress": "peak_mpa", "strain_at_peak": "strain_at_peak"}
SIM_COLOR, LAB_COLOR = "#0072B2", "#000000"
MODEL_COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00"]
TITLES = {"gradation_effect": "does one parameter set reproduce the lab's difference between the sands?",
          "resolution": "how do the results change with the cube edge?",
          "fines_truncation": "what does cutting the fines cost in accuracy?",
          "sensitivity": "which parameter moves which property?",
          "model_form": "which bond model fits the lab best?"}
EXPECTED_FIGURES = {"gradation_effect": 2, "resolution": 1, "fines_truncation": 2, "sensitivity": 1, "model_form": 3}


def build(out_dir):
    path = require(out_dir, "study.json", WRITER)
    study = read_json(path)
    if study.get("schema") != "gradem-study/1":
        raise InputError(f"{path}: schema '{study.get('schema')}': expected gradem-study/1")
    kind = field(study, "kind", path, str)
    if kind not in EXPECTED_FIGURES:
        raise InputError(f"{path}: kind '{kind}': expected one of {', '.join(EXPECTED_FIGURES)}")
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
    page.section("Answer", f"The study's question: {TITLES[kind]}")
    page.notes([str(v).replace(" -> ", " → ") for v in verdict] or ["the study gave no verdict (no successful runs?)"])
    page.cards(run_cards(study, cases) if kind != "model_form" else model_cards(study, data))

    FIGURES[kind](page, data, cases, path)

    for t in tables:
        header, rows = field(t, "header", path, list), field(t, "rows", path, list)
        page.section(str(t.get("title", "table")))
        cells = [[str(c) for c in r] for r in rows]
        long_columns = tuple(k for k in range(len(header)) if any(len(r[k]) > 40 for r in cells if k < len(r)))
        page.table([str(h) for h in header], cells, text_columns=tuple(range(len(header))), wrap_columns=long_columns)
    runs_section(page, cases)
    return page.render()


# ----------------------------------------------------------------------------- runs

def all_runs(cases):
    """(case label, sand, run) of every run in study.json's `cases`."""
    for c in cases:
        for s in c.get("sands") or []:
            for r in s.get("runs") or []:
                yield c.get("label", "?"), s.get("sand", "?"), r


def run_cards(study, cases):
    runs = study.get("runs") or {}
    failed = int(runs.get("failed", 0))
    return [("DEM runs", f"{int(runs.get('executed_now', 0)) + int(runs.get('from_ledger', 0))}",
             f"{runs.get('executed_now', 0)} run now, {runs.get('from_ledger', 0)} from the ledger", ""),
            ("failed runs", f"{failed}", "listed under Runs", "bad" if failed else "good"),
            ("cases", f"{len(cases)}", f"{len(study.get('seeds') or [])} packing seeds per sand", ""),
            ("wall time", clock(study.get("wall_seconds")), f"ledger {os.path.basename(str(study.get('ledger', '?')))}", "")]


def model_cards(study, data):
    models = data.get("models") or []
    runs = study.get("runs") or {}
    failed = int(runs.get("failed", 0))
    return [("models compared", f"{len(models)}", "each from its own calibration's summary.json", ""),
            ("DEM runs", f"{sum(int(m.get('runs') or 0) for m in models)}", "of those calibrations", ""),
            ("wall time", clock(sum(finite(m.get("wall_seconds")) for m in models)), "of those calibrations", ""),
            ("tension tests", f"{int(runs.get('executed_now', 0)) + int(runs.get('from_ledger', 0))}",
             f"for σc/σt: {runs.get('executed_now', 0)} run now, {runs.get('from_ledger', 0)} from the ledger, {failed} failed",
             "bad" if failed else "")]


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


def clock(seconds):
    s = finite(seconds)
    if s != s:
        return "–"
    m, sec = divmod(int(round(s)), 60)
    return f"{m}m{sec:02d}s" if m < 60 else f"{m // 60}h{m % 60:02d}m"


# ----------------------------------------------------------------------------- gradation_effect

def gradation_figures(page, data, cases, path):
    pairs = field(data, "pairs", path, list)
    page.section("The difference between the sands", "One calibrated parameter set, every sand on fresh packing seeds.")
    page.figure(difference_figure(pairs), "Simulated vs lab difference between the sands (a − b) with 95 % intervals",
                "Per property: the difference of the sand means, simulated (blue, Welch 95 % interval over the packing "
                "seeds) and in the lab (black, Welch 95 % interval over the cubes); dotted line: no difference. The "
                "model reproduces the lab when the blue interval excludes 0, has the lab's sign and overlaps the black one.")
    page.figure(seeds_figure(pairs, cases), "Simulated seed values per sand against the lab",
                "Per property and sand: each packing seed's value (dots, one colour per sand) with their mean, and the "
                "lab's mean ± 1 standard deviation (black bar).")


def difference_figure(pairs):
    fig, axes = new_figure(3, width=11.0, height=max(2.6, 1.2 + 0.55 * max(1, len(pairs) // 3)))
    for ax, (q, name, unit) in zip(axes, QUANTITIES):
        rows = [p for p in pairs if p.get("quantity") == q]
        if not rows:
            message_panel(ax, f"no {name} pair")
            continue
        labels = []
        for k, p in enumerate(rows):
            for dy, key, color, tag in ((0.15, "simulated", SIM_COLOR, "simulated"), (-0.15, "lab", LAB_COLOR, "lab")):
                iv = p.get(key) or {}
                est, lo, hi = finite(iv.get("estimate")), finite(iv.get("low")), finite(iv.get("high"))
                y = -k + dy
                if lo == lo and hi == hi:
                    ax.plot([lo, hi], [y, y], color=color, lw=2.2, solid_capstyle="butt")
                ax.plot([est], [y], "o", color=color, ms=6, label=tag if k == 0 else None)
            labels.append(f"{p.get('sand_a')} − {p.get('sand_b')}")
        ax.axvline(0.0, color="#5b6475", ls=":", lw=1)
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.set_yticks([-k for k in range(len(rows))], labels if ax is axes[0] else [""] * len(rows))
        ax.set_ylim(-len(rows) + 0.5, 0.5)
        ax.set_xlabel(f"{name} a − b [{unit}]")
        ax.set_title(name)
        ax.grid(axis="y", visible=False)
    axes[0].legend(loc="best")
    return to_svg(fig)


def seeds_figure(pairs, cases):
    """Per quantity, per sand: the seed values from `cases` and the lab's mean ± std from `pairs`."""
    fig, axes = new_figure(3, width=11.0, height=3.6)
    sands = [s.get("sand") for s in (cases[0].get("sands") if cases else [])]
    lab = {}
    for p in pairs:
        lab.setdefault((p.get("quantity"), p.get("sand_a")), p.get("lab_a") or {})
        lab.setdefault((p.get("quantity"), p.get("sand_b")), p.get("lab_b") or {})
    for ax, (q, name, unit) in zip(axes, QUANTITIES):
        if not sands:
            message_panel(ax, "no runs")
            continue
        for i, sand in enumerate(sands):
            values = [finite(r.get(RUN_KEYS[q])) for c, s, r in all_runs(cases[:1]) if s == sand and r.get("status") == "ok"]
            values = [v for v in values if v == v]
            x = np.full(len(values), float(i)) + np.linspace(-0.12, 0.12, max(1, len(values)))[:len(values)]
            ax.plot(x, values, "o", color=sand_color(i), ms=5, alpha=0.85)
            if values:
                ax.plot([i - 0.2, i + 0.2], [np.mean(values)] * 2, color=sand_color(i), lw=2)
            m = lab.get((q, sand)) or {}
            mean, std = finite(m.get("mean")), finite(m.get("std"))
            if mean == mean:
                ax.errorbar([i + 0.32], [mean], yerr=[[std if std == std else 0.0]], fmt="s", color=LAB_COLOR, ms=5, capsize=4,
                            label="lab mean ± std" if i == 0 else None)
        ax.set_xticks(range(len(sands)), sands)
        ax.set_xlim(-0.6, len(sands) - 0.3)
        ax.set_ylabel(f"{name} [{unit}]")
        ax.set_title(name)
    axes[0].legend(loc="best")
    return to_svg(fig)


# ----------------------------------------------------------------------------- resolution / fines_truncation

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


def resolution_figures(page, data, cases, path):
    series = case_series(data, path)
    conv = {(c.get("sand"), c.get("quantity")): c for c in data.get("convergence") or []}
    page.section("Convergence with the cube edge", "The calibrated parameters on cubes of each edge, every sand, the same seeds.")
    fig, grid = new_grid(max(1, len(series)), 3, width=11.0, height=0.6 + 3.0 * max(1, len(series)))
    if not series:
        for ax in grid[0]:
            message_panel(ax, "no cases")
    for i, (sand, per) in enumerate(series.items()):
        for ax, (q, name, unit) in zip(grid[i], QUANTITIES):
            x, mean, std = (np.array(v) for v in per[q])
            ax.errorbar(x, mean, yerr=np.nan_to_num(std), fmt="o-", color=sand_color(i), ms=4, capsize=3, label=f"{sand}: mean ± seed std")
            c = conv.get((sand, q)) or {}
            if c.get("converged") and c.get("from_x") is not None:
                ax.axvline(finite(c["from_x"]), color="#5b6475", ls="--", lw=1.2, label="converged from here")
            ax.set_xlabel("cube edge [mm]")
            ax.set_ylabel(f"{name} [{unit}]")
            ax.set_title(f"{sand}: {name}")
        grid[i][0].legend(loc="best")
    page.figure(to_svg(fig), "Macro properties against the cube edge",
                "Mean ± seed standard deviation of each property (columns) per sand (rows) against the cube edge; dashed line: the "
                "edge from which every later step changes the mean by less than the seed spread (converged); no line: "
                "not converged within the sweep.")


def truncation_figures(page, data, cases, path):
    rows = field(data, "truncation", path, list)
    page.section("Cost against error of cutting the fines",
                 "Each cut's error relative to the finest cut (the smallest kept grain of the sweep), against what it costs.")
    for cost_key, cost_name in (("particles_ratio", "particles"), ("wall_ratio", "wall time")):
        fig, axes = new_figure(3, width=11.0, height=3.6)
        for ax, (q, name, unit) in zip(axes, QUANTITIES):
            drawn = 0
            for i, sand in enumerate(dict.fromkeys(r.get("sand") for r in rows)):
                pts = [(finite(r.get(cost_key)), 100 * finite((r.get("relative_error") or {}).get(q)), bool(r.get("within_noise")),
                        finite(r.get("x"))) for r in rows if r.get("sand") == sand]
                pts = [p for p in pts if p[0] == p[0] and p[1] == p[1]]
                for cost, err, ok, x in pts:
                    ax.plot([cost], [err], "o", ms=7, color=sand_color(i), mfc=sand_color(i) if ok else "white", mew=1.6)
                    ax.annotate(f"{fmt(x, 3)} mm", (cost, err), textcoords="offset points", xytext=(5, 4), fontsize=8)
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=sand_color(i), lw=1, label=sand)
                drawn += len(pts)
            if not drawn:
                message_panel(ax, f"no {cost_name} ratio recorded\n(runs without wall time, e.g. from the ledger\nor the closed-form stand-in)")
                continue
            ax.axhline(0.0, color="#5b6475", ls=":", lw=1)
            ax.set_xlabel(f"{cost_name} relative to the finest cut [×]")
            ax.set_ylabel(f"{name} error [%]")
            ax.set_title(name)
        if any(ax.get_legend_handles_labels()[0] for ax in axes):
            next(ax for ax in axes if ax.get_legend_handles_labels()[0]).legend(loc="best")
        page.figure(to_svg(fig), f"Error against {cost_name} per cut",
                    f"Relative error of each property (seed mean of the cut / seed mean of the finest cut − 1) against the "
                    f"{cost_name} of the cut relative to the finest; label: smallest kept grain; filled: all three properties "
                    f"within the 95 % seed noise of the finest, open: not.")


# ----------------------------------------------------------------------------- sensitivity

def sensitivity_figures(page, data, cases, path):
    rows = field(data, "elasticities", path, list)
    sands = list(dict.fromkeys(r.get("sand") for r in rows))
    params = list(dict.fromkeys(r.get("parameter") for r in rows))
    page.section("Elasticities", f"One parameter at a time around the calibrated point (step {data.get('step', '?')}), "
                 "each seed paired with itself at the calibrated point.")
    fig, axes = new_figure(max(1, len(sands)), width=11.0, height=3.2 + 0.25 * len(params))
    colors = [c for c, _ in zip(MODEL_COLORS, QUANTITIES)]
    for ax, sand in zip(axes, sands or [None]):
        if sand is None:
            message_panel(ax, "no elasticities")
            continue
        y = np.arange(len(params), dtype=float)
        h = 0.8 / len(QUANTITIES)
        for k, (q, name, _) in enumerate(QUANTITIES):
            e, se = [], []
            for p in params:
                r = next((r for r in rows if r.get("sand") == sand and r.get("parameter") == p), {})
                v = r.get(q) or {}
                e.append(finite(v.get("elasticity")))
                se.append(finite(v.get("std_error")))
            ax.barh(y - 0.4 + h * (k + 0.5), np.nan_to_num(e), height=h * 0.9, color=colors[k],
                    xerr=np.nan_to_num(se), error_kw={"ecolor": "#1d2330", "capsize": 3, "lw": 1}, label=name)
        ax.axvline(0.0, color="#5b6475", lw=1)
        ax.set_yticks(y, params)
        ax.invert_yaxis()
        ax.set_xlabel("elasticity d ln(property) / d ln(parameter) [–]")
        ax.set_title(sand)
        ax.grid(axis="y", visible=False)
    axes[0].legend(loc="best")
    page.figure(to_svg(fig), "Elasticity of each property to each parameter, per sand",
                "Bars: mean elasticity over the packing seeds (per unit of the parameter for linear-scaled parameters); "
                "whiskers: ± 1 standard error over the seeds. A bar near 0 means the property does not see the parameter.")


# ----------------------------------------------------------------------------- model_form

def model_form_figures(page, data, cases, path):
    models = field(data, "models", path, list)
    names = [f"{m.get('model')} ({os.path.basename(os.path.dirname(str(m.get('summary', ''))))})" for m in models]
    tolerances = data.get("target_tolerances") or {}
    sands = list(dict.fromkeys(s.get("sand") for m in models for s in m.get("sands") or []))
    page.section("The models side by side", "Each model's own calibration against the same lab targets.")
    fig, axes = new_figure(max(1, len(sands)), width=11.0, height=3.8)
    w = 0.8 / max(1, len(models))
    for ax, sand in zip(axes, sands or [None]):
        if sand is None:
            message_panel(ax, "no models")
            continue
        for k, (m, label) in enumerate(zip(models, names)):
            s = next((s for s in m.get("sands") or [] if s.get("sand") == sand), {})
            err = [100 * finite(s.get(f"{q.split('_')[0]}_error")) for q, _, _ in QUANTITIES]
            ax.bar(np.arange(3) - 0.4 + w * (k + 0.5), np.nan_to_num(err), width=w * 0.9, color=MODEL_COLORS[k % 5], label=label)
        for q, (key, _, _) in enumerate(QUANTITIES):  # each target's own tolerance (calibrate/target_tolerance.hpp)
            tol = 100 * finite(tolerances.get(key, 0.05))
            ax.fill_between([q - 0.45, q + 0.45], -tol, tol, color="#009E73", alpha=0.12, lw=0)
        ax.axhline(0, color="#5b6475", lw=1)
        ax.set_xticks(range(3), [n for _, n, _ in QUANTITIES])
        ax.set_ylabel("relative error [%]")
        ax.set_title(sand)
    axes[0].legend(loc="best")
    page.figure(to_svg(fig), "Target errors per model and sand",
                "Relative error (simulated / lab − 1) of each target at each model's calibrated parameters; green band: the "
                "target's tolerance (" + ", ".join(f"{n} ± {fmt(100 * finite(tolerances.get(k, 0.05)), 3)} %"
                                                   for k, n, _ in QUANTITIES) + ").")
    fig, (ax, bars) = new_figure(2, width=11.0, height=4.0)
    lo, hi = math.inf, -math.inf
    for k, (m, label) in enumerate(zip(models, names)):
        for i, s in enumerate(m.get("sands") or []):
            d_lab, d_sim = finite(s.get("shape_index_lab")), finite(s.get("shape_index_sim"))
            if d_lab == d_lab and d_sim == d_sim:
                ax.plot([d_lab], [d_sim], "os^Dv"[i % 5], color=MODEL_COLORS[k % 5], ms=8, mfc="none", mew=1.8,
                        label=f"{label}, {s.get('sand')}")
                lo, hi = min(lo, d_lab, d_sim), max(hi, d_lab, d_sim)
    if lo < hi:
        pad = 0.1 * (hi - lo)
        ax.plot([lo - pad, hi + pad], [lo - pad, hi + pad], color="#5b6475", ls=":", lw=1, label="simulated = lab")
        ax.legend(loc="best", fontsize=8)
    elif lo == math.inf:
        message_panel(ax, "no shape index recorded")
    ax.set_xlabel("lab shape index D [–]")
    ax.set_ylabel("simulated shape index D [–]")
    ax.set_title("D simulated vs lab")
    for k, (m, label) in enumerate(zip(models, names)):
        ratio = [100 * (finite(s.get("shape_index_sim")) / finite(s.get("shape_index_lab")) - 1) for s in
                 (next((s for s in m.get("sands") or [] if s.get("sand") == sand), {}) for sand in sands)]
        bars.bar(np.arange(len(sands)) - 0.4 + w * (k + 0.5), np.nan_to_num(ratio), width=w * 0.9, color=MODEL_COLORS[k % 5], label=label)
    bars.axhline(0, color="#5b6475", lw=1)
    bars.set_xticks(range(len(sands)), sands)
    bars.set_ylabel("D simulated / D lab − 1 [%]")
    bars.set_title("Error of D per sand")
    page.figure(to_svg(fig), "Shape of the stress–strain curve: simulated vs lab",
                "The shape index D = E·ε_peak / σ_peak (chord modulus over the secant modulus at the peak; 1 = linear up to the "
                "peak) of the simulated and the lab means, per model (colour) and sand (marker); on the dotted line the "
                "model reproduces the lab's curve shape. Right: the relative error of D per sand and model.")
    ratio_and_cost_figure(page, models, names, sands)


def ratio_and_cost_figure(page, models, names, sands):
    """σc/σt per model and sand (the direct-tension test at the calibrated parameters) against
    mortar's range, and the cost per cube test (particle-steps per second) of each calibration."""
    fig, (ratio_ax, cost_ax) = new_figure(2, width=11.0, height=4.0)
    w = 0.8 / max(1, len(models))
    shown = False
    for k, (m, label) in enumerate(zip(models, names)):
        rows = [next((s for s in m.get("sands") or [] if s.get("sand") == sand), {}) for sand in sands]
        x = np.arange(len(sands)) - 0.4 + w * (k + 0.5)
        ratio = [finite(r.get("compressive_to_tensile_ratio")) for r in rows]
        cost = [finite((r.get("cost") or {}).get("particle_steps_per_second")) for r in rows]
        ratio_ax.bar(x, np.nan_to_num(ratio), width=w * 0.9, color=MODEL_COLORS[k % 5], label=label)
        cost_ax.bar(x, np.nan_to_num(cost), width=w * 0.9, color=MODEL_COLORS[k % 5], label=label)
        shown = shown or any(v == v for v in ratio + cost)
    ratio_ax.axhspan(8, 12, color="#5b6475", alpha=0.12, lw=0, label="mortar: about 8–12")
    for ax, title, unit in ((ratio_ax, "σc / σt", "σc / σt [–]"), (cost_ax, "Cost per cube test", "particle-steps per second [1/s]")):
        ax.set_xticks(range(len(sands)), sands)
        ax.set_ylabel(unit)
        ax.set_title(title)
    ratio_ax.legend(loc="best", fontsize=8)
    if not shown:
        message_panel(cost_ax, "no tension runs or ledger costs recorded")
    page.figure(to_svg(fig), "Compressive over tensile strength, and cost per cube test",
                "Left: σc/σt per model (colour) and sand, the calibrated mean compressive peak over the mean tensile strength "
                "of the direct-tension test of the same packings at the calibrated parameters; grey band: mortar's usual 8–12. "
                "Right: particles × time steps per wall second of the calibration's compression runs (from its ledger; "
                "wall time with the calibration's other runs in flight, so machine load shows).")


FIGURES = {"gradation_effect": gradation_figures, "resolution": resolution_figures, "fines_truncation": truncation_figures,
           "sensitivity": sensitivity_figures, "model_form": model_form_figures}
