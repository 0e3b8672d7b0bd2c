#!/usr/bin/env python3
"""Seconds per step of a run continued from a checkpoint (the settled 1e5 pile, bench/README.md).

Restarts SCENARIO from CHECKPOINT with `blockdem run --restart`, reads the progress lines that
the run prints to stderr every 5 s when stderr is not a terminal ("step N, ..."), and after
SECONDS stops the run and prints the seconds per step between the second progress line and the
last one: the checkpoint's load and the first steps after it are left out. Before and after, the
same fixed loop pinned to each core (bench/core_check.py) says whether the cores ran alike: on a
shared virtual machine one of them can be much slower for minutes, which a two-thread timing
feels.

    python3 bench/settled_rate.py build/blockdem pile.toml settle/checkpoint.bdck 1 60 /tmp/rate

Standard library only (runs with any python3).
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from core_check import core_times  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("binary", help="the blockdem program")
    p.add_argument("scenario", help="the scenario the checkpoint was written by")
    p.add_argument("checkpoint", help="a checkpoint.bdck of that scenario")
    p.add_argument("threads", type=int)
    p.add_argument("seconds", type=float, help="how long to let the run go on")
    p.add_argument("out", help="an output folder (emptied first)")
    a = p.parse_args()
    before = core_times()
    shutil.rmtree(a.out, ignore_errors=True)
    run = subprocess.Popen([a.binary, "run", a.scenario, "--out", a.out, "--threads",
                            str(a.threads), "--restart", a.checkpoint],
                           stderr=subprocess.PIPE, text=True)
    start = time.monotonic()
    points = []  # (time read, step)
    for line in run.stderr:
        m = re.search(r"step (\d+),", line)
        if m:
            points.append((time.monotonic(), int(m.group(1))))
        if time.monotonic() - start > a.seconds:
            break
    run.send_signal(signal.SIGKILL)
    run.wait()
    if len(points) < 3 or points[-1][1] == points[1][1]:
        sys.exit(f"settled_rate: too few progress lines in {a.seconds} s: {points}")
    (t0, s0), (t1, s1) = points[1], points[-1]
    after = core_times()
    print(f"threads {a.threads}: steps {s0}-{s1}, {(t1 - t0) / (s1 - s0):.4f} s per step; "
          f"cores' loop times before {' '.join(f'{t:.3f}' for t in before)} s, "
          f"after {' '.join(f'{t:.3f}' for t in after)} s")


if __name__ == "__main__":
    main()
