"""Kernel instructions side by side: guest instructions of the default path under valgrind,
for machines without hardware counters or too loaded for CPU time to mean anything.

    .venv/bin/python -m benchmarks.perf.kernel_instructions --baseline REF [--baseline REF2]
        [--particles 200] [--t-max 20] [--f 60 --f 80]

Each tree (``git archive REF bbb`` for each baseline, and this checkout) runs the same
ensemble (klages2004 preset, launched family, seed 1) in a fresh process under
``valgrind --tool=callgrind --collect-atstart=no``, which counts the instructions of the one
simulate() call only: callgrind's client requests switch collection on and off around it, from
a three-line C library built here with cc and valgrind's header.  The count does not depend on
the machine's load; the collision counts must agree.  numba compiles for the CPU valgrind
emulates (its name and features, read once under valgrind), natively and before the counted
run, so that valgrind loads the cache instead of compiling: the counts are of that code, not of
the host's.
Prints a table; commit it under benchmarks/results/ with the date and CPU.
"""

from __future__ import annotations

import argparse
import datetime
import os
import re
import subprocess
import sys
import tempfile

from benchmarks.common import ROOT, baseline_tree, cpu_name

CPU_SNIPPET = """
import llvmlite.binding as ll
ll.initialize_native_target()
print(ll.get_host_cpu_name())
print(ll.get_host_cpu_features().flatten())
"""

RUN_SNIPPET = """
import ctypes, os, sys
import numpy as np
from bbb import Params, simulate
f, n, t_max = float(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
p = Params.preset("klages2004", f=f)
simulate(p, 2, 0.1, seed=1, initial="launched", sample_times=np.linspace(0, 0.1, 101))
ctl = ctypes.CDLL(os.environ["BBB_CALLGRIND_CTL"]) if "BBB_CALLGRIND_CTL" in os.environ else None
if ctl is not None:
    ctl.start()
run = simulate(p, n, t_max, seed=1, initial="launched", sample_times=np.linspace(0, t_max, 101))
if ctl is not None:
    ctl.stop()
assert run.counters["anomalies"].sum() == 0
print(int(run.counters["collisions"].sum()))
"""

CTL_SOURCE = """
#include <valgrind/callgrind.h>
void start(void) { CALLGRIND_ZERO_STATS; CALLGRIND_TOGGLE_COLLECT; }
void stop(void) { CALLGRIND_TOGGLE_COLLECT; CALLGRIND_DUMP_STATS; }
"""


def valgrind_cpu() -> tuple[str, str]:
    """(CPU name, feature string) that LLVM sees under valgrind."""
    res = subprocess.run(["valgrind", "-q", sys.executable, "-c", CPU_SNIPPET], check=True,
                         capture_output=True, text=True)
    name, features = res.stdout.split()[-2:]
    return name, features


def control_library(tmp: str) -> str:
    """Builds the start()/stop() library of callgrind client requests in ``tmp``; its path."""
    src = os.path.join(tmp, "ctl.c")
    lib = os.path.join(tmp, "ctl.so")
    with open(src, "w", encoding="utf-8") as fh:
        fh.write(CTL_SOURCE)
    subprocess.run(["cc", "-O1", "-shared", "-fPIC", "-o", lib, src], check=True)
    return lib


def instructions(tree: str, cache: str, cpu: tuple[str, str], ctl: str, f: float, n: int,
                 t_max: float) -> tuple[int, int]:
    """(collisions, instructions of the simulate call) of one process from ``tree``."""
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1",
               PYTHONHASHSEED="0", NUMBA_CPU_NAME=cpu[0], NUMBA_CPU_FEATURES=cpu[1])
    argv = [sys.executable, "-c", RUN_SNIPPET, str(f), str(n), str(t_max)]
    # compile natively for valgrind's CPU (the tiny run types every function the full one does)
    subprocess.run(argv[:3] + [str(f), "2", "0.1"], env=env, check=True, capture_output=True,
                   cwd=tree)
    with tempfile.TemporaryDirectory() as out:
        res = subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no",
                              f"--callgrind-out-file={out}/cg.%p", *argv],
                             env=dict(env, BBB_CALLGRIND_CTL=ctl), check=True,
                             capture_output=True, text=True, cwd=tree)
        counts = []
        for name in os.listdir(out):
            with open(os.path.join(out, name), encoding="utf-8") as fh:
                counts += [int(m) for m in re.findall(r"^summary:\s+(\d+)", fh.read(), re.M)]
    if not counts or max(counts) == 0:
        raise SystemExit(f"callgrind counted nothing: {res.stderr[-300:]}")
    return int(res.stdout.split()[-1]), max(counts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--baseline", action="append", required=True)
    ap.add_argument("--particles", type=int, default=200)
    ap.add_argument("--t-max", type=float, default=20.0)
    ap.add_argument("--f", type=float, action="append")
    args = ap.parse_args()
    freqs = args.f or [60.0, 80.0]
    cpu = valgrind_cpu()
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        ctl = control_library(tmp)
        trees = {}
        for ref in args.baseline:
            d = os.path.join(tmp, f"ref-{len(trees)}")
            os.makedirs(d)
            trees[baseline_tree(ref, d)[1]] = d
        trees[f"this (HEAD {head})"] = str(ROOT)
        print(f"# bbb kernel instructions side by side  {datetime.datetime.now():%Y-%m-%dT%H:%M}")
        print(f"# CPU: {cpu_name()}; code compiled for valgrind's {cpu[0]}")
        print(f"# default path: klages2004, launched, seed 1, {args.particles} particles x "
              f"{args.t_max:g} s; instructions of the simulate call (callgrind)")
        print(f"{'tree':>28} {'f (Hz)':>7} {'collisions':>11} {'instructions':>14} "
              f"{'instr/coll':>10}")
        counts: dict[float, set[int]] = {f: set() for f in freqs}
        for label, tree in trees.items():
            cache = os.path.join(tmp, "cache-" + os.path.basename(tree))
            for f in freqs:
                c, ins = instructions(tree, cache, cpu, ctl, f, args.particles, args.t_max)
                counts[f].add(c)
                print(f"{label:>28} {f:7.1f} {c:11d} {ins:14d} {ins / c:10.1f}", flush=True)
        for f, cs in counts.items():
            if len(cs) != 1:
                raise SystemExit(f"f = {f}: the trees' collision counts differ ({sorted(cs)})")


if __name__ == "__main__":
    main()
