"""report.html of `gradem calibrate`: simulated against lab stress–strain curves per sand, the
convergence of the objective and the parameters, the calibrated parameters with their standard
errors within their bounds, the error of every target, and the curves' shape index D beside the
lab's. Inputs: summary.json, convergence.csv and curves.csv of the calibration's output folder."""

import math
import os

import numpy as np

from figures import message_panel, new_figure, sand_color, to_svg
from inputs import InputError, field, finite, number, read_csv, read_json, require
from page import Page, fmt, pct

WRITER = "gradem calibrate"
QUANTITIES = [("modulus", "chord modulus", "MPa"), ("peak_stress", "peak stress", "MPa"), ("strain_at_peak", "strain at peak", "-")]
TENSION = "tensile_strength"  # the direct-tension target's quantity, when the calibration fits it
LABEL_COLORS = {"start": "#000000", "rescaled": "#0072B2", "shape": "#56B4E9", "confirm": "#009E73", "search": "#E69F00",
                "lm": "#CC79A7", "uncertainty": "#999999", "prediction": "#D55E00"}


def build(out_dir):
    summary_path = require(out_dir, "summary.json", WRITER)
    summary = read_json(summary_path)
    sands = field(summary, "sands", summary_path, list)
    stages = field(summary, "stages", summary_path, list)
    for k, st in enumerate(stages):
        for key in ("label", "parameters", "targets"):
            field(st, key, f"{summary_path} (stages[{k}])")
    history = read_convergence(require(out_dir, "convergence.csv", WRITER))
    curves = read_curves(require(out_dir, "curves.csv", WRITER))

    runs = summary.get("runs") or {}
    page = Page(f"gradem calibration report: {os.path.basename(str(summary.get('config', '?')))}",
                f"mode {summary.get('mode')}, solver {summary.get('solver')}, model {summary.get('model')}; sands "
                f"{', '.join(sands)}; lab targets {summary.get('lab_results')}; folder {os.path.abspath(out_dir)}")
    if summary.get("representative_lab_data"):
        page.banner(summary.get("lab_note") or "the lab results these targets come from are representative, not measurements.")
    page.cards(headline(summary, stages, runs))

    page.section("Simulated and lab curves", "The virtual cube tests at the calibrated parameters against the lab.")
    page.figure(curves_figure(sands, stages, curves), "Simulated vs lab stress–strain curves per sand",
                "Solid: the simulated stress vs gauge strain of each packing seed at the calibrated parameters; dashed black: "
                "the Popovics (1973) curve through the lab means; black cross: the lab's mean peak stress and strain at peak "
                "± 1 standard deviation.")
    errors_caption = ("Relative error (simulated seed mean / lab mean − 1) of each target; green band behind each bar: met "
                      f"(within {tolerance_text(summary)}); grey whiskers: the lab's own scatter (± 1 std / mean)")
    if has_role(stages, "validation"):
        page.figure(errors_figure(sands, stages, "validation"), "Target errors on the validation specimens, which the fit never saw",
                    errors_caption + f"; specimens: {specimens_text(stages[0].get('validation'))}.")
    scale_up = stages[0].get("scale_up") or {} if stages else {}
    page.figure(errors_figure(sands, stages), "Target errors per sand" + (" on the scale-up specimens" if scale_up.get("done") else ""),
                errors_caption + "; hatched: predicted (not fitted) sands."
                + (f" The scales were set on {specimens_text(scale_up)}: the fit's point run there, its moduli × "
                   f"{fmt(scale_up.get('alpha'), 4)} and strengths × {fmt(scale_up.get('beta'), 4)}." if scale_up.get("done") else ""))
    shape_rows = shape_index_rows(stages)
    if shape_rows:
        page.figure(shape_index_figure(sands, shape_rows), "Shape index D = E·ε_peak/σ_peak per sand, simulated and lab",
                    "D is the curve's shape: 1 for a line straight to its peak, more the more it bends over before it. "
                    "Scaling every modulus and every strength (the calibration's scales) leaves it unchanged, so only the "
                    "bond law's shape parameters move it, and a strain at peak that misses with D off the lab's is the "
                    "model's shape, not the fit. Bars: the simulated seed means per specimen set; black line: the lab's D "
                    "from its means. " + shape_index_text(sands, shape_rows))
    tension = summary.get("tension_target") or {}
    if tension.get("source") not in (None, "none"):
        page.figure(ratio_figure(sands, stages, tension), "Compressive over tensile strength per sand",
                    "Bars: the simulated σc/σt (seed means of the cube and direct-tension tests at the calibrated parameters); "
                    + ("green band: the ASSUMED range " + "–".join(fmt(v, 3) for v in tension.get("ratio_band") or [])
                       + " (basis: " + str(tension.get("basis", "?")) + ")." if tension.get("assumed")
                       else "black marks: the lab's σc/σt (its tensile tests converted to direct tension)."))
    page.table(*targets_table(stages), caption="Per sand and target: lab mean ± sample std (n cubes), simulated mean ± seed "
               "spread (n seeds), relative error, z = (sim − lab)/√(s_lab² + s_sim²/n). An assumed tensile target is σc,lab "
               "over the assumed ratio.", text_columns=(0, 1, 2, 3),
               bad_rows=[i for i, t in enumerate(all_targets(stages)) if t.get("met") is False])
    page.section("Calibrated parameters")
    page.figure(parameters_figure(stages), "Calibrated parameters with ± 1 standard error",
                "Each parameter's position within its bounds (log or linear scale as calibrated); bar: one-sigma interval "
                "from the Jacobian at the optimum; open diamond: start value.")
    page.table(*parameters_table(stages), caption="Standard errors are relative for log-scaled parameters, absolute for "
               "linear ones.", text_columns=(0, 1, 7))
    for st in stages:
        page.notes(stage_notes(st, len(stages) > 1))
    page.section("Convergence")
    page.figure(convergence_figure(history), "Calibration convergence",
                "Left: the objective Σr² of every evaluation (colour: what the solver was doing; x: failed) and the best so far. "
                "Right: each free parameter relative to its calibrated value along the way.")
    page.table(["quantity", "value"], run_rows(summary, runs), caption="Budget, runs and provenance.", text_columns=(0, 1))
    return page.render()


# ----------------------------------------------------------------------------- inputs

def read_convergence(path):
    rows, _ = read_csv(path, ["evaluation", "label", "runs_used", "objective", "failed"])
    fixed = {"evaluation", "label", "runs_used", "wall_seconds", "objective", "failed"}
    names = list(rows[0].keys()) if rows else []
    parameters = [c for c in names if c not in fixed and c != "_line" and " " not in c]
    outputs = [c for c in names if " " in c]
    history = []
    for r in rows:
        history.append({"evaluation": number(r, "evaluation", path), "label": r["label"], "runs_used": number(r, "runs_used", path),
                        "objective": number(r, "objective", path), "failed": r["failed"].strip() == "1",
                        "parameters": {p: number(r, p, path) for p in parameters},
                        "has_output": tuple(o for o in outputs if (r.get(o) or "").strip() != "")})
    return history


def read_curves(path):
    """{(stage, sand): {"simulated": {seed: (strain, stress)}, "lab": (strain, stress)}}."""
    rows, _ = read_csv(path, ["stage", "sand", "source", "seed", "strain", "stress_mpa"])
    curves = {}
    for r in rows:
        entry = curves.setdefault((r["stage"], r["sand"]), {"simulated": {}, "lab": ([], [])})
        e, s = number(r, "strain", path), number(r, "stress_mpa", path)
        if r["source"] == "simulated":
            strain, stress = entry["simulated"].setdefault(r["seed"], ([], []))
        elif r["source"] == "lab_mean_popovics":
            strain, stress = entry["lab"]
        else:
            raise InputError(f"{path}:{r['_line']}: source '{r['source']}': expected simulated or lab_mean_popovics")
        strain.append(e)
        stress.append(s)
    return curves


def all_targets(stages):
    return [t for st in stages for t in st.get("targets") or []]


def result_role(st, role):
    """Is a target row of `role` the stage's result on its own specimens? The scale-up rows when the
    scales were set on the scale-up specimens, else the fit's (fitted and predicted sands)."""
    if (st.get("scale_up") or {}).get("done"):
        return role == "scale-up"
    return role in ("fitted", "predicted")


def target(st, sand, quantity, role=None):
    """The stage's row for `sand` and `quantity`: of `role`, or (None) the result's."""
    return next((t for t in st.get("targets") or [] if t.get("sand") == sand and t.get("quantity") == quantity
                 and (t.get("role") == role if role else result_role(st, t.get("role")))), None)


def has_role(stages, role):
    return any(t.get("role") == role for t in all_targets(stages))


# ----------------------------------------------------------------------------- headline

def tolerance_text(summary):
    """The summary's tolerances per quantity, e.g. "E ± 5 %, peak ± 5 %, strain at peak ± 10 %" (and the tension rule)."""
    t = summary.get("target_tolerances") or {"modulus": 0.05, "peak_stress": 0.05, "strain_at_peak": 0.05}
    text = (f"E ± {fmt(100 * finite(t.get('modulus')), 3)} %, peak ± {fmt(100 * finite(t.get('peak_stress')), 3)} %, "
            f"strain at peak ± {fmt(100 * finite(t.get('strain_at_peak')), 3)} %")
    tension = summary.get("tension_target") or {}
    if tension.get("assumed"):
        text += ", σc/σt within " + "–".join(fmt(v, 3) for v in tension.get("ratio_band") or []) + " (assumed)"
    elif tension.get("source") == "lab":
        text += f", σt ± {fmt(100 * finite(tension.get('tolerance')), 3)} %"
    return text


def headline(summary, stages, runs):
    targets = all_targets(stages)
    met = sum(1 for t in targets if t.get("met"))
    items = [("objective Σr²", " / ".join(fmt(st.get("objective"), 3) for st in stages), "at the optimum", ""),
             ("targets met", f"{met} of {len(targets)}", tolerance_text(summary), "good" if met == len(targets) else "bad"),
             *validation_cards(stages),
             ("DEM runs", f"{runs.get('total', summary.get('dem_test_runs', '?'))}",
              f"budget {runs.get('budget', '?')}, {runs.get('from_ledger', 0)} from the ledger, {runs.get('failed', 0)} failed", ""),
             ("wall time", clock(summary.get("wall_seconds")), f"{summary.get('evaluations', '?')} evaluations", "")]
    for st in stages:
        for p in st.get("parameters") or []:
            if p.get("free"):
                items.append((f"{p['name']}" + (f" ({st['label']})" if len(stages) > 1 else ""),
                              f"{fmt(p.get('value'), 4)} {unit_text(p.get('unit'))}", f"± {se_text(p)}", ""))
    return items


def validation_cards(stages):
    """One card per validated stage: does its result hold on the specimens the fit never saw?"""
    cards = []
    for st in stages:
        v = st.get("validation")
        if v:
            holds = v.get("holds") is True
            cards.append(("validation" + (f" ({st['label']})" if len(stages) > 1 else ""), "holds" if holds else "MISSES",
                          specimens_text(v) + ", never fitted", "good" if holds else "bad"))
    return cards


def clock(seconds):
    s = finite(seconds)
    if not math.isfinite(s):
        return "?"
    s = int(round(s))
    return f"{s // 3600}h{(s // 60) % 60:02d}m" if s >= 3600 else f"{s // 60}m{s % 60:02d}s"


def unit_text(unit):
    return "" if unit in (None, "-", "") else unit


def se_text(p):
    se = p.get("std_error") or {}
    if math.isfinite(finite(se.get("relative"))):
        return pct(se["relative"], signed=False)
    if math.isfinite(finite(se.get("absolute"))):
        return f"{fmt(se['absolute'], 3)} {unit_text(p.get('unit'))}".strip()
    return "not computed"


# ----------------------------------------------------------------------------- figures

def curves_figure(sands, stages, curves):
    pairs = [(st, s) for st in stages for s in sands if (st["label"], s) in curves]
    fig, axes = new_figure(max(1, len(pairs)), width=10.0, height=4.3, sharey=True)
    if not pairs:
        message_panel(axes[0], "curves.csv holds no curves (no evaluation succeeded)")
        axes[0].set_title("Simulated vs lab curves")
        return to_svg(fig)
    for ax, (st, sand) in zip(axes, pairs):
        k = sands.index(sand)
        entry = curves[(st["label"], sand)]
        for n, (seed, (e, s)) in enumerate(sorted(entry["simulated"].items())):
            ax.plot(np.array(e) * 1e3, s, color=sand_color(k), lw=1.6, alpha=0.55 + 0.45 * (n == 0),
                    label="simulated, seed " + seed)
        e, s = entry["lab"]
        if e:
            ax.plot(np.array(e) * 1e3, s, "--", color="black", lw=1.8, label="lab mean (Popovics)")
        peak, strain = target(st, sand, "peak_stress"), target(st, sand, "strain_at_peak")
        if peak and strain:
            xerr, yerr = finite(strain.get("lab_std")) * 1e3, finite(peak.get("lab_std"))  # NaN for a single cube
            ax.errorbar([finite(strain.get("lab_mean")) * 1e3], [finite(peak.get("lab_mean"))],
                        xerr=[xerr] if math.isfinite(xerr) else None, yerr=[yerr] if math.isfinite(yerr) else None, fmt="+",
                        color="black", capsize=4, lw=1.3, label="lab peak ± 1 std")
        role = (peak or {}).get("role", "fitted")
        stage_text = f" — {st['label']}" if len(stages) > 1 and st["label"] != sand else ""
        ax.set_title(f"{sand}" + (" (predicted)" if role == "predicted" else "") + stage_text)
        ax.set_xlabel("axial strain ε [‰] (gauge)")
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.legend(loc="lower right", fontsize=8)
    axes[0].set_ylabel("axial stress σ [MPa]")
    return to_svg(fig)


def specimens_text(spec):
    spec = spec or {}
    return f"{fmt(spec.get('edge_mm'), 3)} mm cubes, packing seeds {', '.join(str(s) for s in spec.get('seeds') or [])}"


def errors_figure(sands, stages, role=None):
    """One bar per sand and target: the result's rows, or those of `role` (e.g. validation)."""
    fig, (ax,) = new_figure(1, width=10.0, height=3.9)
    groups = [(st, s) for st in stages for s in sands if target(st, s, "modulus", role)]
    if not groups:
        message_panel(ax, "no targets in summary.json")
        ax.set_title("Target errors")
        return to_svg(fig)
    ax.axhline(0, color="#555", lw=0.8)
    width = 0.26
    shown = set()
    for g, (st, sand) in enumerate(groups):
        k = sands.index(sand)
        for q, (quantity, name, _) in enumerate(QUANTITIES):
            t = target(st, sand, quantity, role)
            if not t:
                continue
            x = g + (q - 1) * width
            err = finite(t.get("rel_error")) * 100
            tol = 100 * finite(t.get("tolerance", 0.05))  # per quantity (calibrate/target_tolerance.hpp)
            ax.fill_between([x - width / 2, x + width / 2], -tol, tol, color="#d8efd9", lw=0,
                            label="met (± the target's tolerance)" if "met" not in shown else None)
            shown.add("met")
            predicted = t.get("role") == "predicted"
            ax.bar([x], [err if math.isfinite(err) else 0], width * 0.9, color=sand_color(k), alpha=0.4 + 0.2 * q,
                   hatch="//" if predicted else None, edgecolor="black" if predicted else sand_color(k))
            ax.text(x, err + (1.0 if err >= 0 else -1.0), pct(t.get("rel_error"), 1).replace(" %", "%"), ha="center",
                    va="bottom" if err >= 0 else "top", fontsize=8)
            lab_cv = finite(t.get("lab_std")) / finite(t.get("lab_mean")) * 100 if finite(t.get("lab_mean")) else math.nan
            if math.isfinite(lab_cv):
                ax.errorbar([x], [0], yerr=[lab_cv], fmt="none", ecolor="#777", capsize=3, lw=1,
                            label="lab scatter (± std/mean)" if "lab" not in shown else None)
                shown.add("lab")
    ticks, labels = [], []
    for g, (st, sand) in enumerate(groups):
        for q, (_, name, _) in enumerate(QUANTITIES):
            ticks.append(g + (q - 1) * width)
            labels.append({"chord modulus": "E", "peak stress": "σp", "strain at peak": "εp"}[name])
    ax.set_xticks(ticks)
    ax.set_xticklabels(labels)
    for g, (st, sand) in enumerate(groups):
        ax.text(g, -0.13, sand + (f" ({st['label']})" if len(stages) > 1 and st["label"] != sand else ""),
                transform=ax.get_xaxis_transform(),
                ha="center", va="top", fontsize=10, fontweight="bold", color=sand_color(sands.index(sand)))
    ax.set_ylabel("relative error [%]")
    ax.set_title(("Validation specimens" if role == "validation" else "Simulated vs lab")
                 + ": error of each target (E chord modulus, σp peak stress, εp strain at peak)")
    ax.grid(axis="x", visible=False)
    ax.margins(y=0.15)
    ax.legend(loc="lower left", fontsize=8.5)
    return to_svg(fig)


def ratio_figure(sands, stages, tension):
    """σc/σt per sand and stage: the simulated bar against the assumed band or the lab's ratio."""
    fig, (ax,) = new_figure(1, width=10.0, height=3.6)
    groups = [(st, s, target(st, s, TENSION), target(st, s, "peak_stress")) for st in stages for s in sands]
    groups = [g for g in groups if g[2]]
    if not groups:
        message_panel(ax, "no tension targets in summary.json")
        ax.set_title("σc/σt")
        return to_svg(fig)
    band = tension.get("ratio_band") or []
    if tension.get("assumed") and len(band) == 2:
        ax.axhspan(finite(band[0]), finite(band[1]), color="#d8efd9", lw=0, label="assumed band (met)")
        ax.axhline(finite(tension.get("compressive_to_tensile_ratio")), color="#2b8a3e", lw=1, ls="--", label="assumed ratio")
    for g, (st, sand, t, peak) in enumerate(groups):
        ratio = finite(t.get("compressive_to_tensile_ratio"))
        ax.bar([g], [ratio if math.isfinite(ratio) else 0], 0.5, color=sand_color(sands.index(sand)), alpha=0.8,
               hatch="//" if t.get("role") == "predicted" else None)
        ax.text(g, (ratio if math.isfinite(ratio) else 0) + 0.2, fmt(ratio, 3), ha="center", va="bottom", fontsize=9)
        if not tension.get("assumed") and peak:
            lab = finite(peak.get("lab_mean")) / finite(t.get("lab_mean")) if finite(t.get("lab_mean")) else math.nan
            ax.plot([g - 0.3, g + 0.3], [lab, lab], color="black", lw=2, label="lab" if g == 0 else None)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels([s + (f" ({st['label']})" if len(stages) > 1 and st["label"] != s else "") for st, s, _, _ in groups])
    ax.set_ylabel("σc / σt [-]")
    ax.set_ylim(bottom=0)
    ax.set_title("Compressive over direct-tension strength (simulated)")
    ax.legend(loc="upper left", fontsize=8.5)
    return to_svg(fig)


def shape_index_rows(stages):
    """The stages' shape-index rows (sand, role, lab, simulated), labelled by stage when there are several."""
    rows = []
    for st in stages:
        for r in st.get("shape_index_d") or []:
            role = r.get("role", "?") + (f" ({st['label']})" if len(stages) > 1 else "")
            rows.append((r.get("sand"), role, finite(r.get("lab")), finite(r.get("simulated"))))
    return rows


def two_decimals(v):
    """D as the figure labels it ('–' when missing)."""
    return f"{v:.2f}" if math.isfinite(v) else "–"


def shape_index_text(sands, rows):
    """Per sand: the lab's D and each specimen set's simulated D, as the figure shows them."""
    parts = []
    for sand in sands:
        mine = [r for r in rows if r[0] == sand]
        if mine:
            sets = ", ".join(f"{role} {two_decimals(sim)}" for _, role, _, sim in mine)
            parts.append(f"{sand}: lab {two_decimals(mine[0][2])}, {sets}")
    return "; ".join(parts) + "."


def shape_index_figure(sands, rows):
    """D per sand: a bar per specimen set (fitted, validation, ...) beside the lab's D."""
    fig, (ax,) = new_figure(1, width=10.0, height=3.6)
    roles = list(dict.fromkeys(role for _, role, _, _ in rows))
    width = 0.8 / max(1, len(roles))
    for i, sand in enumerate(sands):
        mine = {role: (lab, sim) for s, role, lab, sim in rows if s == sand}
        if not mine:
            continue
        for k, role in enumerate(roles):
            if role not in mine:
                continue
            sim = mine[role][1]
            x = i - 0.4 + width * (k + 0.5)
            ax.bar([x], [sim if math.isfinite(sim) else 0], width * 0.9, color=sand_color(i),
                   alpha=0.85 if k == 0 else 0.45, hatch=None if k == 0 else "//", label=role if i == 0 else None)
            if math.isfinite(sim):  # inside the bar's top, clear of the lab's line
                ax.text(x, 0.96 * sim, two_decimals(sim), ha="center", va="top", fontsize=9, color="white" if k == 0 else "black")
        lab = next(iter(mine.values()))[0]
        ax.plot([i - 0.45, i + 0.45], [lab, lab], color="black", lw=2, label="lab" if i == 0 else None)
        ax.text(i + 0.46, lab, f"lab {two_decimals(lab)}", ha="left", va="center", fontsize=9)
    ax.set_xticks(range(len(sands)))
    ax.set_xticklabels(sands)
    ax.set_xlim(-0.6, len(sands) - 0.15)
    ax.set_ylabel("D = E·ε_peak / σ_peak [-]")
    ax.set_ylim(bottom=0)
    ax.set_title("Shape index of the stress–strain curve")
    ax.legend(loc="lower right", fontsize=8.5)
    return to_svg(fig)


def unit_position(p, v):
    """Position of value v within p's bounds in [0, 1] (log scale for log parameters)."""
    lo, hi = finite(p.get("lower")), finite(p.get("upper"))
    if p.get("scale") == "log" and lo > 0 and hi > lo and v > 0:
        return (math.log(v) - math.log(lo)) / (math.log(hi) - math.log(lo))
    return (v - lo) / (hi - lo) if hi > lo else math.nan


def parameters_figure(stages):
    rows = [(st, p) for st in stages for p in st.get("parameters") or [] if p.get("free")]
    fig, (ax,) = new_figure(1, width=10.0, height=1.0 + 0.55 * max(len(rows), 2))
    if not rows:
        message_panel(ax, "no free parameters")
        ax.set_title("Calibrated parameters")
        return to_svg(fig)
    for i, (st, p) in enumerate(rows):
        y = len(rows) - 1 - i
        ax.plot([0, 1], [y, y], color="#c9ced6", lw=6, solid_capstyle="butt", zorder=1)
        interval = p.get("one_sigma_interval") or []
        if len(interval) == 2:
            a, b = (min(max(unit_position(p, finite(v)), -0.02), 1.02) for v in interval)
            ax.plot([a, b], [y, y], color="#1f5fa8", lw=3, zorder=2)
        x = unit_position(p, finite(p.get("value")))
        ax.plot([x], [y], "o", color="#1f5fa8", ms=8, zorder=3)
        ax.plot([unit_position(p, finite(p.get("start")))], [y], "D", mfc="white", mec="black", ms=6, zorder=3)
        ax.text(1.03, y, f"{fmt(p.get('value'), 4)} {unit_text(p.get('unit'))}  ± {se_text(p)}", va="center", fontsize=9,
                transform=ax.get_yaxis_transform())
        ax.text(-0.01, y - 0.32, fmt(p.get("lower"), 3), ha="right", fontsize=7.5, color="#5b6475")
        ax.text(1.01, y - 0.32, fmt(p.get("upper"), 3), ha="left", fontsize=7.5, color="#5b6475")
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([f"{p['name']} [{p.get('unit', '-')}]" + (f" ({st['label']})" if len(stages) > 1 else "")
                        for st, p in reversed(rows)])
    ax.set_xlim(-0.05, 1.05)
    ax.set_ylim(-0.8, len(rows) - 0.4)
    ax.set_xticks([0, 0.25, 0.5, 0.75, 1])
    ax.set_xticklabels(["lower bound", "", "middle", "", "upper bound"])
    ax.set_xlabel("position within the bounds [-] (log scale for log parameters)")
    ax.set_title("Calibrated value (dot), ± 1 standard error (bar), start (diamond)")
    ax.grid(axis="y", visible=False)
    fig.subplots_adjust(right=0.78)
    return to_svg(fig)


def convergence_figure(history):
    fig, (left, right) = new_figure(2, width=10.0, height=4.0)
    if not history:
        for ax in (left, right):
            message_panel(ax, "convergence.csv has no evaluations")
        left.set_title("Objective")
        right.set_title("Parameters")
        return to_svg(fig)
    groups = {}
    for h in history:
        groups.setdefault(h["has_output"], []).append(h)
    labels_done = set()
    for h in history:
        color = LABEL_COLORS.get(h["label"], "#444")
        y = h["objective"] if h["objective"] > 0 else math.nan
        left.plot([h["evaluation"]], [y], "x" if h["failed"] else "o", color=color, ms=6,
                  label=h["label"] if h["label"] not in labels_done else None)
        labels_done.add(h["label"])
    for n, (_, members) in enumerate(groups.items()):
        best, xs, ys = math.inf, [], []
        for h in members:
            if not h["failed"] and h["objective"] > 0:
                best = min(best, h["objective"])
            xs.append(h["evaluation"])
            ys.append(best if math.isfinite(best) else math.nan)
        left.step(xs, ys, where="post", color="black", lw=1.2, label="best so far" if n == 0 else None)
    left.set_yscale("log")
    left.set_xlabel("evaluation [-]")
    left.set_ylabel("objective Σr² [-] (log scale)")
    left.set_title("Objective by evaluation")
    left.legend(fontsize=8, ncol=2)
    final = history[-1]["parameters"]
    best_eval = min((h for h in history if not h["failed"] and h["objective"] > 0), key=lambda h: h["objective"], default=history[-1])
    reference = best_eval["parameters"]
    for j, name in enumerate(final):
        ref = reference.get(name)
        xs = [h["evaluation"] for h in history]
        ys = [h["parameters"][name] / ref if ref and math.isfinite(ref) else math.nan for h in history]
        right.plot(xs, ys, "-o", ms=3.5, lw=1.2, color=["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"][j % 6],
                   label=name)
    right.axhline(1.0, color="#555", lw=0.8)
    right.set_xlabel("evaluation [-]")
    right.set_ylabel("value / best value [-]")
    right.set_title("Free parameters relative to the best evaluation")
    right.legend(fontsize=8)
    return to_svg(fig)


# ----------------------------------------------------------------------------- tables

def targets_table(stages):
    headers = ["stage", "sand", "target", "role", "lab mean ± std (n)", "simulated ± seed spread (n)", "rel. error", "z", "met"]
    rows = []
    for st in stages:
        for t in st.get("targets") or []:
            name = dict((q, n) for q, n, _ in QUANTITIES + [(TENSION, "tensile strength", "MPa")]).get(t.get("quantity"),
                                                                                                         t.get("quantity"))
            unit = t.get("unit", "")
            unit = "" if unit == "-" else f" {unit}"
            lab = (f"{fmt(t.get('lab_mean'), 4)}{unit} (ASSUMED: σc over the assumed ratio)" if t.get("assumed")
                   else f"{fmt(t.get('lab_mean'), 4)} ± {fmt(t.get('lab_std'), 2)}{unit} ({t.get('lab_n', '?')})")
            rows.append([st["label"], t.get("sand"), name, t.get("role", ""), lab,
                         f"{fmt(t.get('sim_mean'), 4)} ± {fmt(t.get('sim_std'), 2)}{unit} ({t.get('sim_n', '?')})",
                         pct(t.get("rel_error")), fmt(t.get("z"), 2), "yes" if t.get("met") else "no"])
    return headers, rows


def parameters_table(stages):
    headers = ["stage", "parameter", "value", "± 1 s.e.", "one-sigma interval", "bounds", "start", "scale, free"]
    rows = []
    for st in stages:
        for p in st.get("parameters") or []:
            interval = p.get("one_sigma_interval") or []
            rows.append([st["label"], f"{p['name']} [{p.get('unit', '-')}]", fmt(p.get("value"), 4),
                         se_text(p) if p.get("free") else "fixed",
                         f"{fmt(interval[0], 3)} – {fmt(interval[1], 3)}"
                         if len(interval) == 2 and all(math.isfinite(finite(v)) for v in interval) else "–",
                         f"[{fmt(p.get('lower'), 3)}, {fmt(p.get('upper'), 3)}]", fmt(p.get("start"), 4),
                         f"{p.get('scale', '')}, {'free' if p.get('free') else 'fixed'}"])
    return headers, rows


def stage_notes(st, label_it):
    prefix = f"{st['label']}: " if label_it else ""
    notes = [f"{prefix}solver {st.get('method')}, stop: {st.get('stop_reason')}"]
    h = st.get("homogeneity") or {}
    if h:
        notes.append(f"{prefix}homogeneity check (moduli × {fmt(h.get('alpha'), 4)}, strengths × {fmt(h.get('beta'), 4)}): "
                     f"E {pct(h.get('modulus_deviation'), 2)}, peak {pct(h.get('peak_deviation'), 2)} — "
                     f"{'holds' if h.get('holds') else 'does not hold'}")
    nf = st.get("noise_floor_rel_se") or {}
    if nf:
        notes.append(f"{prefix}noise floor (relative standard error of the seed mean): "
                     + ", ".join(f"{k.replace('_', ' ')} {pct(v, 2, signed=False)}" for k, v in nf.items()))
    ident = st.get("identifiability") or {}
    if ident.get("computed"):
        notes.append(f"{prefix}identifiability: singular values {', '.join(fmt(v, 3) for v in ident.get('singular_values') or [])}; "
                     f"condition number {fmt(ident.get('condition_number'), 3)}")
        for w in ident.get("poorly_identified") or []:
            notes.append(f"{prefix}the targets cannot pin down {w}")
    notes += [f"{prefix}unmet: {u}" for u in st.get("unmet_targets") or []]
    notes += [f"{prefix}note: {n}" for n in st.get("notes") or []]
    return notes


def packing_seeds_text(summary):
    """Every sand's seeds, or each sand's own list when they differ ("pre-blended: 1, 2; Van Buren: 1, 2, 3")."""
    by_sand = summary.get("packing_seeds_by_sand") or {}
    order = [sand for sand in summary.get("sands") or [] if sand in by_sand] or list(by_sand)
    lists = {sand: ", ".join(str(s) for s in by_sand[sand]) for sand in order}
    if len(set(lists.values())) > 1:
        return "; ".join(f"{sand}: {seeds}" for sand, seeds in lists.items())
    return ", ".join(str(s) for s in summary.get("packing_seeds") or [])


def run_rows(summary, runs):
    return [["DEM test runs", f"{runs.get('total', '?')} of a budget of {runs.get('budget', '?')} ({runs.get('executed_now', '?')} run now, "
             f"{runs.get('from_ledger', '?')} from the ledger, {runs.get('failed', '?')} failed)"],
            ["scale-up and validation runs", f"{runs.get('scale_up', 0)} and {runs.get('validation', 0)} (apart from the budget)"],
            ["evaluations", str(summary.get("evaluations", "?"))],
            ["wall time", clock(summary.get("wall_seconds"))],
            ["packing seeds per sand", packing_seeds_text(summary)],
            ["lab results", str(summary.get("lab_results", ""))],
            ["ledger", str(summary.get("ledger", ""))],
            ["problem fingerprint", str(summary.get("problem_fingerprint", ""))],
            ["code version", str(summary.get("code_version", ""))]]
