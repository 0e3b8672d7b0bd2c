#!/usr/bin/env python3
"""Figures of `blockdem lab`: joint compression and shear tests, and the joint-law figures.

Usage:
  plot_joint_laws.py compression CSV PNG [LABEL]   sigma-u of `blockdem lab compression`
  plot_joint_laws.py shear CSV PNG [LABEL]         tau, tau/sigma_n, plastic slip vs u_s
  plot_joint_laws.py figures DIR                   Figs 1(b), 2, 3, 4 from DIR/fig*.csv
The CSV files are written by blockdem (units in the column names; SI). Prints nothing on stdout
(blockdem prints its JSON summary there). Exit codes: 0 written,
2 bad input, 3 matplotlib unavailable. Run with /usr/bin/python3 on Debian (python3-matplotlib).
Equation and figure numbers refer to Boon, Houlsby & Utili (2015), Geotechnique Letters 5:49-55.
"""

import csv
import math
import os
import sys

TAN40 = math.tan(math.radians(40.0))


def read_csv(path):
    """Columns of a CSV file as lists; numbers as floats (empty cells as NaN), text kept."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError("%s has no rows" % path)
    table = {}
    for key in rows[0].keys():
        values = [r[key] for r in rows]
        try:
            table[key] = [float(v) if v != "" else math.nan for v in values]
        except ValueError:
            table[key] = values
    return table


def group_by(table, key):
    """{value of column key: {column: values}}, groups in file order."""
    out = {}
    for i, value in enumerate(table[key]):
        group = out.setdefault(value, {k: [] for k in table})
        for k in table:
            group[k].append(table[k][i])
    return out


def finite_max(values):
    finite = [abs(v) for v in values if not math.isnan(v)]
    return max(finite) if finite else 0.0


def length_unit(max_m):
    """(scale, label) for displacements: micrometres below 1 mm, millimetres above."""
    return (1e6, "µm") if max_m < 1e-3 else (1e3, "mm")


def stress_unit(max_pa):
    """(scale, label) for stresses: kPa below 1 MPa, MPa above."""
    return (1e-3, "kPa") if max_pa < 1e6 else (1e-6, "MPa")


def every(values, count):
    """About `count` evenly spaced entries of `values` (for markers on long curves)."""
    step = max(1, len(values) // count)
    return values[::step]


def plot_compression(plt, csv_path, png_path, label):
    t = read_csv(csv_path)
    su, sl = stress_unit(finite_max(t["normal_stress_Pa"]))
    lu, ll = length_unit(finite_max(t["closure_m"]))
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    loading = [b == "loading" for b in t["branch"]]
    for wanted, style, name in ((True, "-", "kernel, loading"), (False, "--", "kernel, unloading")):
        u = [x * lu if (l == wanted or i == 0) else math.nan
             for i, (x, l) in enumerate(zip(t["closure_m"], loading))]
        s = [x * su for x in t["normal_stress_Pa"]]
        ax.plot(u, s, style, color="C0" if wanted else "C1", lw=1.6, label=name)
    if "dem_closure_m" in t:
        # Closure under the same load, engine against kernel.
        gap = finite_max([d - k for d, k in zip(t["dem_closure_m"], t["closure_m"])])
        ax.plot([x * lu for x in t["dem_closure_m"]], [x * su for x in t["dem_normal_stress_Pa"]],
                "o", mfc="none", color="C3", ms=5,
                label="DEM, two blocks, load levels\n(max |Δu_n| = %.2g u_max)" %
                (gap / finite_max(t["closure_m"])))
    ax.set_xlabel("closure u_n (%s)" % ll)
    ax.set_ylabel("normal stress σ_n (%s)" % sl)
    ax.set_title("Joint compression test\n%s" % label, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left")
    plot_style.save(fig, png_path)


def plot_shear(plt, csv_path, png_path, label):
    t = read_csv(csv_path)
    lu, ll = length_unit(finite_max(t["shear_displacement_m"]))
    su, sl = stress_unit(finite_max(t["shear_stress_Pa"]))
    has_dem = "dem_shear_stress_Pa" in t
    fig, axes = plt.subplots(3, 1, figsize=(6.4, 8.4), sharex=True)
    u = [x * lu for x in t["shear_displacement_m"]]
    panels = (("shear_stress_Pa", su, "shear stress τ (%s)" % sl),
              ("mobilised_friction", 1.0, "mobilised friction τ/σ_n (-)"),
              ("plastic_slip_m", lu, "plastic slip β (%s)" % ll))
    dem_label = ""
    if has_dem:
        gap = finite_max([d - k for d, k in zip(t["dem_shear_stress_Pa"], t["shear_stress_Pa"])])
        dem_label = "DEM, two blocks\n(max |Δτ| = %.2g max |τ|)" % (
            gap / finite_max(t["shear_stress_Pa"]))
    for ax, (column, scale, ylabel) in zip(axes, panels):
        ax.plot(u, [x * scale for x in t[column]], "-", color="C0", lw=1.6, label="kernel")
        if has_dem:
            du = [x * lu for x in t["dem_shear_displacement_m"]]
            dv = [x * scale for x in t["dem_" + column]]
            ax.plot(every(du, 40), every(dv, 40), "o", mfc="none", color="C3", ms=5,
                    label=dem_label)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best", fontsize=9)
    axes[-1].set_xlabel("shear displacement u_s (%s)" % ll)
    axes[0].set_title("Direct shear test at constant normal stress\n%s" % label, fontsize=10)
    plot_style.save(fig, png_path)


def fig1b(plt, directory):
    t = group_by(read_csv(os.path.join(directory, "fig1b_normal_laws.csv")), "law")
    styles = {"eq3": ("-", "C0", "eq. 3: 0.5405e5 [exp(7.4e4 u_n) - 1]"),
              "eq4": ("-", "C3", "eq. 4: 0.5405e5 [exp(3.7e4 u_n) - 1] (half stiffness)"),
              "linear_table2": ("--", "0.5", "linear, k_n = 10 GPa/m (Table 2)")}
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for law, g in t.items():
        style, color, name = styles.get(law, ("-", None, law))
        ax.plot([u * 1e6 for u in g["closure_m"]], [s * 1e-6 for s in g["normal_stress_Pa"]],
                style, color=color, lw=1.8, label=name)
    ax.set_xlabel("joint closure u_n (µm)")
    ax.set_ylabel("normal stress σ_n (MPa)")
    ax.set_title("Normal joint laws, eqs 3 and 4 (cf. Fig. 1(b))")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    path = os.path.join(directory, "fig1b_normal_laws.png")
    plot_style.save(fig, path)
    return path


def fig2(plt, directory):
    t = group_by(read_csv(os.path.join(directory, "fig2_shear_stiffness.csv")), "normal_stress_Pa")
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for i, (sigma, g) in enumerate(t.items()):
        color = "C%d" % i
        u = [x * 1e6 for x in g["shear_displacement_m"]]
        ax.plot(u, [k * 1e-9 for k in g["shear_stiffness_Pa_per_m"]], "-", color=color, lw=1.8,
                label="σ_n = %g kPa" % (sigma * 1e-3))
        # The capped law, drawn only where the cap changes the stiffness.
        capped = [c * 1e-9 if abs(c - k) > 1e-3 * g["initial_stiffness_Pa_per_m"][0] else math.nan
                  for c, k in zip(g["capped_shear_stiffness_Pa_per_m"],
                                  g["shear_stiffness_Pa_per_m"])]
        ax.plot(u, capped, "--", color=color, lw=1.2)
        peak = g["peak_displacement_m"][0]
        ax.plot([peak * 1e6], [0.0], "v", color=color, ms=7)
    ax.plot([], [], "v", color="0.3", label="u_peak, eq. 6")
    ax.plot([], [], "--", color="0.3", lw=1.2, label="with Mohr-Coulomb cap φ = 40°")
    ax.set_xlabel("shear displacement u_s (µm)")
    ax.set_ylabel("tangent shear stiffness k_s (GPa/m)")
    ax.set_title("Degrading shear stiffness, eq. 5 with eqs 6-7 (cf. Fig. 2)\n"
                 "dτ/du_s of the degrading-law kernel along monotonic shear", fontsize=10)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=-0.05 * ax.get_ylim()[1])
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=9)
    path = os.path.join(directory, "fig2_shear_stiffness.png")
    plot_style.save(fig, path)
    return path


def fig3(plt, directory):
    t = read_csv(os.path.join(directory, "fig3_initial_shear_stiffness.csv"))
    sigma = [s * 1e-3 for s in t["normal_stress_Pa"]]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.loglog(sigma, [k * 1e-9 for k in t["eq7_initial_stiffness_Pa_per_m"]], "-", color="C3",
              lw=1.8, label="eq. 7: k_s,initial = 1.9e6 σ_n^0.7")
    ax.loglog(sigma, [k * 1e-9 for k in t["eq2_stiffness_Pa_per_m"]], "-", color="C0", lw=1.8,
              label="eq. 2: k_s = 1e8 + 9.7e4 σ_n")
    ax.axvspan(sigma[0], 23.0, color="0.85", zorder=0, label="shear tests (≤ 0.023 MPa)")
    for s, name in ((500.0, "full beam"), (1000.0, "half beam")):
        ax.axvline(s, color="0.4", ls=":", lw=1)
        ax.text(s * 0.93, ax.get_ylim()[0] * 1.5, name, rotation=90, ha="right", va="bottom",
                fontsize=8, color="0.3")
    ax.set_xlabel("normal stress σ_n (kPa)")
    ax.set_ylabel("initial shear stiffness (GPa/m)")
    ax.set_title("Initial shear stiffness vs normal stress, eqs 7 and 2 (cf. Fig. 3)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="upper left", fontsize=9)
    path = os.path.join(directory, "fig3_initial_shear_stiffness.png")
    plot_style.save(fig, path)
    return path


def fig4(plt, directory):
    t = group_by(read_csv(os.path.join(directory, "fig4_shear_stress.csv")), "normal_stress_Pa")
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for i, (sigma, g) in enumerate(t.items()):
        color = "C%d" % i
        u = [x * 1e3 for x in g["shear_displacement_m"]]
        ax.plot(u, [s * 1e-3 for s in g["shear_stress_Pa"]], "-", color=color, lw=1.8,
                label="σ_n = %g kPa" % (sigma * 1e-3))
        ax.axhline(sigma * TAN40 * 1e-3, color=color, ls=":", lw=1)
    ax.plot([], [], ":", color="0.3", label="σ_n tan 40°")
    ax.set_xlabel("shear displacement u_s (mm)")
    ax.set_ylabel("shear stress τ (kPa)")
    ax.set_title("Continuously-yielding shear law, eq. 8 with eqs 6-7 (cf. Fig. 4)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=9)
    path = os.path.join(directory, "fig4_shear_stress.png")
    plot_style.save(fig, path)
    return path


def main(argv):
    usage = ("usage: plot_joint_laws.py compression|shear CSV PNG [LABEL]\n"
             "       plot_joint_laws.py figures DIR")
    if not argv or argv[0] not in ("compression", "shear", "figures"):
        print(usage, file=sys.stderr)
        return 2
    if (argv[0] == "figures" and len(argv) != 2) or (argv[0] != "figures" and
                                                     len(argv) not in (3, 4)):
        print(usage, file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        global plot_style
        import plot_style
        plot_style.setup()
    except ImportError as error:
        print("matplotlib is not installed for %s (%s)" % (sys.executable, error), file=sys.stderr)
        return 3
    try:
        if argv[0] == "figures":
            for draw in (fig1b, fig2, fig3, fig4):
                draw(plt, argv[1])
                plt.close("all")
        else:
            label = argv[3] if len(argv) == 4 else ""
            draw = plot_compression if argv[0] == "compression" else plot_shear
            draw(plt, argv[1], argv[2], label)
    except (OSError, ValueError, KeyError) as error:
        print("plot_joint_laws.py: cannot plot: %s" % error, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
