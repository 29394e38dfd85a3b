"""Kernel benchmark: collisions per second per core and numba compile time (cold, warm).

    .venv/bin/python -m benchmarks.perf.kernel [--particles 400] [--t-max 20]
    .venv/bin/python -m benchmarks.perf.kernel --baseline REF [--repeats 3]
    .venv/bin/python -m benchmarks.perf.kernel --reference DIR [--repeats 3]

Prints a table; commit the output under benchmarks/results/ with the date and CPU.
Single-threaded: one process runs the ensemble serially, so the rate is per core.

Side by side with another bbb: ``--baseline REF`` extracts the bbb package of git revision
REF (``git archive REF bbb``) into a temporary directory; ``--reference DIR`` uses a directory
holding a ``bbb`` package.  At f = 60 and 80, fresh processes of the reference and of this
checkout alternate (``--repeats`` rounds, own numba caches, the same ensembles, which must give
the same collision counts), and the rate is per CPU second of the process (not wall time),
which a loaded machine disturbs far less; median and best of each.  Then the conveyor kernel
(tilted and thrown floors) and the contact models (slide, coulomb), also side by side
(median of the repeats).
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

from benchmarks.common import ROOT, baseline_tree, cpu_name

COMPILE_SNIPPET = """
import time
t = time.perf_counter()
from bbb import Params, simulate
simulate(Params.preset('klages2004', f=60.0), 2, 0.05, seed=0, sample_times=[0.0, 0.05],
         record_collisions=2)
print(time.perf_counter() - t)
"""


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
if len(sys.argv) > 7:
    extra.update(contact=sys.argv[7], mu=float(sys.argv[8]))
p = Params.preset("klages2004", f=f, **extra)
simulate(p, 2, 0.1, seed=1, initial=family)  # compile or load the cache
t0 = time.process_time()  # CPU time: robust against other processes sharing the cores
run = simulate(p, n, t_max, seed=1, initial=family, sample_times=np.linspace(0, t_max, 101))
cpu = time.process_time() - t0
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()), cpu)
"""


def rate_in(tree: str, cache: str, f: float, family: str, n: int, t_max: float,
            tilt: float = 0.0, throw: float = 90.0,
            contact: tuple[str, float] | None = None) -> tuple[int, float]:
    """(collisions, CPU s) of one ensemble in a fresh process importing bbb from ``tree``
    with its own numba cache directory ``cache``."""
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    argv = [sys.executable, "-c", RATE_SNIPPET, str(f), family, str(n), str(t_max), str(tilt),
            str(throw)]
    if contact is not None:
        argv += [contact[0], str(contact[1])]
    res = subprocess.run(argv, env=env, check=True, capture_output=True, text=True, cwd=tree)
    n_coll, cpu = res.stdout.split()
    return int(n_coll), float(cpu)


def has_conveyor(tree: str) -> bool:
    """Whether the bbb in ``tree`` takes a tilted floor and a contact model (the wave-1 kernel
    does not: its conveyor and contact rows cannot be run side by side)."""
    env = dict(os.environ, PYTHONPATH=tree, PYTHONDONTWRITEBYTECODE="1")
    probe = ("from bbb import Params; "
             "Params.preset('klages2004', f=60.0, tilt=5.0, throw=60.0, contact='coulomb', mu=0.3)")
    return subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True,
                          cwd=tree).returncode == 0


def compare(reference: str, label: str, n: int, t_max: float, repeats: int) -> None:
    """The default kernel of this checkout against the bbb package in ``reference``, then
    this checkout's conveyor and contact-model rates."""
    here = str(ROOT)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        caches = {"ref": os.path.join(tmp, "cache-ref"), "this": os.path.join(tmp, "cache-this")}
        trees = {"ref": reference, "this": here}
        print(f"# side by side: ref = {label}, this = HEAD ({head}); {repeats} alternating fresh "
              "processes each (own numba caches), same ensembles")
        print(f"# {n} particles x {t_max:g} s, default Numerics, one core; collisions per CPU "
              "second of the process (a loaded machine disturbs it far less than wall time);")
        print("# median and best (max) of the repeats")
        print(f"{'f (Hz)':>7} {'family':>9} {'tilt':>5} {'throw':>5} {'collisions':>11} "
              f"{'ref c/s':>10} {'this c/s':>10} {'this/ref':>8} {'best ref':>10} "
              f"{'best this':>10} {'best t/r':>8}")
        for f in (60.0, 80.0):
            for family in ("rest", "launched"):
                rates: dict[str, list[float]] = {"ref": [], "this": []}
                counts = {}
                for _ in range(repeats):
                    for who in ("ref", "this"):
                        c, cpu = rate_in(trees[who], caches[who], f, family, n, t_max)
                        counts[who] = c
                        rates[who].append(c / cpu)
                if counts["ref"] != counts["this"]:
                    raise SystemExit(f"f = {f}, {family}: the default kernel's collisions differ "
                                     f"({counts['ref']} vs {counts['this']})")
                r, t = float(np.median(rates["ref"])), float(np.median(rates["this"]))
                br, bt = max(rates["ref"]), max(rates["this"])
                print(f"{f:7.1f} {family:>9} {0:5g} {90:5g} {counts['this']:11d} {r:10.3e} "
                      f"{t:10.3e} {t / r:8.3f} {br:10.3e} {bt:10.3e} {bt / br:8.3f}")
        print()
        if not has_conveyor(reference):
            print(f"conveyor and contact models: not measured ({label} has neither)")
            return
        print(f"conveyor (launched; ref and this alternating, {repeats} each; median)")
        print(f"{'f (Hz)':>7} {'tilt':>5} {'throw':>5} {'collisions':>11} {'ref c/s':>10} "
              f"{'this c/s':>10} {'this/ref':>8}")
        for f in (60.0, 80.0):
            for tilt, throw in ((0.0, 60.0), (5.0, 90.0), (5.0, 60.0)):
                c, r, t = alternate(trees, caches, repeats, f, "launched", n, t_max, tilt, throw)
                print(f"{f:7.1f} {tilt:5g} {throw:5g} {c:11d} {r:10.3e} {t:10.3e} {t / r:8.3f}")
        print()
        n, t_max = min(n, 100), min(t_max, 5.0)
        print(f"contact models (from rest; {n} particles x {t_max:g} s; ref and this alternating, "
              f"{repeats} each; median)")
        print(f"{'f (Hz)':>7} {'contact':>13} {'collisions':>11} {'ref c/s':>10} {'this c/s':>10} "
              f"{'this/ref':>8}")
        for f in (54.0, 60.0, 80.0):
            for model in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
                c, r, t = alternate(trees, caches, repeats, f, "rest", n, t_max, contact=model)
                name = model[0] if model[0] != "coulomb" else f"coulomb {model[1]:g}"
                print(f"{f:7.1f} {name:>13} {c:11d} {r:10.3e} {t:10.3e} {t / r:8.3f}")


def alternate(trees: dict[str, str], caches: dict[str, str], repeats: int, f: float, family: str,
              n: int, t_max: float, tilt: float = 0.0, throw: float = 90.0,
              contact: tuple[str, float] | None = None) -> tuple[int, float, float]:
    """(collisions, median ref rate, median this rate) of ``repeats`` alternating fresh
    processes of the reference and of this checkout; the collision counts must agree."""
    rates: dict[str, list[float]] = {"ref": [], "this": []}
    counts = {}
    for _ in range(repeats):
        for who in ("ref", "this"):
            c, cpu = rate_in(trees[who], caches[who], f, family, n, t_max, tilt, throw, contact)
            counts[who] = c
            rates[who].append(c / cpu)
    if counts["ref"] != counts["this"]:
        raise SystemExit(f"f = {f}, {family}, tilt {tilt}, throw {throw}, {contact}: the "
                         f"collisions differ ({counts['ref']} vs {counts['this']})")
    return counts["this"], float(np.median(rates["ref"])), float(np.median(rates["this"]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=400)
    ap.add_argument("--t-max", type=float, default=20.0)
    ap.add_argument("--reference", metavar="DIR",
                    help="directory holding the bbb package to compare with")
    ap.add_argument("--baseline", metavar="REF",
                    help="compare with the bbb of git revision REF (git archive)")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    if args.reference or args.baseline:
        print(f"# bbb kernel benchmark, side by side  "
              f"{datetime.datetime.now().isoformat(timespec='seconds')}")
        print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python "
              f"{platform.python_version()}  numba {numba.__version__}  numpy {np.__version__}")
        if args.reference:
            compare(os.path.abspath(args.reference), os.path.basename(
                os.path.abspath(args.reference)), args.particles, args.t_max, args.repeats)
            return
        with tempfile.TemporaryDirectory() as tmp:
            tree, label = baseline_tree(args.baseline, tmp)
            compare(tree, label, args.particles, args.t_max, args.repeats)
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
