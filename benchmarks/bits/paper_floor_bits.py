"""Does the paper's floor (tilt 0, throw 90°: bbb.kernel) give the same bits as another bbb?

    .venv/bin/python -m benchmarks.bits.paper_floor_bits --baseline REF [--particles 16] [--t-max 10]

Runs the same seeded ensembles — stick, slide, Coulomb 0.05 and 0.3 at 48-99 Hz, from rest
and launched — in a fresh process of this checkout and one of the bbb of git revision REF
(``git archive``, own numba caches), hashes each one's positions, events (lift-offs and contact
events included), counters and contact times, and prints the rows that differ.  Commit the
output under benchmarks/results/.  (tests/bbb/dynamics/test_paper_floor_bits.py holds ten such hashes.)
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

#: what every side-by-side snippet starts with: its arguments and the hash of one ensemble
#: (positions, recorded events, counters, contact times)
PREAMBLE = """
import hashlib, sys
import numpy as np
from bbb import Params, simulate
n, t_max = int(sys.argv[1]), float(sys.argv[2])
SAMPLES = np.linspace(0.0, t_max, 201)


def digest(r):
    h = hashlib.sha256()
    for a in (r.positions, r.collisions_dense, r.n_recorded,
              *(r.counters[k] for k in sorted(r.counters)),
              *(r.contact_time[k] for k in sorted(r.contact_time))):
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()[:16] + " " + str(int(r.counters["collisions"].sum()))
"""

SNIPPET = PREAMBLE + """
for contact, mu in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
    for f in (48.0, 50.0, 52.0, 54.0, 56.0, 58.0, 60.0, 62.0, 66.0, 70.0, 80.0, 90.0, 99.0):
        for fam in ("rest", "launched"):
            p = Params.preset("klages2004", f=f, contact=contact, mu=mu)
            r = simulate(p, n, t_max, seed=int(f * 7), initial=fam, sample_times=SAMPLES,
                         record_collisions=500, record_liftoffs=True)
            print(contact, mu, f, fam, digest(r))
"""


def hashes(tree: str, cache: str, n: int, t_max: float, snippet: str = SNIPPET) -> list[str]:
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=cache, PYTHONDONTWRITEBYTECODE="1")
    res = subprocess.run([sys.executable, "-c", snippet, str(n), str(t_max)], env=env, check=True,
                         capture_output=True, text=True, cwd=tree)
    return res.stdout.splitlines()


def side_by_side(what: str, snippet: str, baseline: str, n: int, t_max: float,
                 columns: str | None = None) -> None:
    """Hash ``snippet``'s ensembles in the bbb of revision ``baseline`` and in this checkout
    (fresh processes, own numba caches) and print the rows that differ."""
    here = str(ROOT)
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as c1, \
            tempfile.TemporaryDirectory() as c2:
        ref_tree, ref_label = baseline_tree(baseline, tmp)
        ref = hashes(ref_tree, c1, n, t_max, snippet)
        this = hashes(here, c2, n, t_max, snippet)
    print(f"# bbb {what}, bits side by side  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  numba {numba.__version__}  "
          f"numpy {np.__version__}")
    print(f"# ref = {ref_label}, this = HEAD ({head}); {n} particles x {t_max:g} s "
          f"per row, positions at 201 times, 500 events per particle")
    if columns:
        print(f"# columns: {columns}")
    differ = [(a, b) for a, b in zip(ref, this, strict=True) if a != b]
    for a, b in differ:
        print(f"DIFFERS  ref: {a}\n         this: {b}")
    total = sum(int(line.split()[-1]) for line in this)
    print(f"{len(this)} ensembles, {total} collisions: {len(differ)} differ"
          + ("  -> bit-identical" if not differ and len(ref) == len(this) else ""))


def cli(doc: str, what: str, snippet: str, particles: int, t_max: float,
        columns: str | None = None) -> None:
    """A side-by-side module's command line (its docstring ``doc``): --baseline REF, and the
    ensembles' size (defaults ``particles`` × ``t_max`` s)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--baseline", metavar="REF", required=True)
    ap.add_argument("--particles", type=int, default=particles)
    ap.add_argument("--t-max", type=float, default=t_max)
    args = ap.parse_args()
    side_by_side(what, snippet, args.baseline, args.particles, args.t_max, columns)


if __name__ == "__main__":
    cli(__doc__, "paper's floor", SNIPPET, 16, 10.0)
