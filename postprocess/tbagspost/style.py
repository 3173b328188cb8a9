"""The paper style of the figures (Agg backend, serif fonts, inward ticks) and saving."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from cycler import cycler  # noqa: E402

PAPER = {
    "font.family": "serif",
    "font.size": 9,
    "axes.labelsize": 9,
    "axes.titlesize": 9,
    "legend.fontsize": 8,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "lines.linewidth": 1.2,
    "savefig.dpi": 200,
    "savefig.bbox": "tight",
    # curves told apart in black and white too (the three loads of the paper)
    "axes.prop_cycle": cycler(color=["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"],
                              linestyle=["-", "--", "-.", ":", "-", "--"]),
}
plt.rcParams.update(PAPER)


def figure(nrows=1, ncols=1, width=7.0, height=3.0, **kw):
    """A new Figure with an nrows x ncols grid of axes (plt.subplots); save() closes it."""
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), **kw)
    return fig, axes


def grid_figure(nrows, ncols, width, height, **gridspec):
    """A new empty Figure and a GridSpec of nrows x ncols cells (for panels spanning cells)."""
    fig = plt.figure(figsize=(width, height))
    return fig, fig.add_gridspec(nrows, ncols, **gridspec)


def save(fig, path, formats=("png",), dpi=None):
    """Save fig as path.<fmt> for each format (path has no suffix; dots in its name stay);
    returns the written paths. Closes the figure."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    out = []
    for fmt in formats:
        p = path.parent / (path.name + "." + fmt)
        fig.savefig(p, dpi=dpi or PAPER["savefig.dpi"])
        out.append(p)
    plt.close(fig)
    return out


def panel_label(ax, text):
    """'(a)'-style label at the top left of an axes."""
    ax.text(0.01, 0.99, text, transform=ax.transAxes, ha="left", va="top", fontweight="bold",
            bbox=dict(facecolor="white", edgecolor="none", alpha=0.7, pad=1))
