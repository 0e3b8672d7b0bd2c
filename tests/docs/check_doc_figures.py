#!/usr/bin/env python3
"""The figures the docs quote from the shipped examples are the ones the current build prints.

Usage: check_doc_figures.py BLOCKDEM SOURCE_DIR [WORK_DIR]

Runs each example a check needs once (`blockdem run ... --no-figures`, or `blockdem keyblocks`),
then finds each quoted sentence in its doc by a pattern whose groups are the quoted numbers, and
compares each number with the run's to the digits the doc prints (one unit of its last digit, so
that a rounded and a truncated figure both pass). A sentence reworded so that its pattern no longer
matches fails too: the check and the doc change together. Standard library only (any python3).
Under the sanitizers (BLOCKDEM_TEST_SANITIZED=1) it exits 77, skipped: full runs are too slow there.
"""
import concurrent.futures
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

NUMBER = r"([0-9][0-9,]*(?:\.[0-9]+)?)"
# A strength reduction's result as `blockdem run` prints it.
SR = r"factor of safety " + NUMBER + r" \(stable at " + NUMBER + ", failed at " + NUMBER + r"\)"


def summary(run):
    with open(os.path.join(run, "summary.json")) as f:
        return json.load(f)


def fos(run):
    f = summary(run)["factor_of_safety"]
    return [f["value"], f["last_stable"], f["first_failed"]]


def key_block(run, name):
    for b in summary(run).get("key_blocks", []):
        if b["block"] == name:
            return b
    raise KeyError(f"{name} is not among the key blocks of {run}")


def removable(run, name):
    with open(os.path.join(run, "key_blocks.json")) as f:
        for b in json.load(f)["key_blocks"]:
            if b["block"] == name:
                return b
    raise KeyError(f"{name} is not among the removable blocks of {run}")


def printed(run, pattern):
    """The numbers of the first line of the run's messages (stderr) that `pattern` matches."""
    with open(run + ".stderr", encoding="utf-8") as f:
        found = re.search(pattern, f.read())
    if not found:
        raise KeyError(f"the run {run} printed no line matching /{pattern}/")
    return [float(g.replace(",", "")) for g in found.groups()]


def stage(run, name):
    for s in summary(run)["stages"]:
        if s["name"] == name:
            return s
    raise KeyError(f"no stage {name} in {run}")


def bolts_csv(run):
    with open(os.path.join(run, "bolts.csv"), newline="") as f:
        return list(csv.DictReader(f))


def displacement_mm(run, name):
    """The block's displacement (ux, uy, uz) at the last stage end, from blocks.csv (in mm)."""
    with open(os.path.join(run, "blocks.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["block"] == name]
    r = rows[-1]
    return [float(r["ux_mm"]), float(r["uy_mm"]), float(r["uz_mm"])]


def last_displacement_mm(run, name):
    """The block's displacement (x, z) at the last stage end, from blocks.csv (in mm)."""
    with open(os.path.join(run, "blocks.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["block"] == name]
    r = rows[-1]
    return [float(r["ux_mm"]), -float(r["uz_mm"])]


# (doc, pattern, run id, numbers of the run in the pattern's group order)
CHECKS = [
    ("docs/stability.md", r"prints `factor of safety " + NUMBER + "`",
     "run:planar_sliding", lambda d: fos(d)[:1]),
    ("docs/stability.md",
     r"\*\*F = " + NUMBER + r"\*\* \(last stable " + NUMBER + ", first failed " + NUMBER,
     "run:slope_fos", fos),
    ("docs/stability.md",
     r"`face_integrated` \(as shipped\) \| F = " + NUMBER + r" \(last stable " + NUMBER +
     ", first failed " + NUMBER, "run:roof_wedge", fos),
    ("docs/key-blocks.md",
     r"\| `roof_wedge.toml` \| rock_6 \| sliding_two \(J2, J3\) \| " + NUMBER + r" \| " + NUMBER +
     r" \| " + NUMBER + r" \(" + NUMBER + "–" + NUMBER + r"\) \|", "run:roof_wedge",
     lambda d: [removable(d + "-keyblocks", "rock_6")["volume_m3"],
                removable(d + "-keyblocks", "rock_6")["factor_of_safety"]] + fos(d)),
    ("docs/key-blocks.md",
     r"\| `slope_fos.toml` \| rock_21 \| sliding_two \(J1, J2\) \| " + NUMBER + r" \| " + NUMBER +
     r" \| " + NUMBER + r" \(" + NUMBER + "–" + NUMBER + r"\) \|", "run:slope_fos",
     lambda d: [removable(d + "-keyblocks", "rock_21")["volume_m3"],
                removable(d + "-keyblocks", "rock_21")["factor_of_safety"]] + fos(d)),
    ("docs/key-blocks.md",
     r"\| `tunnel.toml` \| rock_49 \| falling \| " + NUMBER + r" \| 0 \|", "run:tunnel",
     lambda d: [removable(d + "-keyblocks", "rock_49")["volume_m3"]]),
    ("docs/key-blocks.md",
     r"\| `tunnel.toml` \| rock_29 \| sliding_two \(J3, roller\) \| " + NUMBER + r" \| " + NUMBER,
     "run:tunnel", lambda d: [removable(d + "-keyblocks", "rock_29")["volume_m3"],
                              removable(d + "-keyblocks", "rock_29")["factor_of_safety"]]),
    ("docs/rock-mass.md", r"into " + NUMBER + r" blocks \(36 cuts merged back", "run:tunnel",
     lambda d: [summary(d)["blocks"]]),
    ("docs/rock-mass.md",
     r"`rock_49` \(centroid at x = " + NUMBER + ", y = " + NUMBER + ", z = " + NUMBER +
     r" m before excavation, east of the crown\) drops\s+" + NUMBER +
     r" m in the 0.4 s, still falling at " + NUMBER + " m/s", "run:tunnel",
     lambda d: key_block(d, "rock_49")["centroid_at_start_m"] +
     [key_block(d, "rock_49")["displacement_m"], key_block(d, "rock_49")["speed_m_s"]]),
    ("docs/rock-mass.md",
     r"`rock_21` moves " + NUMBER + " mm east and " + NUMBER + " mm down", "run:slope",
     lambda d: last_displacement_mm(d, "rock_21")),
    ("docs/rock-mass.md",
     r"`key_blocks` in `summary.json` lists\s+`rock_21` alone \(" + NUMBER + " m³, " + NUMBER +
     " mm\\)", "run:slope",
     lambda d: [key_block(d, "rock_21")["volume_m3"],
                1e3 * key_block(d, "rock_21")["displacement_m"]]),
    ("docs/rock-mass.md", r"`rock_21`, sliding on J1 and J2,\s+F = " + NUMBER, "run:slope",
     lambda d: [removable(d + "-keyblocks", "rock_21")["factor_of_safety"]]),
    # Ground stress: the deep tunnel and the staged slope.
    ("docs/ground-stress.md", r"On this build it completes in " + NUMBER + " steps",
     "run:tunnel_deep", lambda d: [summary(d)["steps"]]),
    ("docs/ground-stress.md", r"\| rock_76 \| " + NUMBER + r" east \(into the tunnel\), " +
     NUMBER + " down", "run:tunnel_deep",
     lambda d: [displacement_mm(d, "rock_76")[0], -displacement_mm(d, "rock_76")[2]]),
    ("docs/ground-stress.md", r"\| rock_65 \| " + NUMBER + r" west \(into the tunnel\), " +
     NUMBER + " down", "run:tunnel_deep",
     lambda d: [-displacement_mm(d, "rock_65")[0], -displacement_mm(d, "rock_65")[2]]),
    ("docs/ground-stress.md", r"\| rock_87 \| " + NUMBER + " down", "run:tunnel_deep",
     lambda d: [-displacement_mm(d, "rock_87")[2]]),
    ("docs/ground-stress.md", r"\| rock_37 \| " + NUMBER + " up", "run:tunnel_deep",
     lambda d: [displacement_mm(d, "rock_37")[2]]),
    ("docs/ground-stress.md", r"\| rock_67 \| " + NUMBER + " east, " + NUMBER + " down",
     "run:tunnel_deep",
     lambda d: [displacement_mm(d, "rock_67")[0], -displacement_mm(d, "rock_67")[2]]),
    ("docs/ground-stress.md", r"The horizontal convergence of the walls is " + NUMBER + " mm",
     "run:tunnel_deep",
     lambda d: [displacement_mm(d, "rock_76")[0] - displacement_mm(d, "rock_65")[0]]),
    ("docs/ground-stress.md", r"prints `" + SR + r"` after " + NUMBER + r"\s+trials",
     "run:slope_staged",
     lambda d: fos(d) + [len(summary(d)["factor_of_safety"]["trials"])]),
    # Water and earthquakes: the three factors of safety of the slope with water.
    ("docs/water-and-earthquakes.md", r"'factor of safety, dry': " + SR,
     "run:slope_water", lambda d: printed(d, r"'factor of safety, dry': " + SR)),
    ("docs/water-and-earthquakes.md", r"'factor of safety, half full': " + SR,
     "run:slope_water", lambda d: printed(d, r"'factor of safety, half full': " + SR)),
    ("docs/water-and-earthquakes.md", r"'factor of safety, half full, k_h = 0.1': " + SR,
     "run:slope_water",
     lambda d: printed(d, r"'factor of safety, half full, k_h = 0.1': " + SR)),
    # Support: the bolted roof wedge and the bolted tunnel.
    ("docs/support.md", r"reaches equilibrium after " + NUMBER + r" steps\); the wedge\s+"
     r"\(`rock_6` in `blocks.csv`\) moves " + NUMBER + " mm east and " + NUMBER + " mm down",
     "run:roof_wedge_bolted",
     lambda d: [summary(d)["stages"][-1]["steps"], displacement_mm(d, "rock_6")[0],
                -displacement_mm(d, "rock_6")[2]]),
    ("docs/support.md", r"wedge F = " + NUMBER + r" by block theory, and " + NUMBER + " kN",
     "run:roof_wedge_bolted",
     lambda d: [removable(d + "-keyblocks", "rock_6")["factor_of_safety"],
                removable(d + "-keyblocks", "rock_6")["support_force_N"] / 1e3]),
    ("docs/support.md", r"warns that " + NUMBER + " of " + NUMBER + r" bolts cross no joint"
     r"[^.]*, installs " + NUMBER, "run:tunnel_bolted",
     lambda d: printed(d, r"(\d+) of (\d+) bolts") + [summary(d)["bolts"]["installed"]]),
    ("docs/support.md", r"The largest\s+tendon force in `bolts.csv` is " + NUMBER +
     r" kN \(bolt `tunnel-28`\), the largest dowel shear " + NUMBER + " kN",
     "run:tunnel_bolted",
     lambda d: [max(abs(float(r["axial_force_N"])) for r in bolts_csv(d)) / 1e3,
                max(abs(float(r["shear_force_N"])) for r in bolts_csv(d)) / 1e3]),
    ("docs/support.md", r"Unbolted, `rock_21` slides " + NUMBER + " mm east and " + NUMBER +
     " mm down", "run:slope", lambda d: last_displacement_mm(d, "rock_21")),
    ("docs/support.md", r"Bolted, the run warns that " + NUMBER + " of " + NUMBER +
     r" pattern bolts[^.]*, installs " + NUMBER + r" bolts, and completes\s+with every bolt "
     r"intact and no key block: `rock_21` moves " + NUMBER + " mm east and " + NUMBER +
     " mm down", "run:slope_bolted",
     lambda d: printed(d, r"(\d+) of (\d+) bolts") + [summary(d)["bolts"]["intact"]] +
     last_displacement_mm(d, "rock_21")),
    ("docs/support.md", r"The\s+largest tendon force in `bolts.csv` is " + NUMBER +
     " kN and the largest dowel shear " + NUMBER + " kN", "run:slope_bolted",
     lambda d: [max(abs(float(r["axial_force_N"])) for r in bolts_csv(d)) / 1e3,
                max(abs(float(r["shear_force_N"])) for r in bolts_csv(d)) / 1e3]),
]


# The examples that take longest (their wall seconds in this check on 30 November 2026, beside
# other tests: 137, 97, 74, 59, 44 and 28), started first so that the two runs side by side end
# close together (in name order, the two longest came last); the others follow in name order.
LONGEST_FIRST = ["tunnel_bolted", "tunnel", "slope_fos", "slope_water", "slope_bolted",
                 "tunnel_deep"]

# The examples whose block-theory list (`blockdem keyblocks`, in RUN-keyblocks) a check reads.
WITH_KEYBLOCKS = {"roof_wedge", "slope_fos", "tunnel", "slope", "roof_wedge_bolted"}


def run_example(blockdem, source, work, name):
    scenario = os.path.join(source, "scenarios", "examples", name + ".toml")
    out = os.path.join(work, name)
    r = subprocess.run([blockdem, "run", scenario, "--out", out, "--no-figures", "--threads", "1"],
                       capture_output=True, text=True)
    with open(out + ".stderr", "w", encoding="utf-8") as f:
        f.write(r.stderr)
    if r.returncode not in (0, 3):
        raise RuntimeError(f"blockdem run {name}: exit {r.returncode}\n{r.stderr}")
    if name not in WITH_KEYBLOCKS:
        return out
    k = subprocess.run([blockdem, "keyblocks", scenario, "--out", out + "-keyblocks", "--quiet"],
                       capture_output=True, text=True)
    if k.returncode != 0:
        raise RuntimeError(f"blockdem keyblocks {name}: exit {k.returncode}\n{k.stderr}")
    return out


def agrees(quoted, actual):
    """The quoted figure is the actual one to the digits it prints (one unit of the last)."""
    text = quoted.replace(",", "")
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(float(text) - actual) <= 10.0 ** -decimals * 1.0000001


def main(argv):
    if os.environ.get("BLOCKDEM_TEST_SANITIZED") == "1":
        print("skipped under the sanitizers: full runs of the examples")
        return 77
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    blockdem, source = argv[1], argv[2]
    work = argv[3] if len(argv) > 3 else tempfile.mkdtemp(prefix="blockdem_doc_figures_")
    names = sorted({run.split(":", 1)[1] for _, _, run, _ in CHECKS},
                   key=lambda n: (LONGEST_FIRST.index(n) if n in LONGEST_FIRST else
                                  len(LONGEST_FIRST), n))
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        outs = dict(zip(names, pool.map(lambda n: run_example(blockdem, source, work, n), names)))
    failures = []
    for doc, pattern, run, numbers in CHECKS:
        with open(os.path.join(source, doc), encoding="utf-8") as f:
            text = f.read()
        found = re.search(pattern, text)
        if not found:
            failures.append(f"{doc}: no text matches /{pattern}/ (reworded? change the check too)")
            continue
        actual = numbers(outs[run.split(":", 1)[1]])
        for quoted, value in zip(found.groups(), actual):
            if not agrees(quoted, value):
                failures.append(f"{doc}: quotes {quoted} where the build gives {value:.6g} "
                                f"({run}; in '{found.group(0)}')")
    for line in failures:
        print("stale: " + line)
    print(f"{len(CHECKS) - len(failures)} of {len(CHECKS)} quoted figures checked against "
          f"{len(names)} example runs")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
