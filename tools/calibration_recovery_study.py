#!/usr/bin/env python3
"""How well `blockdem calibrate` recovers known joint laws from noisy synthetic data.

For each seed: make a synthetic data set with tools/make_synthetic_calibration_data.py (known
parameters, relative noise), run `blockdem calibrate normal|shear|cy --no-figures --out DIR`, read
DIR/calibration.json and record the relative error of every fitted parameter. Prints, per
parameter, the RMS and the largest relative error over the seeds. Pure Python standard library.

Usage:
  calibration_recovery_study.py --blockdem build/blockdem [--seeds 40] [--noise 0.02]
      [--normal-points 200] [--shear-points 200]
The defaults are the designs of the noisy-data tests in tests/unit/calibration/ (see
docs/calibration.md for the numbers this prints).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
GENERATOR = os.path.join(HERE, "make_synthetic_calibration_data.py")

# The generator's defaults: eq 4 and eqs 6-8 of Boon, Houlsby & Utili (2015).
TRUE_NORMAL = {"a": 0.5405e5, "b": 3.7e4}
TRUE_SHEAR = {"stiffness_coefficient": 1.9e6, "stiffness_exponent": 0.7,
              "peak_coefficient": 2e-6, "peak_exponent": 0.213}
TRUE_FRICTION_DEG = 40.0


def run(command):
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(command), result.stderr))


def calibrate(blockdem, work, test, generator_args, calibrate_args):
    data = os.path.join(work, test + ".csv")
    out = os.path.join(work, test + "_out")
    run([sys.executable, GENERATOR] + generator_args + ["--out", data])
    run([blockdem, "calibrate", test, "--data", data, "--no-figures", "--out", out] + calibrate_args)
    with open(os.path.join(out, "calibration.json"), encoding="utf-8") as f:
        return json.load(f)


def relative(value, truth):
    return (value - truth) / truth


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blockdem", required=True, help="path of the blockdem program")
    parser.add_argument("--seeds", type=int, default=40)
    parser.add_argument("--noise", type=float, default=0.02)
    parser.add_argument("--normal-points", type=int, default=200)
    parser.add_argument("--shear-points", type=int, default=200)
    args = parser.parse_args(argv)
    noise = ["--noise", repr(args.noise)]
    errors = {}

    def record(key, value):
        errors.setdefault(key, []).append(value)

    with tempfile.TemporaryDirectory() as work:
        for seed in range(1, args.seeds + 1):
            s = ["--seed", str(seed)]
            n = calibrate(args.blockdem, work, "normal",
                          ["normal", "--points", str(args.normal_points)] + noise + s,
                          ["--modulus", "5.6e9", "--height", "0.138", "--joints", "3"])
            record("normal a", relative(n["exponential"]["a_Pa"], TRUE_NORMAL["a"]))
            record("normal b", relative(n["exponential"]["b_per_m"], TRUE_NORMAL["b"]))
            d = calibrate(args.blockdem, work, "shear",
                          ["shear", "--model", "degrading", "--points", str(args.shear_points)]
                          + noise + s, [])
            laws = {"stiffness_coefficient": d["initial_stiffness_eq7"]["coefficient"],
                    "stiffness_exponent": d["initial_stiffness_eq7"]["exponent"],
                    "peak_coefficient": d["peak_displacement_eq6"]["coefficient"],
                    "peak_exponent": d["peak_displacement_eq6"]["exponent"]}
            for key, value in laws.items():
                record("shear " + key, relative(value, TRUE_SHEAR[key]))
            c = calibrate(args.blockdem, work, "cy",
                          ["shear", "--model", "cy", "--points", str(args.shear_points)]
                          + noise + s,
                          ["--stiffness-coefficient", "1.9e6", "--stiffness-exponent", "0.7"])
            record("cy friction_deg", relative(c["friction_deg"], TRUE_FRICTION_DEG))
            record("cy peak_coefficient", relative(c["peak_coefficient"],
                                                   TRUE_SHEAR["peak_coefficient"]))
            record("cy peak_exponent", relative(c["peak_exponent"], TRUE_SHEAR["peak_exponent"]))
    print("relative errors over %d seeds, noise %g, %d normal rows, %d rows per shear curve"
          % (args.seeds, args.noise, args.normal_points, args.shear_points))
    print("%-32s %10s %10s" % ("parameter", "RMS", "max |e|"))
    for key, values in errors.items():
        rms = math.sqrt(sum(v * v for v in values) / len(values))
        print("%-32s %9.2f%% %9.2f%%" % (key, 100 * rms, 100 * max(abs(v) for v in values)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
