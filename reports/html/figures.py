"""matplotlib figures as inline SVG. The Agg backend (no display); text is drawn as paths
(svg.fonttype 'path'), so a figure looks the same on every machine without fonts; ids are salted
per figure so several figures can share one HTML page; no date in the metadata."""

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

# One colour per sand, in the order the results list the sands (colour-blind-safe, Okabe–Ito).
SAND_COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]
MODE_COLORS = {"tension": "#0072B2", "shear": "#D55E00"}

plt.rcParams.update({
    "font.family": "DejaVu Sans",
    "font.size": 10,
    "axes.titlesize": 11.5,
    "axes.titleweight": "bold",
    "axes.labelsize": 10.5,
    "axes.grid": True,
    "grid.color": "#e3e6eb",
    "grid.linewidth": 0.7,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.fontsize": 9,
    "legend.frameon": False,
    "svg.fonttype": "path",
    "figure.dpi": 100,
})

_counter = [0]


def sand_color(index):
    return SAND_COLORS[index % len(SAND_COLORS)]


def new_figure(panels=1, width=10.0, height=4.2, **kwargs):
    """A figure with `panels` axes side by side; returns (fig, list of axes)."""
    fig, axes = plt.subplots(1, panels, figsize=(width, height), squeeze=False, **kwargs)
    return fig, list(axes[0])


def new_grid(rows, cols, width=10.0, height=6.0, **kwargs):
    """A figure with rows × cols axes; returns (fig, 2-D array of axes)."""
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False, **kwargs)
    return fig, axes


def message_panel(ax, text):
    """A panel that says why it has no data (the figure count stays fixed)."""
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, color="#5b6475", wrap=True)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.grid(False)
    for spine in ax.spines.values():
        spine.set_visible(False)


def to_svg(fig):
    """The figure as an <svg> element (no XML prolog), closed afterwards."""
    _counter[0] += 1
    plt.rcParams["svg.hashsalt"] = f"gradem-figure-{_counter[0]}"
    fig.tight_layout()
    buffer = io.StringIO()
    fig.savefig(buffer, format="svg", metadata={"Date": None})
    plt.close(fig)
    text = buffer.getvalue()
    return text[text.index("<svg"):]
