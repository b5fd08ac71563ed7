"""The figures of a `sensitivity` study's report (study_report.py loads this module by the kind's
name; the `data` it reads is written by calibrate/study/kinds/sensitivity.cpp).

Figures: 1: elasticity bars ± standard error, parameter × quantity, per sand.
"""

from figures import message_panel, new_figure, to_svg
from inputs import field, finite
from study_common import MODEL_COLORS, QUANTITIES, np

TITLE = "which parameter moves which property?"


def add_figures(page, data, cases, path):
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
