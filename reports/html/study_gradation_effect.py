"""The figures of a `gradation_effect` study's report (study_report.py loads this module by the kind's
name; the `data` it reads is written by calibrate/study/kinds/gradation_effect.cpp).

Figures: 2: simulated vs lab difference a − b with 95 % intervals; the seed values per sand.
"""

from matplotlib.ticker import MaxNLocator

from figures import message_panel, new_figure, sand_color, to_svg
from inputs import field, finite
from study_common import LAB_COLOR, QUANTITIES, RUN_KEYS, SIM_COLOR, all_runs, np

TITLE = "does one parameter set reproduce the lab's difference between the sands?"


def add_figures(page, data, cases, path):
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
