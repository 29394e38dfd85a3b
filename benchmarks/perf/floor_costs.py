"""What each floor shape costs: cold numba compile time and CPU time per collision.

    .venv/bin/python -m benchmarks.perf.floor_costs [--particles 100] [--t-max 10] [--repeats 3]

For each floor (the paper's arcs; a sine and a sawtooth of depth 0.3 mm on S = 2 mm, the
scenes of workflows/sine.toml and sawtooth.toml; and both as deep as the arcs) a fresh
process with an empty numba cache times its first ``simulate`` (import and compile of that
shape's kernel: cold compile), then fresh processes with the warm cache time an ensemble
from rest at f = 60 and 80 Hz (CPU time, robust against other processes on the cores;
median of the repeats).  The cost per collision is CPU time over collisions; the table also
gives the collision rate per particle-second, so that shapes are compared at the rates they
run at, and the ratio to the arcs' cost.  Commit the output under benchmarks/results/ with
the date and CPU.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import statistics
import subprocess
import sys
import tempfile

import numba

from benchmarks.common import cpu_name

#: the arcs' own depth, R − √(R² − S²/4) for the preset's R = 15, S = 2 (mm): shapes as deep
#: as the paper's floor, besides the scenes' ten times deeper ones
ARC_DEPTH = 15.0 - (15.0**2 - 1.0) ** 0.5
FLOORS = {"arc": {}, "sine": {"floor": "sine", "depth": 0.3},
          "sawtooth": {"floor": "sawtooth", "depth": 0.3, "peak": 0.3},
          "sine/arc depth": {"floor": "sine", "depth": ARC_DEPTH},
          "sawtooth/arc depth": {"floor": "sawtooth", "depth": ARC_DEPTH, "peak": 0.3}}

SNIPPET = """
import json, sys, time
t0 = time.perf_counter()
import numpy as np
from bbb import Params, simulate
kw, f, n, t_max = json.loads(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
p = Params.preset("klages2004", f=f, **kw)
simulate(p, 2, 0.01, seed=1, initial="rest")
first = time.perf_counter() - t0
c0 = time.process_time()
run = simulate(p, n, t_max, seed=1, initial="rest", sample_times=np.linspace(0, t_max, 101))
cpu = time.process_time() - c0
assert run.counters["anomalies"].sum() == 0
print(first, int(run.counters["collisions"].sum()), cpu)
"""


def measure(cache: str, kw: dict, f: float, n: int, t_max: float) -> tuple[float, int, float]:
    import json

    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    res = subprocess.run([sys.executable, "-c", SNIPPET, json.dumps(kw), str(f), str(n), str(t_max)],
                         env=env, check=True, capture_output=True, text=True)
    first, coll, cpu = res.stdout.split()
    return float(first), int(coll), float(cpu)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=100)
    ap.add_argument("--t-max", type=float, default=10.0)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--floors", nargs="*", default=list(FLOORS), choices=list(FLOORS))
    a = ap.parse_args()
    print(f"# bbb floor shapes: cold compile and cost per collision  "
          f"{datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  numba {numba.__version__}")
    print(f"# {a.particles} particles x {a.t_max:g} s from rest, CPU time, median of {a.repeats}")
    print(f"{'floor':18s} {'cold s':>7s} {'f':>4s} {'coll/(particle s)':>18s} "
          f"{'us/coll':>8s} {'x arc':>6s}")
    arc_cost = {}
    for name in a.floors:
        kw = FLOORS[name]
        with tempfile.TemporaryDirectory() as cache:
            cold = measure(cache, kw, 60.0, 2, 0.01)[0]
            for f in (60.0, 80.0):
                runs = [measure(cache, kw, f, a.particles, a.t_max) for _ in range(a.repeats)]
                coll = runs[0][1]
                assert all(r[1] == coll for r in runs)
                us = 1e6 * statistics.median(r[2] for r in runs) / coll
                arc_cost.setdefault(f, us)
                print(f"{name:18s} {cold:7.1f} {f:4.0f} {coll / (a.particles * a.t_max):18.1f} "
                      f"{us:8.3f} {us / arc_cost[f]:6.2f}", flush=True)


if __name__ == "__main__":
    main()
