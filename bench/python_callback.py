#!/usr/bin/env python3
"""The cost of a Python callback every 100 steps on the 9 926-block brick pile (bench/make_pile.py
--n 32): the same Simulation steps in rounds of `--steps` steps, alternately without a callback
and with one every 100 steps that copies every block's position and the equilibrium measures (a
recording callback). Prints per round the wall and CPU time; the medians and their ratio; and
the time spent inside the callbacks (the cost itself, free of the drift between rounds). Run
from the build's Python module:

    PYTHONPATH=build/python OMP_NUM_THREADS=1 /usr/bin/python3 bench/python_callback.py
"""
import argparse
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import blockdem as bd


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=32, help="pile size (32: 9 926 blocks)")
    p.add_argument("--steps", type=int, default=300, help="steps per round")
    p.add_argument("--rounds", type=int, default=4, help="rounds of each kind (even: ABBA)")
    p.add_argument("--every", type=int, default=100)
    p.add_argument("--warmup", type=int, default=20, help="steps before the first round")
    a = p.parse_args()

    here = pathlib.Path(__file__).resolve().parent
    with tempfile.TemporaryDirectory() as tmp:
        toml = pathlib.Path(tmp) / "pile.toml"
        text = subprocess.run([sys.executable, str(here / "make_pile.py"), "--n", str(a.n),
                               "--steps", "1"], check=True, capture_output=True, text=True).stdout
        toml.write_text(text)
        sim = bd.Simulation(bd.load(toml))
    blocks = len(sim.block_names)
    sim.step(a.warmup)  # contacts formed, caches warm
    inside = []
    recorded = []

    def callback(s, k):
        t0, c0 = time.perf_counter(), time.process_time()
        recorded.append((s.positions[:, 2].mean(), s.equilibrium()["unbalanced_force_ratio"]))
        inside.append((time.perf_counter() - t0, time.process_time() - c0))

    callback(sim, 0)  # the first call pays one-off set-up (NumPy, pybind11 types): not timed
    inside.clear()
    rows = {"plain": [], "callback": []}
    # Rounds in the order plain, callback, callback, plain, ... (ABBA): the pile still settles
    # and a step gets cheaper as it does; this order cancels a linear drift from the comparison.
    for r in range(a.rounds):
        for kind in (("plain", "callback") if r % 2 == 0 else ("callback", "plain")):
            w0, c0 = time.perf_counter(), time.process_time()
            if kind == "plain":
                sim.step(a.steps)
            else:
                sim.step(a.steps, callback=callback, every=a.every)
            w, c = time.perf_counter() - w0, time.process_time() - c0
            rows[kind].append((w, c))
            print(f"{kind:>8}: {a.steps} steps, wall {w:.3f} s, cpu {c:.3f} s", flush=True)
    med = {k: (statistics.median(r[0] for r in v), statistics.median(r[1] for r in v))
           for k, v in rows.items()}
    calls = len(inside)
    wall_in = sum(w for w, _ in inside) / a.rounds  # per callback round
    cpu_in = sum(c for _, c in inside) / a.rounds
    print(f"blocks {blocks}, contacts {sim.contact_count}, steps per round {a.steps}, "
          f"callback every {a.every} steps ({calls} calls)")
    print(f"median wall: plain {med['plain'][0]:.3f} s, callback {med['callback'][0]:.3f} s, "
          f"ratio {med['callback'][0] / med['plain'][0]:.4f}")
    print(f"median cpu:  plain {med['plain'][1]:.3f} s, callback {med['callback'][1]:.3f} s, "
          f"ratio {med['callback'][1] / med['plain'][1]:.4f}")
    print(f"inside the callbacks per call: wall {1e3 * sum(w for w, _ in inside) / calls:.3f} ms, "
          f"cpu {1e3 * sum(c for _, c in inside) / calls:.3f} ms; per round: "
          f"{100 * wall_in / med['callback'][0]:.3f} % of the wall time, "
          f"{100 * cpu_in / med['callback'][1]:.3f} % of the cpu time")

if __name__ == "__main__":
    main()
