"""Does the conveyor floor (tilted and thrown, bbb's conveyor kernel) give the same bits as another bbb?

    .venv/bin/python benchmarks/conveyor_bits.py --baseline main [--particles 8] [--t-max 4]

The twin of benchmarks/paper_floor_bits.py for the conveyor: the bbb package of git revision
REF (``git archive``) and this checkout, in fresh processes with their own numba caches, run
the same seeded ensembles under stick, slide and Coulomb contact on tilted, thrown, tilted-and-
thrown and flat conveyors (and the paper's floor forced through the conveyor kernel), and hash
positions, recorded events (lift-offs and contact events included), counters and contact
times; the rows that differ are printed.  Commit the output under benchmarks/results/.
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
from kernel import baseline_tree, cpu_name
from paper_floor_bits import hashes

SNIPPET = """
import hashlib, sys
import numpy as np
from bbb import Params, simulate
n, t_max = int(sys.argv[1]), float(sys.argv[2])
FLOORS = ((0.0, 60.0, 15.0), (5.0, 90.0, 15.0), (5.0, 60.0, 15.0), (-8.0, 110.0, 15.0),
          (3.0, 75.0, 1.1), (2.0, 70.0, float("inf")), (0.0, 90.0, 15.0))
for contact, mu in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
    for tilt, throw, R in FLOORS:
        for f in (50.0, 60.0, 80.0):
            for fam in ("rest", "launched"):
                p = Params.preset("klages2004", f=f, contact=contact, mu=mu, tilt=tilt,
                                  throw=throw, R=R)
                r = simulate(p, n, t_max, seed=int(f * 7), initial=fam,
                             sample_times=np.linspace(0.0, t_max, 201), record_collisions=500,
                             record_liftoffs=True, _force_conveyor=True)
                h = hashlib.sha256()
                for a in (r.positions, r.collisions_dense, r.n_recorded,
                          *(r.counters[k] for k in sorted(r.counters)),
                          *(r.contact_time[k] for k in sorted(r.contact_time))):
                    h.update(np.ascontiguousarray(a).tobytes())
                print(contact, mu, tilt, throw, R, f, fam, h.hexdigest()[:16],
                      int(r.counters["collisions"].sum()))
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="REF", required=True)
    ap.add_argument("--particles", type=int, default=8)
    ap.add_argument("--t-max", type=float, default=4.0)
    args = ap.parse_args()
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=here, check=True,
                          capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as c1, \
            tempfile.TemporaryDirectory() as c2:
        ref_tree, ref_label = baseline_tree(args.baseline, tmp)
        ref = hashes(ref_tree, c1, args.particles, args.t_max, SNIPPET)
        this = hashes(here, c2, args.particles, args.t_max, SNIPPET)
    print(f"# bbb conveyor floor, bits side by side  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  python {platform.python_version()}  numba {numba.__version__}  "
          f"numpy {np.__version__}")
    print(f"# ref = {ref_label}, this = HEAD ({head}); {args.particles} particles x {args.t_max:g} s "
          f"per row, positions at 201 times, 500 events per particle")
    print("# columns: contact mu tilt throw R f family hash collisions")
    differ = [(a, b) for a, b in zip(ref, this, strict=True) if a != b]
    for a, b in differ:
        print(f"DIFFERS  ref: {a}\n         this: {b}")
    total = sum(int(line.split()[-1]) for line in this)
    print(f"{len(this)} ensembles, {total} collisions: {len(differ)} differ"
          + ("  -> bit-identical" if not differ and len(ref) == len(this) else ""))


if __name__ == "__main__":
    main()
