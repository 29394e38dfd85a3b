"""Draft measurement: D(f) and the contact fraction per contact model near the onset.

    .venv/bin/python benchmarks/contact_onset.py [--particles 64] [--t-max 20] [--family rest]

D = var(x(t_max) − x(t₀)) / (2 (t_max − t₀)) with t₀ = t_max/4 (transient dropped), a 95 %
bootstrap CI over particles (percentile, 1000 resamples); contact fraction = time held or
sliding / t_max, mean over particles.  A draft at small size, not the study (which belongs
in pipeline/studies/contact/).
"""

from __future__ import annotations

import argparse
import datetime
import os

import numpy as np

from bbb import Params, simulate

MODELS = (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=64)
    ap.add_argument("--t-max", type=float, default=20.0)
    ap.add_argument("--family", default="rest")
    ap.add_argument("--freqs", default="48,50,52,54,56,58,60,62")
    args = ap.parse_args()
    freqs = [float(f) for f in args.freqs.split(",")]
    t0 = args.t_max / 4
    print(f"# contact models near onset  {datetime.datetime.now().isoformat(timespec='seconds')}"
          f"  ({os.cpu_count()} cores)")
    print(f"# klages2004, {args.particles} particles x {args.t_max:g} s from {args.family}, "
          f"D from x({args.t_max:g}) - x({t0:g}), 95 % bootstrap CI over particles")
    print(f"{'f':>5} {'model':>13} {'D (mm²/s)':>10} {'CI low':>8} {'CI high':>8} {'contact':>8} "
          f"{'held':>6} {'slid':>6}")
    rng = np.random.default_rng(0)
    for f in freqs:
        for contact, mu in MODELS:
            p = Params.preset("klages2004", f=f, contact=contact, mu=mu)
            run = simulate(p, args.particles, args.t_max, seed=int(f * 1000), initial=args.family,
                           sample_times=np.array([t0, args.t_max]))
            assert run.counters["anomalies"].sum() == 0
            dx = run.positions[:, 1] - run.positions[:, 0]
            scale = 2.0 * (args.t_max - t0)
            d = np.var(dx) / scale
            boot = [np.var(dx[rng.integers(0, dx.size, dx.size)]) / scale for _ in range(1000)]
            lo, hi = np.percentile(boot, [2.5, 97.5])
            held = run.contact_time["held"].mean() / args.t_max
            slid = run.contact_time["sliding"].mean() / args.t_max
            name = contact if contact != "coulomb" else f"coulomb {mu:g}"
            print(f"{f:5.1f} {name:>13} {d:10.4f} {lo:8.4f} {hi:8.4f} {held + slid:8.3f} "
                  f"{held:6.3f} {slid:6.3f}", flush=True)


if __name__ == "__main__":
    main()
