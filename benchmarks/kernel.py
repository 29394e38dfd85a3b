"""Kernel benchmark: collisions per second per core and numba compile time (cold, warm).

    .venv/bin/python benchmarks/kernel.py [--particles 400] [--t-max 20]
    .venv/bin/python benchmarks/kernel.py --baseline main [--repeats 5]

Prints a table; commit the output under benchmarks/results/ with the date and CPU.
Single-threaded: one process runs the ensemble serially, so the rate is per core.

``--baseline REF`` compares this checkout's default (stick) kernel with the bbb package of
git revision REF side by side: ``git archive REF bbb`` into a temporary directory, then
alternating fresh processes (baseline, this checkout, baseline, ...) with their own numba
caches, the same ensembles, and the median rate of each; then the rates of the contact
models (this checkout only).
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
f, family, n, t_max = float(sys.argv[1]), sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
extra = dict(contact=sys.argv[5], mu=float(sys.argv[6])) if len(sys.argv) > 5 else {}
p = Params.preset("klages2004", f=f, **extra)
simulate(p, 2, 0.1, seed=1, initial=family)  # compile (or load) in this process
t0 = time.perf_counter()
run = simulate(p, n, t_max, seed=1, initial=family, sample_times=np.linspace(0, t_max, 101))
wall = time.perf_counter() - t0
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()), wall)
"""


def rate_in(path: str, cache: str, f: float, family: str, n: int, t_max: float,
            contact: tuple[str, float] | None = None) -> tuple[int, float]:
    """(collisions, wall s) of one ensemble in a fresh process importing bbb from ``path``."""
    env = dict(os.environ, PYTHONPATH=path, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    argv = [sys.executable, "-c", RATE_SNIPPET, str(f), family, str(n), str(t_max)]
    if contact is not None:
        argv += [contact[0], str(contact[1])]
    res = subprocess.run(argv, env=env, check=True, capture_output=True, text=True, cwd=path)
    coll, wall = res.stdout.split()
    return int(coll), float(wall)


def compare(ref: str, n: int, t_max: float, repeats: int) -> None:
    """The default kernel of this checkout against the one of git revision ``ref``."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rev = subprocess.run(["git", "rev-parse", "--short", ref], cwd=here, check=True,
                         capture_output=True, text=True).stdout.strip()
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        base = os.path.join(tmp, "baseline")
        os.mkdir(base)
        arch = subprocess.run(["git", "archive", ref, "bbb"], cwd=here, check=True,
                              capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", base], input=arch, check=True)
        caches = {"baseline": os.path.join(tmp, "cache-base"), "this": os.path.join(tmp, "cache-this")}
        paths = {"baseline": base, "this": here}
        print(f"# side by side: baseline = {ref} ({rev}), this = HEAD ({head}), "
              f"{repeats} alternating fresh processes each, median rate")
        print(f"# ensemble: {n} particles x {t_max:g} s, default Numerics, one core")
        print()
        print("# median and best (max) rate of each; on a loaded machine the best is the rate")
        print("# least disturbed by other processes")
        print(f"{'f (Hz)':>7} {'family':>9} {'collisions':>11} {'baseline c/s':>13} "
              f"{'this c/s':>12} {'this/base':>10} {'best base':>10} {'best this':>10} {'best t/b':>9}")
        for f in (60.0, 80.0):
            for family in ("rest", "launched"):
                rates: dict[str, list[float]] = {"baseline": [], "this": []}
                colls = {}
                for _ in range(repeats):
                    for who in ("baseline", "this"):
                        c, wall = rate_in(paths[who], caches[who], f, family, n, t_max)
                        rates[who].append(c / wall)
                        colls[who] = c
                if colls["baseline"] != colls["this"]:
                    raise SystemExit(f"f = {f}, {family}: the default kernel's collisions differ "
                                     f"({colls['baseline']} vs {colls['this']})")
                b, t = float(np.median(rates["baseline"])), float(np.median(rates["this"]))
                bb, bt = max(rates["baseline"]), max(rates["this"])
                print(f"{f:7.1f} {family:>9} {colls['this']:11d} {b:13.3e} {t:12.3e} {t / b:10.3f} "
                      f"{bb:10.3e} {bt:10.3e} {bt / bb:9.3f}")
        print()
        n, t_max = min(n, 100), min(t_max, 5.0)
        print(f"contact models (this checkout only; from rest; {n} particles x {t_max:g} s)")
        print(f"{'f (Hz)':>7} {'contact':>13} {'collisions':>11} {'wall (s)':>9} {'coll/s':>10}")
        for f in (54.0, 60.0, 80.0):
            for model in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
                c, wall = rate_in(here, caches["this"], f, "rest", n, t_max, model)
                name = model[0] if model[0] != "coulomb" else f"coulomb {model[1]:g}"
                print(f"{f:7.1f} {name:>13} {c:11d} {wall:9.2f} {c / wall:10.3e}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=400)
    ap.add_argument("--t-max", type=float, default=20.0)
    ap.add_argument("--baseline", metavar="REF", help="compare with the bbb of git revision REF")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    if args.baseline:
        print(f"# bbb kernel benchmark, side by side  "
              f"{datetime.datetime.now().isoformat(timespec='seconds')}")
        print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python {platform.python_version()}  "
              f"numba {numba.__version__}  numpy {np.__version__}")
        compare(args.baseline, args.particles, args.t_max, args.repeats)
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
