#!/usr/bin/env python3
"""Failure mechanism of a strength-reduction run: blocks at their start position (grey), the
moving blocks' velocity as arrows (x-z view), and the bisection of the factor of safety.

Usage: plot_mechanism.py RUN_DIR   (reads mechanism.csv, strength_reduction.csv, summary.json;
writes RUN_DIR/mechanism.png)"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    run = sys.argv[1]
    blocks = rows(os.path.join(run, "mechanism.csv"))
    trials = rows(os.path.join(run, "strength_reduction.csv"))
    with open(os.path.join(run, "summary.json")) as f:
        fos = json.load(f)["factor_of_safety"]

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    xs = [float(b["x_m"]) - float(b["ux_mm"]) / 1e3 for b in blocks]
    zs = [float(b["z_m"]) - float(b["uz_mm"]) / 1e3 for b in blocks]
    vx = [float(b["vx_m_s"]) for b in blocks]
    vz = [float(b["vz_m_s"]) for b in blocks]
    moving = [b["moving"] == "1" for b in blocks]
    if not any(moving):
        # The failed trial stopped early: show the blocks moving at half the top speed or more.
        speed = [float(b["speed_m_s"]) for b in blocks]
        moving = [v >= 0.5 * max(speed) and v > 0 for v in speed]
    ax.scatter([x for x, m in zip(xs, moving) if not m], [z for z, m in zip(zs, moving) if not m],
               c="0.6", s=18, label="block centroid, at rest")
    ax.scatter([x for x, m in zip(xs, moving) if m], [z for z, m in zip(zs, moving) if m],
               c="tab:red", s=24, label="block centroid, moving")
    if any(moving):
        ax.quiver([x for x, m in zip(xs, moving) if m], [z for z, m in zip(zs, moving) if m],
                  [v for v, m in zip(vx, moving) if m], [v for v, m in zip(vz, moving) if m],
                  color="tab:red", angles="xy", width=0.004)
    ax.set_aspect("equal", adjustable="datalim")
    span = max(max(xs) - min(xs), max(zs) - min(zs), 0.05)
    ax.set_xlim(min(xs) - 0.5 * span, max(xs) + 0.5 * span)
    ax.set_ylim(min(zs) - 0.5 * span, max(zs) + 0.5 * span)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(f"Mechanism at F = {fos['first_failed']:.3f} (velocity arrows)")
    ax.legend(loc="best", fontsize=8)

    f = [float(t["factor"]) for t in trials]
    ok = [t["stable"] == "1" for t in trials]
    n = list(range(1, len(trials) + 1))
    bx.plot(n, f, color="0.5", lw=0.8)
    bx.scatter([i for i, s in zip(n, ok) if s], [v for v, s in zip(f, ok) if s], c="tab:green",
               label="stable")
    bx.scatter([i for i, s in zip(n, ok) if not s], [v for v, s in zip(f, ok) if not s],
               c="tab:red", marker="x", label="failed")
    bx.axhline(fos["value"], color="k", ls="--", lw=0.8, label=f"F = {fos['value']:.3f}")
    bx.set_xlabel("trial")
    bx.set_ylabel("strength reduction factor F (-)")
    bx.set_title("Bisection of the factor of safety")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(run, "mechanism.png"), dpi=120)


if __name__ == "__main__":
    main()
