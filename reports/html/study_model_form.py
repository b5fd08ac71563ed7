"""The figures of a `model_form` study's report (study_report.py loads this module by the kind's
name; the `data` it reads is written by calibrate/study/kinds/model_form.cpp).

Figures: 3: target errors per model; shape index D simulated vs lab; σc/σt and cost per cube test.
"""

import math
import os

from figures import message_panel, new_figure, to_svg
from inputs import field, finite
from page import fmt
from study_common import MODEL_COLORS, QUANTITIES, clock, np

TITLE = "which bond model fits the lab best?"


def cards(study, data):
    models = data.get("models") or []
    runs = study.get("runs") or {}
    failed = int(runs.get("failed", 0))
    return [("models compared", f"{len(models)}", "each from its own calibration's summary.json", ""),
            ("DEM runs", f"{sum(int(m.get('runs') or 0) for m in models)}", "of those calibrations", ""),
            ("wall time", clock(sum(finite(m.get("wall_seconds")) for m in models)), "of those calibrations", ""),
            ("tension tests", f"{int(runs.get('executed_now', 0)) + int(runs.get('from_ledger', 0))}",
             f"for σc/σt: {runs.get('executed_now', 0)} run now, {runs.get('from_ledger', 0)} from the ledger, {failed} failed",
             "bad" if failed else "")]


def add_figures(page, data, cases, path):
    models = field(data, "models", path, list)
    names = [f"{m.get('model')} ({os.path.basename(os.path.dirname(str(m.get('summary', ''))))})" for m in models]
    tolerances = data.get("target_tolerances") or {}
    sands = list(dict.fromkeys(s.get("sand") for m in models for s in m.get("sands") or []))
    page.section("The models side by side", "Each model's own calibration against the same lab targets.")
    fig, axes = new_figure(max(1, len(sands)), width=11.0, height=3.8)
    w = 0.8 / max(1, len(models))
    shown_validation = False
    for ax, sand in zip(axes, sands or [None]):
        labelled = False  # one legend entry for the validation markers
        if sand is None:
            message_panel(ax, "no models")
            continue
        for k, (m, label) in enumerate(zip(models, names)):
            s = next((s for s in m.get("sands") or [] if s.get("sand") == sand), {})
            err = [100 * finite(s.get(f"{q.split('_')[0]}_error")) for q, _, _ in QUANTITIES]
            x = np.arange(3) - 0.4 + w * (k + 0.5)
            ax.bar(x, np.nan_to_num(err), width=w * 0.9, color=MODEL_COLORS[k % 5], label=label)
            v = s.get("validation") or {}
            val = [100 * finite(v.get(f"{q.split('_')[0]}_error")) for q, _, _ in QUANTITIES]
            if any(e == e for e in val):  # the calibration's validation specimens (NaN: none)
                shown_validation = True
                ax.plot(x, val, "D", color="black", mfc="white", ms=6, mew=1.5,
                        label=None if labelled else "validation specimens")
                labelled = True
        for q, (key, _, _) in enumerate(QUANTITIES):  # each target's own tolerance (calibrate/target_tolerance.hpp)
            tol = 100 * finite(tolerances.get(key, 0.05))
            ax.fill_between([q - 0.45, q + 0.45], -tol, tol, color="#009E73", alpha=0.12, lw=0)
        ax.axhline(0, color="#5b6475", lw=1)
        ax.set_xticks(range(3), [n for _, n, _ in QUANTITIES])
        ax.set_ylabel("relative error [%]")
        ax.set_title(sand)
    axes[0].legend(loc="best")
    page.figure(to_svg(fig), "Target errors per model and sand",
                "Relative error (simulated / lab − 1) of each target at each model's calibrated parameters on its fitted "
                "specimens" + ("; white diamonds: on its validation specimens (larger cubes, unseen seeds)" if shown_validation else "") +
                "; green band: the target's tolerance (" + ", ".join(f"{n} ± {fmt(100 * finite(tolerances.get(k, 0.05)), 3)} %"
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
