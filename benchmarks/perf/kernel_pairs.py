"""The default kernel (paper's floor, stick) against another bbb in many short alternating pairs.

    .venv/bin/python -m benchmarks.perf.kernel_pairs --baseline REF [--pairs 12] [--particles 100]
                                                     [--t-max 10]

For a machine shared with other work: each pair runs the same seeded ensemble in a fresh
process of the reference (``git archive REF bbb``, own numba cache) and one of this checkout,
in alternating order (ref first in even pairs, this first in odd ones), at f = 60 and 80 Hz
from rest and launched; the rate is collisions per CPU second of the process
(benchmarks/perf/kernel.py's rate_in), the collision counts must agree.  Prints each row's median
rates, the median of the pairwise ratios this/ref and their spread (quartiles); commit the
output under benchmarks/results/.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import tempfile

import numba
import numpy as np

from benchmarks.common import ROOT, baseline_tree, cpu_name
from benchmarks.perf.kernel import rate_in

ROWS = ((60.0, "rest"), (60.0, "launched"), (80.0, "rest"), (80.0, "launched"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="REF", required=True)
    ap.add_argument("--pairs", type=int, default=12)
    ap.add_argument("--particles", type=int, default=100)
    ap.add_argument("--t-max", type=float, default=10.0)
    args = ap.parse_args()
    here = str(ROOT)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "ref"))
        ref_tree, label = baseline_tree(args.baseline, os.path.join(tmp, "ref"))
        caches = {"ref": os.path.join(tmp, "cache-ref"), "this": os.path.join(tmp, "cache-this")}
        trees = {"ref": ref_tree, "this": here}
        print(f"# bbb default kernel, alternating pairs  "
              f"{datetime.datetime.now().isoformat(timespec='seconds')}")
        print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python {platform.python_version()}  "
              f"numba {numba.__version__}  numpy {np.__version__}")
        print(f"# ref = {label}, this = HEAD ({head}); {args.pairs} pairs per row, "
              f"{args.particles} particles x {args.t_max:g} s, collisions per CPU second")
        print(f"{'f (Hz)':>7} {'family':>9} {'collisions':>11} {'ref c/s':>10} {'this c/s':>10} "
              f"{'ratio med':>9} {'ratio q1':>8} {'ratio q3':>8}")
        for f, family in ROWS:
            rates: dict[str, list[float]] = {"ref": [], "this": []}
            counts: dict[str, int] = {}
            for k in range(args.pairs):
                for who in (("ref", "this") if k % 2 == 0 else ("this", "ref")):
                    c, cpu = rate_in(trees[who], caches[who], f, family, args.particles,
                                     args.t_max)
                    if counts.setdefault(who, c) != c:
                        raise SystemExit(f"{who}: collisions changed between runs")
                    rates[who].append(c / cpu)
            if counts["ref"] != counts["this"]:
                raise SystemExit(f"f = {f}, {family}: the collisions differ "
                                 f"({counts['ref']} vs {counts['this']})")
            ratio = np.array(rates["this"]) / np.array(rates["ref"])
            q1, med, q3 = np.percentile(ratio, [25, 50, 75])
            print(f"{f:7.1f} {family:>9} {counts['this']:11d} {np.median(rates['ref']):10.3e} "
                  f"{np.median(rates['this']):10.3e} {med:9.3f} {q1:8.3f} {q3:8.3f}", flush=True)


if __name__ == "__main__":
    main()
