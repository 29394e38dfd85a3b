"""Coverage of D's 95 % CI when only a few particles move: the bootstrap alone vs the rare-mover
rule (bbb/analysis/stats/rare.py).  Prints the calibration table of docs/statistics.md.

    python -m benchmarks.calibrations.rare_movers [--reps 200] [--reps-4096 100] [--json PATH]

With --json the calibration is also written as JSON (the coverage by the sample's n_eff that
`bbb reduce` puts in its D_cover column reads bbb/analysis/stats/rare_movers_calibration.json, made so).

Populations (bbb.analysis.stats.synthetic.rare_movers): N particles, each a mover with probability
p = m / N (m: expected movers), light tails (Brownian, D_i ~ Gamma CV 0.5) or heavy tails
(3 mm jumps, D_i lognormal σ = 1.5); the rest creep (D = 1e-6 mm²/s).  The scenes' sampling:
t_max = 50 s, sample_dt = 0.5 s, 10 % discarded, fit lags 5-25 % of T.  True D = p + (1 − p)
1e-6 mm²/s.  The CI is the percentile bootstrap of `bbb reduce` (1000 resamples), with and
without the rule; the rule's threshold n_eff < t is scanned over t (coverage at each t).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from datetime import date

import numpy as np

from bbb.analysis.stats import per_particle_D
from bbb.analysis.stats.bootstrap import bootstrap_mean_unchecked
from bbb.analysis.stats.rare import RARE_N_EFF, RARE_SHARE, effective_movers, rare_mover_interval
from bbb.analysis.stats.synthetic import rare_movers

N_SAMPLES, DT, CREEP = 101, 0.5, 1e-6
TIMES = np.arange(N_SAMPLES) * DT
EXPECTED = (0.5, 1, 2, 3, 5, 10, 20, 50)
SIZES = (128, 512, 4096)
THRESHOLDS = (5.0, 10.0, 20.0, 40.0)
N_BOOT, CI = 1000, 0.95


def one(rng: np.random.Generator, n: int, m: float, tails: str) -> tuple:
    """(true D, k movers, n_eff, boot lo, hi, gamma lo, hi, N) of one sample."""
    p = min(1.0, m / n)
    x = rare_movers(rng, n, N_SAMPLES, DT, p, tails, creep=CREEP)
    k = int(np.count_nonzero(np.ptp(x, axis=1) > 0.5))  # movers travel ~10 mm, creepers ~0.01 mm
    d_i = per_particle_D(x, TIMES)
    b = bootstrap_mean_unchecked(d_i, N_BOOT, CI, rng, "percentile")
    g = rare_mover_interval(d_i, CI)
    return (p + (1 - p) * CREEP, k, effective_movers(d_i), b.lo, b.hi, g[0], g[1], n)


def cell(n: int, m: float, tails: str, reps: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng([seed, n, int(m * 10), tails == "heavy"])
    return np.array([one(rng, n, m, tails) for _ in range(reps)])


def coverage(r: np.ndarray, threshold: float | None) -> tuple[float, float, float]:
    """(coverage, miss below (truth < lo), miss above (truth > hi)) of the rule at threshold."""
    D, n_eff, n, lo, hi = r[:, 0], r[:, 2], r[:, 7], r[:, 3].copy(), r[:, 4].copy()
    if threshold is not None:
        on = n_eff < np.minimum(threshold, RARE_SHARE * n)
        lo[on] = np.minimum(lo[on], r[on, 5])
        hi[on] = np.maximum(hi[on], r[on, 6])
    below, above = np.mean(D < lo), np.mean(D > hi)
    return 1 - below - above, below, above


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=200)
    ap.add_argument("--reps-4096", type=int, default=100)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--json", help="also write the calibration to this JSON file")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    print("# m: expected movers; m_eff: the population's effective movers N E[c]²/E[c²]\n"
          "# (c = max(D_i, 0); = m / a mover's E[c²]/E[c]²); k: mean movers seen; n_eff: median\n"
          "# of the sample's; boot/rule: coverage of the nominal 95 % CI; lo/hi: share with the\n"
          "# truth below lo / above hi; hw×: median widening of the CI by the rule")
    print("# where the rule is on (n_eff < threshold) its CI is the hull of bootstrap and gamma CI")
    print(f"# benchmarks/calibrations/rare_movers.py, {date.today()}, "
          f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs; reps {a.reps} "
          f"(N = 4096: {a.reps_4096}), {N_BOOT} resamples")
    print(f"# rule: hull with the Fay-Feuer gamma interval when n_eff < min({RARE_N_EFF:g}, "
          f"{RARE_SHARE:g} N) (columns 'rule'); cov@t: the same with t in place of {RARE_N_EFF:g}")
    head = (f"{'tails':>5} {'N':>5} {'m':>5} {'m_eff':>6} {'k':>5} {'n_eff':>6} {'boot':>5} {'lo/hi':>9}"
            f" {'rule':>5} {'lo/hi':>9} {'hw×':>5}" + "".join(f" {f'cov@{t:g}':>7}" for t in THRESHOLDS))
    pooled = []
    cells = []
    ratio = {}
    for tails in ("light", "heavy"):  # E[D_i²] / E[D_i]² of a mover, from 20480 movers
        rng = np.random.default_rng([a.seed, tails == "heavy"])
        c = np.concatenate([per_particle_D(rare_movers(rng, 4096, N_SAMPLES, DT, 1.0, tails),
                                           TIMES) for _ in range(5)])
        c = np.maximum(c, 0.0)
        ratio[tails] = float(np.mean(c * c) / c.mean() ** 2)
    print("# a mover's E[c²]/E[c]² (m_eff = m / it): "
          + ", ".join(f"{t} {v:.2f}" for t, v in ratio.items()))
    print(head)
    for tails in ("light", "heavy"):
        for n in SIZES:
            reps = a.reps_4096 if n == 4096 else a.reps
            for m in (*EXPECTED, n):
                r = cell(n, m, tails, reps, a.seed)
                pooled.append(r)
                cb, bl, ba = coverage(r, None)
                cr, rl, ra = coverage(r, RARE_N_EFF)
                on = r[:, 2] < min(RARE_N_EFF, RARE_SHARE * n)
                widen = np.where(on, np.maximum(r[:, 4], r[:, 6]) - np.minimum(r[:, 3], r[:, 5]),
                                 r[:, 4] - r[:, 3])
                base = r[:, 4] - r[:, 3]
                ok = base > 0
                hw = float(np.median(widen[ok] / base[ok])) if ok.any() else float("nan")
                m_eff = min(m, n) / ratio[tails]
                cells.append({"tails": tails, "N": n, "m": m, "m_eff": round(m_eff, 3),
                              "bootstrap": round(cb, 3), "rule": round(cr, 3), "samples": reps})
                print(f"{tails:>5} {n:5d} {m:5g} {m_eff:6.2f} {r[:, 1].mean():5.1f}"
                      f" {np.median(r[:, 2]):6.1f}"
                      f" {cb:5.2f} {bl:4.2f}/{ba:4.2f} {cr:5.2f} {rl:4.2f}/{ra:4.2f} {hw:5.2f}"
                      + "".join(f" {coverage(r, t)[0]:7.2f}" for t in THRESHOLDS), flush=True)
    allr = np.concatenate(pooled)
    print("\n# pooled over all cells with >= 1 mover seen, by the sample's n_eff (what the rule "
          "sees);\n# last row: samples with no mover seen (no rule on the data can cover them)")
    print(f"{'n_eff':>11} {'samples':>7} {'boot':>5} {'rule':>5}")
    edges = (0, 1.5, 3, 5, 10, 20, 40, 100, np.inf)
    seen = allr[:, 1] >= 1
    by_n_eff = []
    for lo_e, hi_e in zip(edges[:-1], edges[1:], strict=True):
        sel = seen & (allr[:, 2] >= lo_e) & (allr[:, 2] < hi_e)
        if sel.any():
            cb, cr = coverage(allr[sel], None)[0], coverage(allr[sel], RARE_N_EFF)[0]
            print(f"[{lo_e:g}, {hi_e:g}) {sel.sum():7d} {cb:5.2f} {cr:5.2f}")
            by_n_eff.append({"n_eff_from": lo_e, "n_eff_to": None if np.isinf(hi_e) else hi_e,
                             "samples": int(sel.sum()), "bootstrap": round(cb, 3),
                             "rule": round(cr, 3)})
    none = (coverage(allr[~seen], None)[0], coverage(allr[~seen], RARE_N_EFF)[0])
    print(f"{'no mover':>11} {np.sum(~seen):7d} {none[0]:5.2f} {none[1]:5.2f}")
    print(f"\n# {time.perf_counter() - t0:.0f} s")
    if a.json:
        out = {"benchmark": "benchmarks/calibrations/rare_movers.py", "date": str(date.today()), "ci": CI,
               "n_resamples": N_BOOT, "reps": a.reps, "reps_4096": a.reps_4096, "seed": a.seed,
               "rule": {"n_eff": RARE_N_EFF, "share": RARE_SHARE},
               "mover_ratio": {k: round(v, 3) for k, v in ratio.items()},
               "coverage_by_n_eff": by_n_eff,
               "no_mover_seen": {"samples": int(np.sum(~seen)), "bootstrap": round(none[0], 3),
                                 "rule": round(none[1], 3)},
               "cells": cells}
        with open(a.json, "w") as fh:
            json.dump(out, fh, indent=1)
            fh.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
