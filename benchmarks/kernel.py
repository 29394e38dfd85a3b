"""Kernel benchmark: collisions per second per core and numba compile time (cold, warm).

    .venv/bin/python benchmarks/kernel.py [--particles 400] [--t-max 20]
    .venv/bin/python benchmarks/kernel.py --reference DIR [--repeats 3]

Prints a table; commit the output under benchmarks/results/ with the date and CPU.
Single-threaded: one process runs the ensemble serially, so the rate is per core.

``--reference DIR``: side by side with another bbb (DIR holds its ``bbb`` package, e.g.
``git archive main bbb | tar -x -C DIR``): at f = 60 and 80, processes of this tree and of the
reference alternate (``--repeats`` rounds, best of each kept), so both see the same machine
load, and the rate is per CPU second of the process (not wall time), which a loaded machine
disturbs far less; then the conveyor kernel's rate (tilted and thrown floors) of this tree.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np

COMPILE_SNIPPET = """
import time
t = time.perf_counter()
from bbb import Params, simulate
simulate(Params.preset('klages2004', f=60.0), 2, 0.05, seed=0, sample_times=[0.0, 0.05],
         record_collisions=2)
print(time.perf_counter() - t)
"""


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def compile_times() -> tuple[float, float]:
    """Import + first call in a fresh process with an empty numba cache, then again warm."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = []
        for _ in range(2):
            res = subprocess.run([sys.executable, "-c", COMPILE_SNIPPET], env=env, check=True,
                                 capture_output=True, text=True)
            out.append(float(res.stdout.strip().splitlines()[-1]))
        return out[0], out[1]


def rate(f: float, family: str, n: int, t_max: float, numerics=None) -> tuple[int, float]:
    from bbb import Params, simulate

    p = Params.preset("klages2004", f=f)
    t0 = time.perf_counter()
    run = simulate(p, n, t_max, seed=1, initial=family, numerics=numerics,
                   sample_times=np.linspace(0, t_max, 101))
    wall = time.perf_counter() - t0
    assert run.counters["anomalies"].sum() == 0
    return int(run.counters["collisions"].sum()), wall


RATE_SNIPPET = """
import sys, time
import numpy as np
from bbb import Params, simulate
f, family, n, t_max, tilt, throw = (float(sys.argv[1]), sys.argv[2], int(sys.argv[3]),
                                    float(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6]))
extra = dict(tilt=tilt, throw=throw) if (tilt, throw) != (0.0, 90.0) else {}
p = Params.preset("klages2004", f=f, **extra)
simulate(p, 2, 0.1, seed=1, initial=family)  # compile or load the cache
t0 = time.process_time()  # CPU time: robust against other processes sharing the cores
run = simulate(p, n, t_max, seed=1, initial=family, sample_times=np.linspace(0, t_max, 101))
wall = time.process_time() - t0
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()), wall)
"""


def rate_in(tree: str, f: float, family: str, n: int, t_max: float, tilt: float = 0.0,
            throw: float = 90.0) -> tuple[int, float]:
    """(collisions, wall s) of one ensemble in a fresh process importing bbb from ``tree``."""
    env = dict(os.environ, PYTHONPATH=tree)
    res = subprocess.run([sys.executable, "-c", RATE_SNIPPET, str(f), family, str(n),
                          str(t_max), str(tilt), str(throw)], env=env, check=True,
                         capture_output=True, text=True, cwd=tree)
    n_coll, wall = res.stdout.split()
    return int(n_coll), float(wall)


def compare(reference: str, n: int, t_max: float, repeats: int) -> None:
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    print(f"# side by side, alternating processes, best of {repeats}; "
          f"{n} particles x {t_max:g} s; collisions per CPU second")
    print(f"{'f (Hz)':>7} {'family':>9} {'tilt':>5} {'throw':>5} {'ref coll/s':>11} "
          f"{'this coll/s':>11} {'this/ref':>8}")
    for f in (60.0, 80.0):
        for family in ("rest", "launched"):
            best = {"ref": 0.0, "this": 0.0}
            counts = {}
            for _ in range(repeats):
                for name, tree in (("ref", reference), ("this", here)):
                    c, wall = rate_in(tree, f, family, n, t_max)
                    counts[name] = c
                    best[name] = max(best[name], c / wall)
            assert counts["ref"] == counts["this"], counts  # the same trajectories
            print(f"{f:7.1f} {family:>9} {0:5g} {90:5g} {best['ref']:11.3e} {best['this']:11.3e} "
                  f"{best['this'] / best['ref']:8.3f}")
    for f in (60.0, 80.0):
        for tilt, throw in ((0.0, 60.0), (5.0, 90.0), (5.0, 60.0)):
            rates = [rate_in(here, f, "launched", n, t_max, tilt, throw) for _ in range(repeats)]
            best = max(c / wall for c, wall in rates)
            print(f"{f:7.1f} {'launched':>9} {tilt:5g} {throw:5g} {'':>11} {best:11.3e} "
                  f"{'':>8}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=400)
    ap.add_argument("--t-max", type=float, default=20.0)
    ap.add_argument("--reference", help="directory holding the bbb package to compare with")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    if args.reference:
        print(f"# bbb kernel benchmark, side by side  "
              f"{datetime.datetime.now().isoformat(timespec='seconds')}")
        print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python "
              f"{platform.python_version()}  numba {numba.__version__}  numpy {np.__version__}")
        compare(os.path.abspath(args.reference), args.particles, args.t_max, args.repeats)
        return
    cold, warm = compile_times()
    print(f"# bbb kernel benchmark  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python {platform.python_version()}  "
          f"numba {numba.__version__}  numpy {np.__version__}")
    print(f"# ensemble: {args.particles} particles x {args.t_max:g} s, default Numerics, one core")
    print()
    print(f"numba compile + import, cold cache: {cold:6.2f} s")
    print(f"numba compile + import, warm cache: {warm:6.2f} s")
    print()
    print(f"{'f (Hz)':>7} {'family':>9} {'collisions':>12} {'wall (s)':>9} {'coll/s/core':>12}")
    rate(60.0, "launched", 2, 0.1)  # compile in this process
    for f in (54.0, 60.0, 66.0, 72.0, 80.0, 90.0):
        for family in ("rest", "launched"):
            n, wall = rate(f, family, args.particles, args.t_max)
            print(f"{f:7.1f} {family:>9} {n:12d} {wall:9.2f} {n / wall:12.3e}")


if __name__ == "__main__":
    main()
