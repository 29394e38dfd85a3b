"""Does a larger first sample make the target-driven Fig. 2 agree with the fixed-ensemble one
at the creeping frequencies?  D from rest there (~1e-6 to 1e-1 mm²/s) is an average over rare
events; this prints D, n_eff and z against the committed 4096-particle table after 128, 256,
512 and 1024 particles (the same chunks, seeds and CI the wave rule uses).

    python -m benchmarks.checks.creeping_tail runs/creeping_tail.zarr OLD.csv

The store comes from ``bbb run benchmarks/checks/creeping_tail.toml --store runs/creeping_tail.zarr``
(fixed 1024 particles at the ten creeping frequencies where the 128-particle run disagreed or
was rare; its chunks are the Fig. 2 store's, keyed by (seed, f, family, chunk)).  OLD.csv is the
fixed-ensemble table (``git show 27c76bc:figures/diffusion_figure2.csv``).  z as in
benchmarks/checks/agreement.py: (D_new − D_old) over the combined facing half-widths; |z| ≤ 1 agrees.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys

import numpy as np

from bbb.analysis import stats
from bbb.analysis.stats.rare import effective_movers
from benchmarks.checks.agreement import _facing_half as facing_half
from pipeline.execute.intervals import unit_ci
from pipeline.store.study_store import StudyStore


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("store")
    ap.add_argument("old")
    a = ap.parse_args(argv)
    with open(a.old, newline="") as fh:
        old = {round(float(r["f"]), 3): r for r in csv.DictReader(fh)}
    st = StudyStore.open(a.store)
    study = st.study
    an, acc = study.analysis, study.accuracy
    T = an.duration(acc.t_max)
    fit = dict(fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)
    done = st.done()
    sizes = [n for n in (1, 2, 4, 8) if n <= acc.n_chunks]
    print(f"{'f/Hz':>6} {'D_old':>9} " + " ".join(f"{'D@' + str(n * acc.chunk_size):>9} "
                                                  f"{'n_eff':>5} {'z':>5}" for n in sizes))
    agree = {n: 0 for n in sizes}
    for fi, f in enumerate(study.frequencies):
        o = old[round(f, 3)]
        d0, lo0, hi0 = float(o["D"]), float(o["D_lo"]), float(o["D_hi"])
        cells = []
        for n in sizes:
            if done[fi, 0, :n].sum() < n:
                cells.append(f"{'-':>9} {'-':>5} {'-':>5}")
                continue
            x = st.read_done("positions", fi, 0, np.arange(acc.n_chunks) < n)
            D, lo, hi = unit_ci(st, fi, 0, n)
            h = math.hypot(facing_half(d0, lo0, hi0, D), facing_half(D, lo, hi, d0))
            z = (D - d0) / h
            agree[n] += abs(z) <= 1.0
            n_eff = effective_movers(stats.per_particle_D(x, study.sample_times(), **fit))
            cells.append(f"{D:9.3g} {n_eff:5.1f} {z:5.2f}")
        print(f"{f:6.2f} {d0:9.3g} " + " ".join(cells), flush=True)
    nf = len(study.frequencies)
    print("agree (|z| <= 1): " + ", ".join(f"{agree[n]}/{nf} at {n * acc.chunk_size}"
                                           for n in sizes))
    return 0


if __name__ == "__main__":
    sys.exit(main())
