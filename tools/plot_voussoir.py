#!/usr/bin/env python3
"""Figures of voussoir-beam runs written by blockdem.

  plot_voussoir.py case DIR            figures of one run, into DIR
  plot_voussoir.py report DIR CASE...  figures of `blockdem reproduce boon2015`, into DIR/figures

Reads history.csv, blocks.csv, joints.csv and summary.json of each run. Needs numpy and matplotlib.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import plot_style  # noqa: E402
from plot_style import legend  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def column(rows, name, cast=float):
    return np.array([cast(r[name]) for r in rows])


class Run:
    """One run folder."""

    def __init__(self, folder, label=None):
        self.folder = folder
        self.label = label or os.path.basename(os.path.normpath(folder))
        self.history = [r for r in read_csv(os.path.join(folder, "history.csv")) if r["converged"] == "1"]
        self.blocks = read_csv(os.path.join(folder, "blocks.csv"))
        self.joints = read_csv(os.path.join(folder, "joints.csv"))
        with open(os.path.join(folder, "summary.json")) as f:
            self.summary = json.load(f)
        self.g = column(self.history, "g_level")

    def levels(self):
        return [int(r["level"]) for r in self.history]

    def profile(self, level):
        rows = [r for r in self.blocks if int(r["level"]) == level]
        x = np.array([float(r["x_m"]) for r in rows]) * 1e3
        d = np.array([float(r["deflection_mm"]) for r in rows])
        return x, d

    def thrust_points(self, level):
        rows = [r for r in self.joints if int(r["level"]) == level and r["in_contact"] == "1"]
        return np.array([float(r["x_mm"]) for r in rows]), np.array([float(r["z_mm"]) for r in rows])

    def fits(self, g_level):
        for lv in self.summary.get("voussoir", {}).get("levels", []):
            if abs(lv["g_level"] - g_level) < 1e-9:
                return lv["fits"]
        return None

    def level_at(self, g_level):
        for r in self.history:
            if abs(float(r["g_level"]) - g_level) < 1e-9:
                return int(r["level"])
        return None


def style(ax, xlabel, ylabel, title=None):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)


def downward(ax):
    """Deflections are downward positive: draw them downward, as the beam sags."""
    ax.invert_yaxis()


def draw_thrust_line(ax, run, g_level, colour):
    level = run.level_at(g_level)
    fits = run.fits(g_level)
    if level is None or not fits or "parabola" not in fits:
        return False
    x, z = run.thrust_points(level)
    xs = np.linspace(x.min(), x.max(), 200)
    p, c = fits["parabola"], fits["catenary"]
    ax.plot(x, z, "o", color=colour, label=f"contact points, {g_level:g} g")
    ax.plot(xs, 1e3 * (p["c0_m"] + p["c1"] * xs / 1e3 + p["c2_per_m"] * (xs / 1e3) ** 2), "-", color=colour,
            label=f"parabola {g_level:g} g (RMS {p['rms_mm']:.3f} mm)")
    ax.plot(xs, 1e3 * (c["y0_m"] - c["a_m"] * (np.cosh((xs / 1e3 - c["x0_m"]) / c["a_m"]) - 1)), "--",
            color=colour, label=f"catenary {g_level:g} g (RMS {c['rms_mm']:.3f} mm)")
    return True


def beam_outline(ax, run):
    beam = run.summary.get("voussoir", {}).get("beam", {})
    span, depth = 1e3 * beam.get("span_m", 0), 1e3 * beam.get("block_depth_m", 0)
    n = beam.get("blocks", 0)
    for i in range(n + 1):
        ax.plot([i * span / n] * 2, [-depth, 0], color="0.7", lw=0.8)
    ax.plot([0, span, span, 0, 0], [0, 0, -depth, -depth, 0], color="0.5", lw=1)


def case_figures(folder):
    run = Run(folder)
    out = []
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(run.g, column(run.history, "thrust_N"), **plot_style.mode_style(run.label))
    style(ax, plot_style.GRAVITY_LABEL, plot_style.THRUST_LABEL, f"{run.label}: thrust")
    out.append(save(fig, folder, "thrust_vs_g.png"))

    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(run.g, column(run.history, "midspan_deflection_mm"), **plot_style.mode_style(run.label))
    style(ax, plot_style.GRAVITY_LABEL, plot_style.MIDSPAN_DEFLECTION_LABEL,
          f"{run.label}: midspan deflection")
    downward(ax)
    out.append(save(fig, folder, "midspan_deflection_vs_g.png"))

    fig, ax = plt.subplots(figsize=(6.5, 4))
    colours = plot_style.level_colours(len(run.g))
    for colour, level, g in zip(colours, run.levels(), run.g):
        x, d = run.profile(level)
        ax.plot(x, d, color=colour, label=f"{g:g} g", **plot_style.mode_style(run.label))
    style(ax, "x along the span (mm)", "block bottom " + plot_style.DEFLECTION_LABEL,
          f"{run.label}: deflection profiles")
    downward(ax)
    legend(ax, ncol=2)
    out.append(save(fig, folder, "deflection_profiles.png"))

    fig, ax = plt.subplots(figsize=(7, 4))
    beam_outline(ax, run)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    drawn = False
    for i, g in enumerate(sorted({10.0, float(run.g[-1])})):
        drawn |= draw_thrust_line(ax, run, g, colours[i % len(colours)])
    style(ax, "x along the span (mm)", "z, up positive (mm)", f"{run.label}: line of thrust")
    if drawn:
        legend(ax)
    out.append(save(fig, folder, "thrust_line.png"))
    return out


def save(fig, folder, name):
    return plot_style.save(fig, os.path.join(folder, name))


def panels(groups):
    """One panel per non-empty (runs, title) group: a subset draws only what ran."""
    groups = [(runs, title) for runs, title in groups if runs]
    if not groups:
        return None, []
    fig, axes = plt.subplots(1, len(groups), figsize=(5 * len(groups), 4), squeeze=False)
    return fig, list(zip(axes[0], groups))


def case_colour(label):
    """One colour per paper case, shared by its two contact modes."""
    base = label[:-3] if label.endswith("-fi") else label
    order = ["T2-1", "T2-2", "T2-3", "F8", "T3-full", "T3-half", "T3-half-old"]
    index = order.index(base) if base in order else len(order)
    return plt.get_cmap("tab10")(index % 10)


def report_figures(folder, cases):
    runs = {c: Run(os.path.join(folder, c), c) for c in cases if os.path.exists(os.path.join(folder, c, "history.csv"))}
    figs = os.path.join(folder, "figures")
    os.makedirs(figs, exist_ok=True)
    full = [r for r in runs.values() if r.summary["voussoir"]["beam"]["block_depth_m"] > 0.03]
    half = [r for r in runs.values() if r.summary["voussoir"]["beam"]["block_depth_m"] <= 0.03]

    # Fig. 5 analogue: thrust build-up of the full-block beam.
    if full:
        fig, ax = plt.subplots(figsize=(6, 4.2))
        for r in full:
            ax.plot(r.g, column(r.history, "thrust_N"), color=case_colour(r.label), label=r.label,
                    **plot_style.mode_style(r.label))
        ax.plot([40], [349], "D", color="0.2", mfc="none", ms=8,
                label="test 180-E, strain gauges, 40 g (349 N, as read by the paper)")
        style(ax, plot_style.GRAVITY_LABEL, plot_style.THRUST_LABEL,
              "Thrust build-up, full-block beam (cf. paper Fig. 5)")
        legend(ax)
        save(fig, figs, "fig5_thrust_full_block.png")

    # Midspan deflection against g, both beams.
    fig, pairs = panels([(full, "full-block beam"), (half, "half-block beam")])
    for ax, (group, title) in pairs:
        for r in group:
            ax.plot(r.g, column(r.history, "midspan_deflection_mm"), color=case_colour(r.label),
                    label=r.label, **plot_style.mode_style(r.label))
        style(ax, plot_style.GRAVITY_LABEL, plot_style.MIDSPAN_DEFLECTION_LABEL,
              f"Midspan deflection, {title}")
        downward(ax)
        legend(ax)
    if fig is not None:
        save(fig, figs, "midspan_deflection_vs_g.png")

    # Figs 6, 8, 9 analogues: deflection profiles at the last level.
    fig, pairs = panels([(full, "full-block beam"), (half, "half-block beam")])
    for ax, (group, title) in pairs:
        for r in group:
            level = r.levels()[-1]
            x, d = r.profile(level)
            ax.plot(x, d, color=case_colour(r.label), label=f"{r.label} ({r.g[-1]:g} g)",
                    **plot_style.mode_style(r.label))
        style(ax, "x along the span (mm)", "block bottom " + plot_style.DEFLECTION_LABEL,
              f"Deflection profiles, {title}\n(cf. paper Figs 6, 8, 9)")
        downward(ax)
        legend(ax)
    if fig is not None:
        save(fig, figs, "deflection_profiles.png")

    # Fig. 7 analogue: line of thrust, catenary and parabola at 10 g and 40 g.
    first = next((r for r in full if r.label == "T2-1"), full[0] if full else None)
    if first is not None:
        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        beam_outline(ax, first)
        draw_thrust_line(ax, first, 10.0, "tab:blue")
        draw_thrust_line(ax, first, 40.0, "tab:red")
        style(ax, "x along the span (mm)", "z, up positive (mm)",
              f"Line of thrust, {first.label} (cf. Fig. 7)")
        legend(ax, loc="lower center")
        save(fig, figs, "fig7_thrust_line.png")

    # Block rotations along the beam.
    fig, pairs = panels([(full, "full-block beam"), (half, "half-block beam")])
    for ax, (group, title) in pairs:
        for r in group:
            level = r.levels()[-1]
            rows = [b for b in r.blocks if int(b["level"]) == level]
            ax.plot([1e3 * float(b["x_m"]) for b in rows], [float(b["rotation_deg"]) for b in rows],
                    color=case_colour(r.label), label=f"{r.label} ({r.g[-1]:g} g)",
                    **plot_style.mode_style(r.label))
        style(ax, "x along the span (mm)", "rotation about y (degrees)", f"Block rotations, {title}")
        legend(ax)
    if fig is not None:
        save(fig, figs, "block_rotations.png")
    for r in runs.values():
        case_figures(r.folder)


def main(argv):
    plot_style.setup()
    if len(argv) >= 2 and argv[0] == "case":
        case_figures(argv[1])
    elif len(argv) >= 3 and argv[0] == "report":
        report_figures(argv[1], argv[2:])
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
