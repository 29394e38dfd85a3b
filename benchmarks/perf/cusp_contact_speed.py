"""Speed of this checkout's paper-floor kernel against another bbb, in alternating pairs of
fresh processes, with the pairwise ratios: the default (stick) path and the Coulomb contact path.

    nice .venv/bin/python -m benchmarks.perf.cusp_contact_speed --baseline 717f991 [--pairs 7]

Each scene runs ``--pairs`` times in a fresh process of the bbb of revision REF (``git
archive``) and of this checkout, alternating ref/this (own numba caches, compiled before the
first pair), and the rate is collisions per CPU second of the process (a loaded machine
disturbs CPU time far less than wall time).  Prints per scene the collision counts (the
default path's must agree), the median rates, and the median, least and largest of the
pairwise ratios this/ref (each pair ran back to back, so a load change between pairs cancels
in its ratio).  Scenes: stick at 60 and 80 Hz from rest and launched (the klages2004
preset, R = 15 mm), Coulomb μ = 0.05 and 0.3 at 60 Hz from rest on the preset, and Coulomb
near steep cusps (R = 1.05 and 1.2 mm, f = 128 Hz), where the contact start in a cusp
changed (counts may differ there).  Commit the output under benchmarks/results/.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile

import numpy as np

from benchmarks.common import ROOT, baseline_tree, cpu_name

SNIPPET = """
import json, sys, time
import numpy as np
from bbb import Params, simulate
kw = json.loads(sys.argv[1])
n, t_max, family = kw.pop("n"), kw.pop("t_max"), kw.pop("family")
p = Params.preset("klages2004", **kw)
simulate(p, 2, 0.05, seed=1, initial=family)  # compile or load the cache
t0 = time.process_time()
run = simulate(p, n, t_max, seed=1, initial=family, sample_times=np.linspace(0, t_max, 101))
cpu = time.process_time() - t0
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()), cpu)
"""

SCENES = [
    ("stick 60 rest", dict(f=60.0, family="rest", n=400, t_max=30.0)),
    ("stick 60 launched", dict(f=60.0, family="launched", n=400, t_max=30.0)),
    ("stick 80 rest", dict(f=80.0, family="rest", n=400, t_max=30.0)),
    ("stick 80 launched", dict(f=80.0, family="launched", n=400, t_max=30.0)),
    ("coulomb 0.05 60 rest", dict(f=60.0, family="rest", n=400, t_max=20.0, contact="coulomb",
                                  mu=0.05)),
    ("coulomb 0.3 60 rest", dict(f=60.0, family="rest", n=400, t_max=20.0, contact="coulomb", mu=0.3)),
    ("coulomb 0.05 R1.05 128", dict(f=128.0, A=0.45, R=1.05, alpha=0.5, beta=0.5, family="launched",
                                    n=400, t_max=10.0, contact="coulomb", mu=0.05)),
    ("coulomb 0.2 R1.2 128", dict(f=128.0, A=0.9, R=1.2, alpha=0.1, beta=0.5, family="launched",
                                  n=400, t_max=10.0, contact="coulomb", mu=0.2)),
]


def run_in(tree: str, cache: str, scene: dict) -> tuple[int, float]:
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    res = subprocess.run([sys.executable, "-c", SNIPPET, json.dumps(scene)], env=env, check=True,
                         capture_output=True, text=True, cwd=tree)
    n, cpu = res.stdout.split()
    return int(n), float(cpu)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="REF", required=True)
    ap.add_argument("--pairs", type=int, default=7)
    args = ap.parse_args()
    here = str(ROOT)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    print(f"# bbb paper-floor kernel speed, alternating pairs  "
          f"{datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores, shared with other jobs: loaded)  python "
          f"{platform.python_version()}")
    with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as c1, \
            tempfile.TemporaryDirectory() as c2:
        ref, label = baseline_tree(args.baseline, tmp)
        trees = {"ref": (ref, c1), "this": (here, c2)}
        print(f"# ref = {label}, this = HEAD ({head}); {args.pairs} pairs per scene, collisions "
              "per CPU second of each fresh process")
        print(f"{'scene':>24} {'coll ref':>9} {'coll this':>9} {'ref c/s':>10} {'this c/s':>10} "
              f"{'med ratio':>9} {'min':>6} {'max':>6}")
        for name, scene in SCENES:
            for who in ("ref", "this"):  # compile both kernels before timing
                run_in(*trees[who], dict(scene, n=2, t_max=0.05))
            rates: dict[str, list[float]] = {"ref": [], "this": []}
            counts = {}
            for k in range(args.pairs):
                order = ("ref", "this") if k % 2 == 0 else ("this", "ref")
                for who in order:
                    c, cpu = run_in(*trees[who], scene)
                    counts[who] = c
                    rates[who].append(c / cpu)
            ratio = np.array(rates["this"]) / np.array(rates["ref"])
            print(f"{name:>24} {counts['ref']:9d} {counts['this']:9d} "
                  f"{np.median(rates['ref']):10.3e} {np.median(rates['this']):10.3e} "
                  f"{np.median(ratio):9.3f} {ratio.min():6.3f} {ratio.max():6.3f}", flush=True)


if __name__ == "__main__":
    main()
