"""Mechanisms measurement: the Green–Kubo expansion (D_0, D_1, D_5, D_∞) and the largest
Lyapunov exponent λ at the paper's extrema, beside the MSD-based D.

    .venv/bin/python benchmarks/mechanisms.py [--particles 256] [--t-max 50] [--f 54,58,60,62,80]

Prints a table (and the cost of each part); commit the output under benchmarks/results/.
Preset klages2004, family "rest", seed 1; the first 10 % of the run is the transient.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bbb import Params, simulate  # noqa: E402
from bbb.greenkubo import cell_jumps, expansion, period_jumps  # noqa: E402
from bbb.lyapunov import lyapunov  # noqa: E402
from bbb.stats import bootstrap_D  # noqa: E402
from benchmarks.kernel import cpu_name  # noqa: E402

SEED = 1
DISCARD = 0.1
# collisions kept per particle for the per-collision expansion (from the end of the transient)
ROWS = 4000


def ci(v: float, lo: float, hi: float) -> str:
    return f"{v:8.2f} [{lo:.2f}, {hi:.2f}]"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--particles", type=int, default=256)
    ap.add_argument("--t-max", type=float, default=50.0)
    ap.add_argument("--f", default="54,58,60,62,80")
    args = ap.parse_args()
    freqs = [float(f) for f in args.f.split(",")]
    print(f"# bbb mechanisms  {datetime.date.today()}")
    print(f"# CPU: {cpu_name()} ({os.cpu_count()} cores)  python {platform.python_version()}  "
          f"numpy {np.__version__}")
    print(f"# klages2004, rest, seed {SEED}, {args.particles} particles x {args.t_max:g} s, "
          f"transient {DISCARD:.0%}; D in mm²/s with 95 % bootstrap CIs over particles")
    for f in freqs:
        p = Params.preset("klages2004", f=f)
        n = int(round(args.t_max * f))
        times = np.arange(n + 1) / f
        t0 = time.perf_counter()
        run = simulate(p, args.particles, float(times[-1]), SEED, sample_times=times,
                       record_collisions=ROWS, record_from=DISCARD * float(times[-1]))
        t1 = time.perf_counter()
        msd = bootstrap_D(run.positions, times, n_resamples=1000, seed=SEED)
        gk = expansion(period_jumps(run.positions, math.ceil(DISCARD * n)), 1.0 / f, seed=SEED)
        t2 = time.perf_counter()
        print(f"\n## f = {f:g} Hz (Γ = {p.gamma:.3f}); run {t1 - t0:.1f} s, expansion {t2 - t1:.1f} s")
        print(f"MSD D          {ci(*msd)}")
        print("per period     " + "  ".join(f"D_{k} {ci(*gk.at(k))}" for k in (0, 1, 5)))
        print(f"               D_inf {ci(gk.D_inf, gk.D_inf_lo, gk.D_inf_hi)}  lag K = {gk.lag} "
              f"periods, converged = {gk.converged}")
        try:
            cj = cell_jumps(run.collisions_dense, run.n_recorded, p.S)
            if cj.jumps.shape[1] >= 8 and args.particles - cj.n_excluded >= 2:
                gc = expansion(cj.jumps * p.S, cj.tau, seed=SEED)
                print(f"per collision  tau = {cj.tau * 1e3:.3f} ms, {cj.jumps.shape[1]} jumps, "
                      f"{cj.n_excluded} particles excluded; "
                      + "  ".join(f"D_{k} {ci(*gc.at(k))}" for k in (0, 1, 5))
                      + f"  D_inf {ci(gc.D_inf, gc.D_inf_lo, gc.D_inf_hi)} K = {gc.lag}, "
                      f"converged = {gc.converged}")
            else:
                print(f"per collision  too few jumps ({cj.jumps.shape[1]}) or particles")
        except ValueError as err:
            print(f"per collision  n/a: {err}")
        t3 = time.perf_counter()
        ly = lyapunov(p, args.particles, args.t_max, SEED, "rest", discard=DISCARD)
        t4 = time.perf_counter()
        print(f"lambda         {ci(ly.lam, ly.lam_lo, ly.lam_hi)} 1/s;  per collision "
              f"{ly.per_coll:.4f} [{ly.per_coll_lo:.4f}, {ly.per_coll_hi:.4f}];  collapsed "
              f"{ly.n_collapsed}/{args.particles};  collisions/s "
              f"{np.mean(ly.collisions) / ly.duration:.1f};  cost {t4 - t3:.1f} s")


if __name__ == "__main__":
    main()
