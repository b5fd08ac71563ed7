"""The figures of a `fines_truncation` study's report (study_report.py loads this module by the kind's
name; the `data` it reads is written by calibrate/study/kinds/fines_truncation.cpp).

Figures: 2: error against the particle ratio and against the wall-time ratio.
"""

from figures import message_panel, new_figure, sand_color, to_svg
from inputs import field, finite
from page import fmt
from study_common import QUANTITIES

TITLE = "what does cutting the fines cost in accuracy?"


def add_figures(page, data, cases, path):
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
