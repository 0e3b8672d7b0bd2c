#!/usr/bin/env python3
"""Figures of `blockdem calibrate normal|shear|cy --out DIR`: data against the fitted laws.

Usage: calibration_plot.py DIR
Reads DIR/calibration.json (which command wrote it) and the fit CSVs next to it, writes PNGs into
DIR and prints the name of every PNG written, one per line. Exit codes: 0 written, 2 bad input,
3 matplotlib unavailable (the calibration itself is unaffected: JSON and CSVs are already written).
Run with /usr/bin/python3 on Debian (its python3-matplotlib). Figure numbers refer to Boon, Houlsby
& Utili (2015), whose Figs 1-4 these mirror.
"""

import csv
import json
import math
import os
import sys


def read_csv(path):
    with open(path, newline="", encoding="ascii") as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in (rows[0].keys() if rows else [])}


def by_stress(table):
    """Splits a table into {normal_stress_Pa: {column: values}} in file order."""
    out = {}
    for i, s in enumerate(table["normal_stress_Pa"]):
        group = out.setdefault(s, {key: [] for key in table})
        for key in table:
            group[key].append(table[key][i])
    return out


def title_suffix(report):
    return " (SYNTHETIC data)" if report["data"].get("synthetic") else ""


def grid_axes(plt, count, width=4.2, height=3.2):
    columns = min(3, count)
    rows = int(math.ceil(count / columns))
    fig, axes = plt.subplots(rows, columns, figsize=(width * columns, height * rows), squeeze=False)
    flat = [ax for row in axes for ax in row]
    for ax in flat[count:]:
        ax.set_visible(False)
    return fig, flat[:count]


def plot_normal(plt, directory, report):
    points = read_csv(os.path.join(directory, "normal_fit_points.csv"))
    curve = read_csv(os.path.join(directory, "normal_fit_curve.csv"))
    e = report["exponential"]
    lin = report["linear"]
    mpa = [s / 1e6 for s in points["stress_Pa"]]
    fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(15, 4.4))
    ax0.plot([d * 1e6 for d in points["displacement_m"]], mpa, "o", ms=3, label="measured total")
    ax0.plot([d * 1e6 for d in points["intact_displacement_m"]], mpa, "-",
             label="intact blocks, sigma H / E")
    ax0.set_xlabel("column shortening (um)")
    ax0.set_ylabel("axial stress (MPa)")
    ax0.set_title("(a) column test (cf. Fig 1(a))")
    ax0.legend(fontsize=8)
    ax1.plot([u * 1e6 for u in points["joint_closure_m"]], mpa, "o", ms=3,
             label="data: (d - sigma H/E) / %d" % report["inputs"]["joints"])
    ax1.plot([u * 1e6 for u in curve["joint_closure_m"]],
             [s / 1e6 for s in curve["exponential_stress_Pa"]], "-",
             label="a[exp(bu)-1]: a = %.4g Pa, b = %.4g 1/m, R2 = %.4f"
             % (e["a_Pa"], e["b_per_m"], e["fit"]["r_squared"]))
    ax1.plot([u * 1e6 for u in curve["joint_closure_m"]],
             [s / 1e6 for s in curve["linear_stress_Pa"]], "--",
             label="linear: k = %.4g Pa/m, R2 = %.4f"
             % (lin["stiffness_Pa_per_m"], lin["fit"]["r_squared"]))
    ax1.set_ylim(0, 1.1 * max(mpa))
    ax1.set_xlabel("joint closure u (um)")
    ax1.set_ylabel("normal stress (MPa)")
    ax1.set_title("(b) joint law (cf. Fig 1(b))")
    ax1.legend(fontsize=7)
    ax2.axhline(0.0, color="0.6", lw=0.8)
    ax2.plot(mpa, [r * 1e6 for r in points["exponential_residual_m"]], "o", ms=3,
             label="exponential")
    ax2.plot(mpa, [r * 1e6 for r in points["linear_residual_m"]], "x", ms=3, label="linear")
    ax2.set_xlabel("normal stress (MPa)")
    ax2.set_ylabel("closure residual, model - data (um)")
    ax2.set_title("(c) residuals")
    ax2.legend(fontsize=8)
    fig.suptitle("blockdem calibrate normal: " + report["data"]["file"] + title_suffix(report),
                 fontsize=10)
    plot_style.save(fig, os.path.join(directory, "normal_fit.png"))
    return ["normal_fit.png"]


def plot_shear_curves(plt, directory, report, points_name, curves_name, model_key, model_label,
                      out_name, title):
    points = by_stress(read_csv(os.path.join(directory, points_name)))
    curves = by_stress(read_csv(os.path.join(directory, curves_name)))
    fig, axes = grid_axes(plt, len(points))
    for ax, (sigma, p) in zip(axes, points.items()):
        c = curves[sigma]
        u = [x * 1e6 for x in p["shear_displacement_m"]]
        tau = [t / 1e3 for t in p["shear_stress_Pa"]]
        if "used_in_eq5_fit" in p:
            used = [i for i, flag in enumerate(p["used_in_eq5_fit"]) if flag > 0.5]
            unused = [i for i, flag in enumerate(p["used_in_eq5_fit"]) if flag <= 0.5]
            ax.plot([u[i] for i in used], [tau[i] for i in used], "o", ms=2.5, label="data (fitted)")
            if unused:
                ax.plot([u[i] for i in unused], [tau[i] for i in unused], "o", ms=2.5, mfc="none",
                        label="data (after the peak)")
            ax.plot([x * 1e6 for x in c["shear_displacement_m"]],
                    [t / 1e3 for t in c["eq5_fit_stress_Pa"]], "--", lw=1.2,
                    label="eq 5 fit of this curve")
        else:
            ax.plot(u, tau, "o", ms=2.5, label="data")
        ax.plot([x * 1e6 for x in c["shear_displacement_m"]],
                [t / 1e3 for t in c[model_key]], "-", lw=1.2, label=model_label)
        ax.set_title("sigma_n = %.4g kPa" % (sigma / 1e3), fontsize=9)
        ax.set_xlabel("shear displacement (um)")
        ax.set_ylabel("shear stress (kPa)")
    axes[0].legend(fontsize=7)
    fig.suptitle(title + ": " + report["data"]["file"] + title_suffix(report), fontsize=10)
    plot_style.save(fig, os.path.join(directory, out_name))
    return [out_name]


def plot_shear_stiffness(plt, directory, report):
    points = by_stress(read_csv(os.path.join(directory, "shear_fit_points.csv")))
    curves = by_stress(read_csv(os.path.join(directory, "shear_fit_curves.csv")))
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    for sigma, p in points.items():
        u = p["shear_displacement_m"]
        tau = p["shear_stress_Pa"]
        mid = [0.5 * (u[i] + u[i + 1]) * 1e6 for i in range(len(u) - 1)]
        slope = [(tau[i + 1] - tau[i]) / (u[i + 1] - u[i]) / 1e9 for i in range(len(u) - 1)]
        line, = ax.plot([x * 1e6 for x in curves[sigma]["shear_displacement_m"]],
                        [k / 1e9 for k in curves[sigma]["eq5_fit_stiffness_Pa_per_m"]], "-",
                        label="eq 5, sigma_n = %.4g kPa" % (sigma / 1e3))
        ax.plot(mid, slope, ".", ms=2, color=line.get_color(), alpha=0.5)
    top = max(max(c["eq5_fit_stiffness_Pa_per_m"]) for c in curves.values()) / 1e9
    ax.set_ylim(-0.15 * top, 1.2 * top)  # differences of noisy data scatter far beyond this
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("shear displacement (um)")
    ax.set_ylabel("shear stiffness dtau/du (GPa/m)")
    ax.set_title("Instantaneous shear stiffness (cf. Fig 2): eq 5 lines, data differences (dots)"
                 + title_suffix(report), fontsize=9)
    ax.legend(fontsize=7)
    plot_style.save(fig, os.path.join(directory, "shear_stiffness.png"))
    return ["shear_stiffness.png"]


def plain_log_ticks(ax):
    """Tick labels as plain numbers (%g) on both logarithmic axes. Minor ticks are labelled on an
    axis spanning less than a decade (which may hold no major tick), else only at 2 and 5 times a
    power of ten when the axis spans less than three decades."""
    from matplotlib.ticker import FormatStrFormatter, FuncFormatter
    for axis, limits in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        decades = math.log10(max(limits) / min(limits))

        def minor(value, _position, decades=decades):
            mantissa = round(value / 10 ** math.floor(math.log10(value) + 1e-9))
            return "%g" % value if decades < 1.0 or (decades < 3.0 and mantissa in (2, 5)) else ""

        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(FuncFormatter(minor))
        axis.set_tick_params(which="minor", labelsize=7)


def power_law_panel(ax, sigma, values, law, scale, ylabel, label):
    lo, hi = min(sigma), max(sigma)
    xs = [lo * (hi / lo) ** (i / 50.0) for i in range(51)]
    ref = law["reference_stress_Pa"]
    ref_value = [v for k, v in law.items() if k.startswith("value_at_reference_stress")][0]
    ax.loglog([s / 1e3 for s in sigma], [v * scale for v in values], "o", label="per curve")
    ax.loglog([x / 1e3 for x in xs], [ref_value * (x / ref) ** law["exponent"] * scale for x in xs],
              "-", label=label % (law["coefficient"], law["exponent"], law["r_squared_of_log"]))
    ax.set_xlabel("normal stress (kPa)")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7)
    plain_log_ticks(ax)


def plot_shear_power_laws(plt, directory, report):
    t = read_csv(os.path.join(directory, "shear_power_laws.csv"))
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.3))
    power_law_panel(ax0, t["normal_stress_Pa"], t["initial_stiffness_Pa_per_m"],
                    report["initial_stiffness_eq7"], 1e-9, "k_s,initial (GPa/m)",
                    "eq 7: A = %.4g, B = %.4g (R2 log %.4f)")
    ax0.set_title("(a) initial shear stiffness (cf. Fig 3)", fontsize=9)
    power_law_panel(ax1, t["normal_stress_Pa"], t["peak_displacement_m"],
                    report["peak_displacement_eq6"], 1e6, "u_peak (um)",
                    "eq 6: C = %.4g, D = %.4g (R2 log %.4f)")
    ax1.set_title("(b) peak displacement (x-intercepts of Fig 2)", fontsize=9)
    fig.suptitle("blockdem calibrate shear: " + report["data"]["file"] + title_suffix(report),
                 fontsize=10)
    plot_style.save(fig, os.path.join(directory, "shear_power_laws.png"))
    return ["shear_power_laws.png"]


def plot_cy_parameters(plt, directory, report):
    t = read_csv(os.path.join(directory, "cy_curve_fits.csv"))
    sigma = [s / 1e3 for s in t["normal_stress_Pa"]]
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.3))
    ax0.semilogx(sigma, t["single_curve_friction_coefficient"], "o", label="single-curve fits")
    ax0.semilogx(sigma, t["law_friction_coefficient"], "-",
                 label="calibrated mu0 = tan(%.4g deg)" % report["friction_deg"])
    values = t["single_curve_friction_coefficient"] + t["law_friction_coefficient"]
    ax0.set_ylim(0.9 * min(values), 1.1 * max(values))
    ax0.set_xlabel("normal stress (kPa)")
    ax0.set_ylabel("mu0 (-)")
    ax0.set_title("(a) friction reached at large slip (eq 8)", fontsize=9)
    ax0.legend(fontsize=7)
    ax1.loglog(sigma, [u * 1e6 for u in t["single_curve_peak_displacement_m"]], "o",
               label="single-curve fits")
    ax1.loglog(sigma, [u * 1e6 for u in t["law_peak_displacement_m"]], "-",
               label="eq 6: C = %.4g, D = %.4g" % (report["peak_coefficient"],
                                                   report["peak_exponent"]))
    ax1.set_xlabel("normal stress (kPa)")
    ax1.set_ylabel("u_peak (um)")
    ax1.set_title("(b) u_peak of eq 8", fontsize=9)
    ax1.legend(fontsize=7)
    plain_log_ticks(ax1)
    fig.suptitle("blockdem calibrate cy: " + report["data"]["file"] + title_suffix(report),
                 fontsize=10)
    plot_style.save(fig, os.path.join(directory, "cy_parameters.png"))
    return ["cy_parameters.png"]


def main(argv):
    if len(argv) != 1:
        print("usage: calibration_plot.py DIR", file=sys.stderr)
        return 2
    directory = argv[0]
    try:
        with open(os.path.join(directory, "calibration.json"), encoding="utf-8") as f:
            report = json.load(f)
    except (OSError, ValueError) as error:
        print("calibration_plot.py: cannot read %s/calibration.json: %s" % (directory, error),
              file=sys.stderr)
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
    command = report.get("command")
    if command == "calibrate normal":
        written = plot_normal(plt, directory, report)
    elif command == "calibrate shear":
        written = plot_shear_curves(plt, directory, report, "shear_fit_points.csv",
                                    "shear_fit_curves.csv", "law_stress_Pa",
                                    "calibrated degrading law (kernel)", "shear_curves.png",
                                    "blockdem calibrate shear (eqs 5-7)")
        written += plot_shear_stiffness(plt, directory, report)
        written += plot_shear_power_laws(plt, directory, report)
    elif command == "calibrate cy":
        written = plot_shear_curves(plt, directory, report, "cy_fit_points.csv",
                                    "cy_fit_curves.csv", "law_stress_Pa",
                                    "continuously-yielding law (kernel)", "cy_curves.png",
                                    "blockdem calibrate cy (eq 8, cf. Fig 4)")
        written += plot_cy_parameters(plt, directory, report)
    else:
        print("calibration_plot.py: unknown command %r in calibration.json" % command,
              file=sys.stderr)
        return 2
    for name in written:
        print(name)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
