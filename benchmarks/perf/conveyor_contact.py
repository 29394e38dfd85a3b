"""Conveyor contact-model benchmark: CPU seconds of an ensemble on a tilted and thrown floor
under ``stick``, ``slide`` and ``coulomb``, this checkout beside another bbb.

    .venv/bin/python -m benchmarks.perf.conveyor_contact [--baseline REF] [--particles 32] [--t-max 2]

klages2004 geometry (R = 15, S = 2: shallow cusps, θ_c = 3.8°), A = 0.1 mm, tilt 3°, throw
60°, from rest (seed 1), f = 40 and 55 Hz.  Each row runs in a fresh process with its own
numba cache (compiled before the clock starts); the time is the process's CPU time, which
a loaded machine disturbs far less than wall time.  ``--baseline REF`` runs the bbb package
of git revision REF (``git archive``) beside this checkout.  Prints a table; commit the
output under benchmarks/results/ with the date and machine.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile

import numba
import numpy as np

from benchmarks.common import ROOT, baseline_tree, cpu_name

SNIPPET = """
import sys, time
import numpy as np
from bbb import Params, simulate
f, contact, mu, n, t_max = (float(sys.argv[1]), sys.argv[2], float(sys.argv[3]), int(sys.argv[4]),
                            float(sys.argv[5]))
p = Params.preset("klages2004", f=f, A=0.1, tilt=3.0, throw=60.0, contact=contact, mu=mu)
simulate(p, 2, 0.01, seed=1, initial="rest")  # compile or load the cache
t0 = time.process_time()
run = simulate(p, n, t_max, seed=1, initial="rest", sample_times=np.linspace(0, t_max, 101))
cpu = time.process_time() - t0
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()), cpu)
"""

MODELS = (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.3))


def cpu_in(tree: str, cache: str, f: float, model: tuple[str, float], n: int,
           t_max: float) -> tuple[int, float]:
    """(collisions, CPU s) of one ensemble in a fresh process importing bbb from ``tree``."""
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    argv = [sys.executable, "-c", SNIPPET, str(f), model[0], str(model[1]), str(n), str(t_max)]
    res = subprocess.run(argv, env=env, check=True, capture_output=True, text=True, cwd=tree)
    n_coll, cpu = res.stdout.split()
    return int(n_coll), float(cpu)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=32)
    ap.add_argument("--t-max", type=float, default=2.0)
    ap.add_argument("--baseline", metavar="REF",
                    help="run the bbb of git revision REF (git archive) beside this checkout")
    args = ap.parse_args()
    here = str(ROOT)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    print(f"# bbb conveyor contact-model benchmark  "
          f"{datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python {platform.python_version()}  "
          f"numba {numba.__version__}  numpy {np.__version__}")
    print(f"# klages2004 (R = 15, S = 2), A = 0.1 mm, tilt 3 deg, throw 60 deg, from rest, "
          f"{args.particles} particles x {args.t_max:g} s, one run each; CPU s of the process")
    with tempfile.TemporaryDirectory() as tmp:
        trees = {"this": here}
        label = f"this = HEAD ({head})"
        if args.baseline:
            os.mkdir(os.path.join(tmp, "ref"))
            trees["ref"], ref_label = baseline_tree(args.baseline, os.path.join(tmp, "ref"))
            label = f"ref = {ref_label}, " + label
        print(f"# {label}")
        cols = [f"{'f (Hz)':>7} {'contact':>12}"]
        for who in trees:
            cols.append(f"{who + ' coll':>11} {who + ' CPU s':>11}")
        if "ref" in trees:
            cols.append(f"{'ref/this':>8}")
        print(" ".join(cols))
        for f in (40.0, 55.0):
            for model in MODELS:
                name = model[0] if model[0] != "coulomb" else f"coulomb {model[1]:g}"
                row = [f"{f:7.1f} {name:>12}"]
                cpu = {}
                for who, tree in trees.items():
                    c, cpu[who] = cpu_in(tree, os.path.join(tmp, "cache-" + who), f, model,
                                         args.particles, args.t_max)
                    row.append(f"{c:11d} {cpu[who]:11.2f}")
                if "ref" in trees:
                    row.append(f"{cpu['ref'] / max(cpu['this'], 1e-9):8.1f}")
                print(" ".join(row), flush=True)


if __name__ == "__main__":
    main()
