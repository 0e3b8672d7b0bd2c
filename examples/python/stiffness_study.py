"""A parametric study: the joint normal stiffness k_n of a voussoir beam against its midspan
deflection, each run written as `blockdem run` would, compared with the analytical voussoir beam
(Diederichs & Kaiser 1999) with E_rm = k_n x block length for rigid blocks.
Usage: stiffness_study.py --out DIR [--short]"""
import argparse
import csv
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import blockdem as bd  # noqa: E402

G = 9.81
BLOCK = 0.046    # block length, depth and width (m), the [voussoir] defaults
BLOCKS = 6
DENSITY = 1207.0  # kg/m^3


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, type=pathlib.Path)
    ap.add_argument("--short", action="store_true", help="two stiffnesses, capped steps (tests)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    stiffnesses = [5e9, 20e9] if args.short else [2.5e9, 5e9, 10e9, 20e9, 40e9]
    g_max = 5.0 if args.short else 10.0
    rows = []
    for kn in stiffnesses:
        scene = bd.Scene(title=f"voussoir beam, k_n = {kn:g} Pa/m")
        scene.settings(damping=0.7, contact_mode="boon2012", rounding_distance=2e-4)
        scene.voussoir(beam="full", blocks=BLOCKS, g_levels=[g_max],
                       normal={"law": "linear", "stiffness": kn},
                       shear={"law": "linear", "stiffness": kn / 10, "friction_deg": 40})
        scenario = scene.build()
        if args.short:
            scenario.limit_steps(4000)
        r = bd.run(scenario, args.out / f"kn_{kn:g}")
        dem_mm = r["summary"].get("midspan_deflection_mm", float("nan"))
        analytic = bd.analytic_voussoir(span=BLOCKS * BLOCK, depth=BLOCK, density=DENSITY,
                                        gravity=g_max * G, modulus=kn * BLOCK)
        dk_mm = analytic["midspan_deflection_m"] * 1e3
        rows.append((kn, r["status"], dem_mm, dk_mm))
        print(f"k_n = {kn:8.3g} Pa/m: {r['status']}, midspan deflection {dem_mm:.4f} mm "
              f"(analytical {dk_mm:.4f} mm)")

    with open(args.out / "stiffness_study.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["normal_stiffness_Pa_m", "status", "dem_midspan_mm", "analytic_midspan_mm"])
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog([r[0] for r in rows], [r[2] for r in rows], "o-", label="DEM")
    ax.loglog([r[0] for r in rows], [r[3] for r in rows], "s--", label="Diederichs & Kaiser")
    ax.set_xlabel("joint normal stiffness k_n (Pa/m)")
    ax.set_ylabel(f"midspan deflection at {g_max:g} g (mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out / "stiffness_study.png", dpi=120)
    print(f"wrote {args.out / 'stiffness_study.csv'} and {args.out / 'stiffness_study.png'}")


if __name__ == "__main__":
    main()
