#!/usr/bin/env python3
"""Synthetic laboratory data for `blockdem calibrate` (docs/calibration.md), from known joint laws.

The files are SYNTHETIC: every one opens with '#' comment lines saying so and naming this script,
the model, its parameters, the noise and the seed. They stand in for the laboratory tests the paper
calibrates its laws from (Boon, Houlsby & Utili 2015, Figs 1-4; "eq N" is that paper's equation N),
for the documentation and the tests. Pure Python standard library: runs with any python3.

  normal  column compression test (Fig 1): a column of blocks with `joints` equivalent joints and
          intact blocks of modulus E, total height H, loaded in steps of stress sigma. Measured
          displacement d = sigma H / E + joints * u(sigma), with u the closure of the joint law
          sigma = a [exp(b u) - 1] (eqs 3-4), i.e. u = ln(1 + sigma / a) / b.
          Columns: stress_Pa, displacement_m.
  shear   direct shear tests at several normal stresses, monotonic shear displacement u from 0.
          --model degrading: eq 5 integrated, tau = k_i (u - u^2 / (2 u_peak)) for u < u_peak and
            tau = k_i u_peak / 2 beyond (the stiffness k_s = dtau/du of eq 5 reaches zero at
            u_peak); no Mohr-Coulomb cap. k_i = A sigma_n^B (eq 7), u_peak = C sigma_n^D (eq 6).
          --model cy: the continuously-yielding law (eq 8 with the Appendix's plastic slip beta)
            along monotonic shear at constant normal stress, in closed form:
            tau = mu(beta) sigma_n, mu(beta) = tan(phi) [1 - exp(-beta / u_peak)],
            u = beta + tau / k_i (elastic part with stiffness k_i = A sigma_n^B); beta is found
            for each u by bisection to machine precision. Independent of the C++ kernel.
          Columns: normal_stress_Pa, shear_displacement_m, shear_stress_Pa.

Noise: each measured value (displacement_m, resp. shear_stress_Pa) is multiplied by (1 + f z),
z standard normal from random.Random(seed), f = --noise (0 gives exact data). The controlled
quantities (stress_Pa, normal_stress_Pa, shear_displacement_m) are exact.

Examples:
  python3 tools/make_synthetic_calibration_data.py normal --noise 0.02 --out column.csv
  python3 tools/make_synthetic_calibration_data.py shear --model cy --noise 0.02 --out cy.csv
"""

import argparse
import math
import random
import sys

SCRIPT = "tools/make_synthetic_calibration_data.py"


def positive(text):
    value = float(text)
    if not (value > 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError("must be positive and finite, got %s" % text)
    return value


def non_negative(text):
    value = float(text)
    if not (value >= 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError("must be zero or positive and finite, got %s" % text)
    return value


def point_count(text):
    value = int(text)
    if value < 2:
        raise argparse.ArgumentTypeError("must be at least 2, got %s" % text)
    return value


def stress_list(text):
    values = [positive(item) for item in text.split(",") if item.strip()]
    if not values:
        raise argparse.ArgumentTypeError("needs at least one normal stress")
    return values


def noisy(value, noise, rng):
    """value (1 + noise z), z standard normal."""
    return value * (1.0 + noise * rng.gauss(0.0, 1.0)) if noise > 0.0 else value


def column_rows(args, rng):
    rows = []
    for j in range(args.points):
        stress = args.max_stress * j / (args.points - 1)
        closure = math.log1p(stress / args.a) / args.b
        displacement = stress * args.height / args.modulus + args.joints * closure
        rows.append((stress, noisy(displacement, args.noise, rng)))
    return rows


def degrading_stress(stiffness, peak, u):
    """Eq 5 integrated along monotonic loading: tau (Pa) at shear displacement u (m)."""
    if u >= peak:
        return 0.5 * stiffness * peak
    return stiffness * (u - u * u / (2.0 * peak))


def cy_stress(stiffness, peak, mu0, sigma, u):
    """Continuously-yielding law at constant sigma: tau (Pa) at total shear displacement u (m)."""

    def mu(beta):
        return mu0 * -math.expm1(-beta / peak)

    # g(beta) = beta + mu(beta) sigma / k - u is increasing, g(0) = -u <= 0, g(u) >= 0.
    low, high = 0.0, u
    for _ in range(200):
        mid = 0.5 * (low + high)
        if mid <= low or mid >= high:
            break
        if mid + mu(mid) * sigma / stiffness - u < 0.0:
            low = mid
        else:
            high = mid
    return mu(0.5 * (low + high)) * sigma


def shear_rows(args, rng):
    mu0 = math.tan(math.radians(args.friction_deg))
    factor = args.max_displacement_factor
    rows = []
    for sigma in args.normal_stresses:
        stiffness = args.stiffness_coefficient * sigma ** args.stiffness_exponent
        peak = args.peak_coefficient * sigma ** args.peak_exponent
        for j in range(args.points):
            u = factor * peak * j / (args.points - 1)
            if args.model == "degrading":
                tau = degrading_stress(stiffness, peak, u)
            else:
                tau = cy_stress(stiffness, peak, mu0, sigma, u)
            rows.append((sigma, u, noisy(tau, args.noise, rng)))
    return rows


def header(args, argv):
    lines = ["SYNTHETIC DATA, not laboratory measurements. Source: %s (blockdem)" % SCRIPT,
             "command: %s %s" % (SCRIPT, " ".join(argv))]
    if args.test == "normal":
        lines.append(
            "model: column compression, joint law sigma = a [exp(b u) - 1] (eqs 3-4) with "
            "a = %r Pa, b = %r 1/m; d = sigma H / E + joints u; E = %r Pa, H = %r m, joints = %d"
            % (args.a, args.b, args.modulus, args.height, args.joints))
        lines.append("loading: %d stresses from 0 to %r Pa" % (args.points, args.max_stress))
        measured = "displacement_m"
    else:
        if args.model == "degrading":
            lines.append("model: degrading shear, eq 5 integrated, tau = k_i (u - u^2/(2 u_peak)) "
                         "for u < u_peak, k_i u_peak / 2 beyond; no Mohr-Coulomb cap")
        else:
            lines.append("model: continuously yielding, eq 8, mu = tan(phi) [1 - exp(-beta/u_peak)],"
                         " u = beta + tau / k_i, monotonic shear at constant normal stress; "
                         "friction_deg = %r" % args.friction_deg)
        lines.append(
            "power laws: k_i = A sigma_n^B (eq 7), u_peak = C sigma_n^D (eq 6); "
            "stiffness_coefficient A = %r, stiffness_exponent B = %r, peak_coefficient C = %r, "
            "peak_exponent D = %r" % (args.stiffness_coefficient, args.stiffness_exponent,
                                      args.peak_coefficient, args.peak_exponent))
        lines.append("loading: normal stresses %s Pa, %d points per curve from u = 0 to %s u_peak"
                     % (",".join(repr(s) for s in args.normal_stresses), args.points,
                        repr(args.max_displacement_factor)))
        measured = "shear_stress_Pa"
    if args.noise > 0.0:
        lines.append("noise: each %s multiplied by (1 + %r z), z standard normal, "
                     "random.Random(%d)" % (measured, args.noise, args.seed))
    else:
        lines.append("noise: none (exact values)")
    return lines


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description="Write synthetic calibration data (clearly labelled) from known joint laws.",
        epilog="See the module docstring and docs/calibration.md.")
    sub = parser.add_subparsers(dest="test", required=True)

    normal = sub.add_parser("normal", help="column compression test (stress_Pa, displacement_m)")
    normal.add_argument("--a", type=positive, default=0.5405e5, help="a of eq 3-4 (Pa)")
    normal.add_argument("--b", type=positive, default=3.7e4, help="b of eq 3-4 (1/m)")
    normal.add_argument("--modulus", type=positive, default=5.6e9, help="intact E (Pa)")
    normal.add_argument("--height", type=positive, default=0.138, help="column height H (m)")
    normal.add_argument("--joints", type=int, default=3, help="equivalent joints (-)")
    normal.add_argument("--max-stress", type=positive, default=1e6, help="largest stress (Pa)")
    normal.add_argument("--points", type=point_count, default=25, help="number of rows")

    shear = sub.add_parser("shear", help="direct shear tests at several normal stresses")
    shear.add_argument("--model", choices=["degrading", "cy"], default="degrading")
    shear.add_argument("--stiffness-coefficient", type=positive, default=1.9e6, help="A of eq 7")
    shear.add_argument("--stiffness-exponent", type=non_negative, default=0.7, help="B of eq 7")
    shear.add_argument("--peak-coefficient", type=positive, default=2e-6, help="C of eq 6")
    shear.add_argument("--peak-exponent", type=non_negative, default=0.213, help="D of eq 6")
    shear.add_argument("--friction-deg", type=positive, default=40.0, help="phi of eq 8 (deg)")
    shear.add_argument("--normal-stresses", type=stress_list,
                       default=[1e4, 3e4, 1e5, 3e5, 1e6], help="comma-separated list (Pa)")
    shear.add_argument("--points", type=point_count, default=40, help="rows per curve")
    shear.add_argument("--max-displacement-factor", type=positive, default=None,
                       help="largest u as a multiple of u_peak (default 2 degrading, 5 cy)")

    for p in (normal, shear):
        p.add_argument("--noise", type=non_negative, default=0.0,
                       help="relative noise f on the measured column (0: exact)")
        p.add_argument("--seed", type=int, default=1, help="seed of random.Random")
        p.add_argument("--out", required=True, help="CSV file to write")
    args = parser.parse_args(argv)
    if args.test == "normal" and args.joints < 1:
        parser.error("--joints must be at least 1, got %d" % args.joints)
    if args.test == "shear":
        if not 0.0 < args.friction_deg < 90.0:
            parser.error("--friction-deg must lie in (0, 90), got %r" % args.friction_deg)
        if args.max_displacement_factor is None:
            args.max_displacement_factor = 2.0 if args.model == "degrading" else 5.0
    return args


def main(argv):
    args = parse_arguments(argv)
    rng = random.Random(args.seed)
    if args.test == "normal":
        columns = ["stress_Pa", "displacement_m"]
        rows = column_rows(args, rng)
    else:
        columns = ["normal_stress_Pa", "shear_displacement_m", "shear_stress_Pa"]
        rows = shear_rows(args, rng)
    with open(args.out, "w", encoding="ascii") as out:
        for line in header(args, argv):
            out.write("# %s\n" % line)
        out.write(",".join(columns) + "\n")
        for row in rows:
            out.write(",".join(repr(float(v)) for v in row) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
