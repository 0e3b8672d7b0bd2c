#!/usr/bin/env python3
"""Whether the machine's cores run alike now: the same fixed loop, pinned to each core in turn.

A shared virtual machine's cores need not be equal: another tenant on the same physical core
slows one of them, for minutes at a time. A two-thread run then waits for its slower thread at
every statically split pass, and the 1-to-2-thread speed-up measures the machine, not the code.
Run this before and after a timing (bench/README.md, "Two cores that are not alike"):

    python3 bench/core_check.py            # seconds per core; quiet and alike: within ~5 %

Standard library only (runs with any python3; Linux, for the affinity call).
"""
import os
import sys
import time


def loop(n):
    s = 0.0
    x = 1.0000001
    for _ in range(n):
        s += x
    return s


def core_times(n=20_000_000):
    """Seconds of the loop of n additions on each core this process may run on, in order."""
    cores = sorted(os.sched_getaffinity(0))
    times = []
    for c in cores:
        os.sched_setaffinity(0, {c})
        t = time.perf_counter()
        loop(n)
        times.append(time.perf_counter() - t)
    os.sched_setaffinity(0, set(cores))
    return times


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20_000_000
    cores = sorted(os.sched_getaffinity(0))
    times = core_times(n)
    fastest = min(times)
    for c, t in zip(cores, times):
        print(f"core {c}: {t:.3f} s ({t / fastest:.2f} x the fastest)")
    print(f"slowest / fastest: {max(times) / fastest:.2f}")


if __name__ == "__main__":
    main()
