"""One plotting style for every blockdem figure.

Every figure is saved twice: a PNG at 200 dpi and a vector copy (SVG) beside it. Contact modes are
told apart by line style and marker, not by colour alone; many load levels get colours from a
sequential colour map. Axis labels carry symbols and units, and deflections are downward positive,
as in the tables.
"""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 200
VECTOR_FORMAT = "svg"

# Line style per contact mode: the paper's point contact solid with circles, face integration
# dashed with squares.
MODE_STYLE = {
    "boon2012": {"linestyle": "-", "marker": "o"},
    "face_integrated": {"linestyle": "--", "marker": "s"},
}

DEFLECTION_LABEL = "deflection, downward positive (mm)"
MIDSPAN_DEFLECTION_LABEL = "midspan deflection δ, downward positive (mm)"
GRAVITY_LABEL = "gravity level (g; 1 g = 9.81 m/s²)"
THRUST_LABEL = "horizontal thrust H (N)"


def setup():
    """Sets the shared matplotlib parameters (call once per script)."""
    plt.rcParams.update({
        "figure.dpi": 100,
        "savefig.dpi": DPI,
        "font.size": 9,
        "axes.titlesize": 10,
        "axes.labelsize": 9,
        "legend.fontsize": 7,
        "lines.linewidth": 1.5,
        "lines.markersize": 4,
        "axes.grid": True,
        "grid.alpha": 0.3,
        "svg.fonttype": "none",
    })


def mode_of(label):
    """The contact mode of a case id: the suffix -fi marks face integration."""
    return "face_integrated" if label.endswith("-fi") else "boon2012"


def mode_style(label):
    return dict(MODE_STYLE[mode_of(label)])


def level_colours(count, cmap="viridis"):
    """`count` colours from a sequential colour map, light to dark with rising load."""
    colour_map = plt.get_cmap(cmap)
    if count <= 1:
        return [colour_map(0.6)]
    return [colour_map(0.15 + 0.8 * i / (count - 1)) for i in range(count)]


def legend(ax, **kwargs):
    """A legend only when something is labelled (no warning for an empty one)."""
    handles, labels = ax.get_legend_handles_labels()
    if labels:
        ax.legend(**kwargs)


def save(fig, path):
    """Saves the PNG (200 dpi) and its vector copy; returns the PNG path."""
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    fig.savefig(os.path.splitext(path)[0] + "." + VECTOR_FORMAT)
    plt.close(fig)
    return path
