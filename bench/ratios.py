#!/usr/bin/python3
"""Medians of the narrow-phase benchmarks and the CLP-path / fast-path ratios from one run.

Usage:
  blockdem_bench --benchmark_filter=Narrow --benchmark_repetitions=10 \
      --benchmark_report_aggregates_only=true --benchmark_out=narrow.json
  /usr/bin/python3 bench/ratios.py narrow.json

Prints, per scene, the median real time per candidate pair (ns) of the fast path and of the
CLP path, cold and warm, and the ratios CLP / fast (cold / cold, warm / warm, and CLP cold over
fast warm: a general solver from scratch per step against the warm-started fast path).
"""
import json
import sys


def medians(path):
    with open(path) as f:
        report = json.load(f)
    out = {}
    for b in report["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        name = b["run_name"]  # e.g. BM_Narrow_FastWarm/1
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
        out[name] = (b["real_time"] * scale, b.get("label", ""))
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    m = medians(sys.argv[1])
    scenes = sorted({name.split("/")[1] for name in m if name.startswith("BM_Narrow_")})
    print("| scene | fast cold (ns) | fast warm (ns) | CLP cold (ns) | CLP warm (ns) "
          "| CLP/fast cold | CLP/fast warm | CLP cold / fast warm |")
    print("|---|---|---|---|---|---|---|---|")
    for s in scenes:
        def get(kind):
            return m.get(f"BM_Narrow_{kind}/{s}", (float("nan"), ""))
        fc, label = get("FastCold")
        fw, _ = get("FastWarm")
        cc, _ = get("ClpCold")
        cw, _ = get("ClpWarm")
        print(f"| {label} | {fc:.0f} | {fw:.0f} | {cc:.0f} | {cw:.0f} "
              f"| {cc / fc:.0f} | {cw / fw:.1f} | {cc / fw:.0f} |")


if __name__ == "__main__":
    main()
