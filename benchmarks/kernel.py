"""Kernel benchmark: collisions per second per core and numba compile time (cold, warm).

    .venv/bin/python benchmarks/kernel.py [--particles 400] [--t-max 20]

Prints a table; commit the output under benchmarks/results/ with the date and CPU.
Single-threaded: one process runs the ensemble serially, so the rate is per core.
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=400)
    ap.add_argument("--t-max", type=float, default=20.0)
    args = ap.parse_args()
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
