"""How much does the spread estimate CV² = 2 EB(T) − EB(T/2) scatter at a given ensemble size?
Disjoint subsets of one large run, each with its bootstrap CI (bbb.analysis.stats.ergodic_verdict).

    bbb run benchmarks/checks/cv2_scatter.toml --store runs/cv2_scatter.zarr
    python -m benchmarks.checks.cv2_scatter runs/cv2_scatter.zarr [--sizes 256,640,1024,3072]

At 58 Hz the committed tables showed CV(D_i) = 0 % (ergodicity scene, 3 × 1024 particles),
23 % (Fig. 2, 640) and 39 % (transport_t0, 256) for the same physics: this prints the
all-particle CV² with its CI and, per size, the subsets' mean, SD and range of CV², the clipped
CV √max(0, CV²) they would have shown, and how many subset CIs hold the all-particle value.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
from datetime import date

import numpy as np

from bbb.analysis import stats
from pipeline.store.study_store import StudyStore


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("store")
    ap.add_argument("--sizes", default="256,640,1024,3072")
    ap.add_argument("--resamples", type=int, default=2000)
    a = ap.parse_args(argv)
    store = StudyStore.open(a.store)
    study = store.study
    an, acc = study.analysis, study.accuracy
    T = an.duration(acc.t_max)
    times = study.sample_times()
    kw = dict(lag=an.eb_lag * T, n_resamples=a.resamples, fit_from=an.fit_from * T,
              fit_to=an.fit_to * T, discard=an.discard)
    print(f"# benchmarks/checks/cv2_scatter.py, {date.today()}, {platform.machine()}, "
          f"{os.cpu_count()} CPUs; store {study.name}, {a.resamples} resamples, 95 % CIs")
    for fi, f in enumerate(study.frequencies):
        x = store.read_done("positions", fi, 0, store.done()[fi, 0])
        full = stats.ergodic_verdict({"all": x}, times, seed=1, **kw)
        ref = full.cv2_hat["all"]
        print(f"f = {f:g} Hz, all {x.shape[0]} particles: EB = {full.eb['all']:.3f} (Brownian "
              f"{full.eb_brownian:.4f}), CV² = {ref:+.4f} [{full.cv2_lo:+.4f}, "
              f"{full.cv2_hi:+.4f}], CV excluded above {full.cv_upper:.3f}")
        print(f"{'N':>5} {'subsets':>7} {'CV² mean':>9} {'SD':>7} {'min':>8} {'max':>8} "
              f"{'clipped CV':>11} {'CV=0':>5} {'CI hw':>7} {'CI holds all':>12}")
        for n in (int(s) for s in a.sizes.split(",")):
            k = x.shape[0] // n
            if k < 1:
                continue
            res = [stats.ergodic_verdict({"s": x[j * n:(j + 1) * n]}, times, seed=j, **kw)
                   for j in range(k)]
            c2 = np.array([r.cv2_hat["s"] for r in res])
            lo, hi = np.array([r.cv2_lo for r in res]), np.array([r.cv2_hi for r in res])
            cv = 100 * np.sqrt(np.maximum(c2, 0.0))
            sd = c2.std(ddof=1) if k > 1 else float("nan")
            print(f"{n:5d} {k:7d} {c2.mean():+9.4f} {sd:7.4f} {c2.min():+8.4f} {c2.max():+8.4f}"
                  f" {f'{cv.min():.0f}-{cv.max():.0f} %':>11} {np.mean(c2 <= 0):5.0%}"
                  f" {np.mean(hi - lo) / 2:7.4f} {np.mean((lo <= ref) & (ref <= hi)):12.0%}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
