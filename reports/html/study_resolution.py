"""The figures of a `resolution` study's report (study_report.py loads this module by the kind's
name; the `data` it reads is written by calibrate/study/kinds/resolution.cpp).

Figures: 1: mean ± seed std against the cube edge, converged edge marked.
"""

from figures import message_panel, new_grid, sand_color, to_svg
from inputs import finite
from study_common import QUANTITIES, case_series, np

TITLE = "how do the results change with the cube edge?"


def add_figures(page, data, cases, path):
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
