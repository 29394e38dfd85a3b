"""A focused property run of Coulomb contact near steep cusps: the project's no-miss test
(tests/bbb/dynamics/test_contact_step_level.py, the independent trajectory checker and the
brute-force gap grid) over many random scenes where the cusp walls are nearly vertical.

    nice .venv/bin/python -m benchmarks.checks.cusp_contact_property [--examples 2000] [--seed 0] [--jobs 2]
        [--baseline REF]

Draws R in [1.05, 1.3] mm (S = 2 mm: cusp walls 17.8°-40° from vertical), f in [100, 200] Hz,
A in [0.2, 1] mm, Coulomb μ in [0.05, 0.5], α in [0.05, 1], β in [0, 1], every family (rest,
dropped, launched) and a seed; a quarter of the draws of each value are "simple" ones (the
range's ends, dyadic values inside it, as hypothesis favours: three of the four examples
that found the cusp contact-start fault had R = 1.05 and f = 128).  Each example runs the
test's inner function (3 particles, 60 periods).  Prints the date, CPU, commit, the count
and every failure with its arguments; commit the output under benchmarks/results/.
``--baseline REF``: the same draws against the bbb package of git revision REF (``git
archive``, own numba cache; the tests stay this checkout's), e.g. to see the run fail there.
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
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from benchmarks.common import ROOT, baseline_tree, cpu_name

HERE = str(ROOT)

RANGES = {"f": (100.0, 200.0), "A": (0.2, 1.0), "radius": (1.05, 1.3), "alpha": (0.05, 1.0),
          "beta": (0.0, 1.0), "mu": (0.05, 0.5)}
FAMILIES = ("rest", "dropped", "launched")


def simple_values(lo: float, hi: float) -> list[float]:
    """The range's ends and the dyadic values k/2^m (m ≤ 6, and whole numbers) inside it."""
    vals = {lo, hi}
    for m in range(7):
        k0, k1 = int(np.ceil(lo * 2**m)), int(np.floor(hi * 2**m))
        vals.update(k / 2**m for k in range(k0, k1 + 1) if k1 - k0 < 64)
    return sorted(vals)


def draw(rng: np.random.Generator, n: int) -> list[dict]:
    out = []
    simple = {k: simple_values(*r) for k, r in RANGES.items()}
    for i in range(n):
        v = {}
        for k, (lo, hi) in RANGES.items():
            v[k] = float(rng.choice(simple[k])) if rng.random() < 0.25 else float(rng.uniform(lo, hi))
        out.append(dict(f=v["f"], A=v["A"], radius=v["radius"], alpha=v["alpha"], beta=v["beta"],
                        model=("coulomb", v["mu"]), family=FAMILIES[i % 3],
                        seed=int(rng.integers(0, 2**32))))
    return out


def one(kw: dict) -> tuple[dict, str | None]:
    from tests.bbb.dynamics.test_contact_step_level import (
        test_no_event_is_missed_and_no_particle_goes_below_the_surface_under_the_contact_models as test,
    )

    try:
        test.hypothesis.inner_test(**kw)
    except AssertionError as exc:
        return kw, str(exc).splitlines()[0][:300]
    return kw, None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--baseline", metavar="REF")
    ap.add_argument("--label", help=argparse.SUPPRESS)  # set by the --baseline re-run
    args = ap.parse_args()
    if args.baseline:
        # the baseline's bbb in a fresh process: its extracted tree first on the path (the working
        # directory, then PYTHONPATH), this checkout after it for benchmarks/ and tests/
        with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as cache:
            tree, label = baseline_tree(args.baseline, tmp)
            env = dict(os.environ, PYTHONPATH=os.pathsep.join([tree, HERE]), NUMBA_CACHE_DIR=cache)
            argv = [sys.executable, "-m", "benchmarks.checks.cusp_contact_property", "--label", label,
                    "--examples", str(args.examples), "--seed", str(args.seed), "--jobs", str(args.jobs)]
            sys.exit(subprocess.run(argv, env=env, cwd=tree).returncode)
    run(args, args.label)


def run(args, label: str | None) -> None:
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=HERE, check=True,
                          capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "bbb"], cwd=HERE, check=True,
                           capture_output=True, text=True).stdout.strip()
    examples = draw(np.random.default_rng(args.seed), args.examples)
    t0 = time.perf_counter()
    failures = []
    with ProcessPoolExecutor(args.jobs) as pool:
        for k, (kw, err) in enumerate(pool.map(one, examples, chunksize=8)):
            if err is not None:
                failures.append((kw, err))
            if (k + 1) % 100 == 0:
                print(f"{k + 1} examples, {len(failures)} failures, {time.perf_counter() - t0:.0f} s",
                      file=sys.stderr, flush=True)
    wall = time.perf_counter() - t0
    print(f"# bbb cusp contact property run  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores, shared: loaded)  python "
          f"{platform.python_version()}  tests of commit {head}, bbb of "
          f"{label or head + (' + uncommitted bbb changes' if dirty else '')}")
    print(f"# ranges: {RANGES}, families {FAMILIES}; draw seed {args.seed}, {args.jobs} processes")
    print("# each example: tests/bbb/dynamics/test_contact_step_level.py's no-miss test "
          "(3 particles, 60/f s)")
    for kw, err in failures:
        print(f"FAILED {kw}\n       {err}")
    print(f"examples: {len(examples)}  failures: {len(failures)}  wall: {wall:.0f} s")


if __name__ == "__main__":
    main()
