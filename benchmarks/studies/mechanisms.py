"""Mechanisms measurement: the Green–Kubo expansion (D_0, D_1, D_5, D_∞; per period, per
collision in mm and in cells) and the largest Lyapunov exponent λ at the paper's extrema,
beside the MSD-based D; and where particles do not move, the cusp rattling.

    .venv/bin/python -m benchmarks.studies.mechanisms [--particles 256] [--t-max 50] [--f 54,58,60,62,80]

Prints a table (and the cost of each part); commit the output under benchmarks/results/.
Preset klages2004, family "rest", seed 1; the first 10 % of the run is the transient.
λ is split into particles that move (x at the period ends of λ's window spans ≥ S) and
confined ones.  The rattling lines describe the confined particles of the positions run
(x spans < S after the transient): their largest distance from the nearest cusp apex
x = (k + ½) S over their recorded collisions, and their collisions per floor period.
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import platform
import time

import numpy as np

from bbb import Params, simulate
from bbb.analysis.greenkubo import cell_jumps, collision_jumps, expansion, period_jumps
from bbb.analysis.lyapunov import lyapunov
from bbb.analysis.stats import bootstrap_D
from benchmarks.common import cpu_name
from pipeline.tables.mechanisms import distinct_values

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
        dx, dt = collision_jumps(run.collisions_dense, run.n_recorded)
        nj = int(np.isfinite(dx).sum(axis=1).min())
        if nj >= 8:
            gx = expansion(dx[:, :nj], dt[:, :nj].sum(axis=1) / nj, seed=SEED)
            print(f"per collision  x (mm), tau = {gx.step * 1e3:.3f} ms, {nj} jumps; "
                  + "  ".join(f"D_{k} {ci(*gx.at(k))}" for k in (0, 1, 5))
                  + f"  D_inf {ci(gx.D_inf, gx.D_inf_lo, gx.D_inf_hi)} K = {gx.lag}, "
                  f"converged = {gx.converged}")
        rattling(run, p, times)
        try:
            cj = cell_jumps(run.collisions_dense, run.n_recorded, p.S)
            if cj.jumps.shape[1] >= 8 and args.particles - cj.n_excluded >= 2:
                gc = expansion(cj.jumps * p.S, cj.tau, seed=SEED)
                print(f"per cell       tau = {cj.tau * 1e3:.3f} ms, {cj.jumps.shape[1]} jumps, "
                      f"{cj.n_excluded} particles excluded; "
                      + "  ".join(f"D_{k} {ci(*gc.at(k))}" for k in (0, 1, 5))
                      + f"  D_inf {ci(gc.D_inf, gc.D_inf_lo, gc.D_inf_hi)} K = {gc.lag}, "
                      f"converged = {gc.converged}")
            else:
                print(f"per cell       too few jumps ({cj.jumps.shape[1]}) or particles")
        except ValueError as err:
            print(f"per cell       n/a: {err}")
        t3 = time.perf_counter()
        ly = lyapunov(p, args.particles, args.t_max, SEED, "rest", discard=DISCARD)
        t4 = time.perf_counter()
        print(f"lambda         {ci(ly.lam, ly.lam_lo, ly.lam_hi)} 1/s;  per collision "
              f"{ly.per_coll:.4f} [{ly.per_coll_lo:.4f}, {ly.per_coll_hi:.4f}];  collapsed "
              f"{ly.n_collapsed}/{args.particles};  collisions/s "
              f"{np.mean(ly.collisions) / ly.duration:.1f};  cost {t4 - t3:.1f} s")
        moves = ly.x_range >= p.S
        for name, sel in (("moving", moves), ("confined", ~moves)):
            v = ly.lam_i[sel & np.isfinite(ly.lam_i)]
            if v.size:
                print(f"  {name:9s} {v.size:4d} particles: lambda mean {v.mean():8.2f}, range "
                      f"[{v.min():.2f}, {v.max():.2f}] 1/s, distinct to 4 digits "
                      f"{distinct_values(v)[0]}, largest tie {distinct_values(v)[1]}")


def rattling(run, p, times) -> None:
    """The confined particles of the positions run: distance from the nearest cusp apex and
    collisions per floor period over their recorded collisions (after the transient)."""
    x = run.positions[:, math.ceil(DISCARD * (times.size - 1)):]
    confined = np.ptp(x, axis=1) < p.S
    if not confined.any():
        print("rattling       no confined particle")
        return
    typical, largest, rate = [], [], []
    for i in np.flatnonzero(confined):
        k = int(run.n_recorded[i])
        if k < 4:
            continue
        xc = run.collisions_dense[i, k // 2 : k, 1]  # the second half: settled
        tc = run.collisions_dense[i, :k, 0]
        d = np.abs(xc - (np.floor(xc / p.S) + 0.5) * p.S)
        typical.append(np.median(d))
        largest.append(d.max())
        rate.append((k - 1) / ((tc[-1] - tc[0]) * p.f) if tc[-1] > tc[0] else 0.0)
    t, m, r = np.array(typical), np.array(largest), np.array(rate)
    print(f"rattling       {confined.sum()} of {confined.size} particles confined (x spans < S); "
          f"over the second half of their first {ROWS} collisions: distance from the nearest "
          f"cusp apex, per-particle median: median {np.median(t):.2e} mm, per-particle largest: "
          f"median {np.median(m):.2e} mm, max {m.max():.2e} mm; collisions per floor period "
          f"median {np.median(r):.1f} (range {r.min():.1f}-{r.max():.1f})")


if __name__ == "__main__":
    main()
