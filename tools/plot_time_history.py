#!/usr/bin/env python3
"""Time histories of a run (blockdem run): the energy budget and the convergence measures.

Usage: plot_time_history.py RUN_DIR
Reads RUN_DIR/time_history.csv (docs/outputs.md); writes RUN_DIR/time_history.png (and its SVG).
Upper panel: the energy budget's terms against model time (kinetic and elastic energy, the work
of gravity and of the loads, the friction and damping dissipation, the residual). Lower panel:
the unbalanced-force ratio and the kinetic-energy ratio (log scale). Dotted lines mark where each
stage begins. A strength reduction's trials step copies of the model and are not in the file.
"""
import csv
import math
import os
import sys

import plot_style

plt = plot_style.plt

# The budget's columns, their labels and whether a term that stays zero is left out.
ENERGY = [
    ("kinetic_energy_J", "kinetic", False),
    ("elastic_energy_J", "elastic (joints)", False),
    ("gravity_work_J", "work of gravity", False),
    ("load_work_J", "work of the loads", True),
    ("boundary_work_J", "work of the boundaries", True),
    ("friction_dissipation_J", "friction dissipation", False),
    ("damping_dissipation_J", "damping dissipation", True),
    ("contact_damping_J", "contact dashpots", True),
    ("energy_residual_J", "residual", False),
]
RATIOS = [("unbalanced_force_ratio", "unbalanced-force ratio"),
          ("kinetic_energy_ratio", "kinetic-energy ratio")]


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_time_history.py RUN_DIR")
    run = sys.argv[1]
    with open(os.path.join(run, "time_history.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    if len(rows) < 2:
        return  # a run of fewer steps than history_interval: nothing to draw
    plot_style.setup()
    t = [number(r["time_s"]) for r in rows]
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for column, label, optional in ENERGY:
        if column not in rows[0]:
            continue
        values = [number(r[column]) for r in rows]
        if optional and not any(v != 0 for v in values if not math.isnan(v)):
            continue
        ax.plot(t, values, label=label, lw=1.2,
                linestyle=":" if column == "energy_residual_J" else "-")
    ax.set_ylabel("energy (J)")
    ax.set_title("Energy budget of the free blocks")
    plot_style.legend(ax, loc="best", ncol=2)
    for column, label in RATIOS:
        if column not in rows[0]:
            continue
        # Zero and infinite ratios (no load yet, at rest) have no place on a log axis.
        values = [number(r[column]) for r in rows]
        values = [v if 0 < v < math.inf else math.nan for v in values]
        bx.plot(t, values, label=label, lw=1.2)
    bx.set_yscale("log")
    bx.set_xlabel("model time t (s)")
    bx.set_ylabel("ratio (-)")
    bx.set_title("Convergence measures")
    plot_style.legend(bx, loc="best")
    # Where each stage begins.
    stage = None
    for r, time in zip(rows, t):
        if r["stage"] != stage:
            stage = r["stage"]
            for axis in (ax, bx):
                axis.axvline(time, color="0.5", lw=0.6, linestyle=":")
            bx.annotate(stage, (time, 0.02), xycoords=("data", "axes fraction"), fontsize=6,
                        rotation=90, va="bottom", ha="right", color="0.35")
    plot_style.save(fig, os.path.join(run, "time_history.png"))


if __name__ == "__main__":
    main()
