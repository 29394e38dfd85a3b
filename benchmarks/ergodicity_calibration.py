"""Calibration of the ergodicity rule on synthetic populations with a known D spread.

    .venv/bin/python benchmarks/ergodicity_calibration.py [--seeds 100] [--sizes 64,1024]

Prints a table; commit the output as benchmarks/results/ergodicity-calibration-<date>.txt
(docs/statistics.md explains it).  For every population (law x per-particle D spread) and
ensemble size, ``bbb.stats.ergodic_verdict`` runs on ``--seeds`` independent samples with
the real scenes' sampling: t_max = 50 s, sample_dt = 0.5 s, discard 10 %, fit lags 5-25 %
and EB lag 5 % of the analysed T = 45 s; three families (rest/dropped/launched) of N
particles each (ergodicity scene: N = 1024; draft: 64) or one family of 4096 (Fig. 2).
Each column is the fraction of samples a rule component (or rule) declares ergodic.

Truth: every population but ``families differ`` has the same law in every family.
'ergodic' rows are CV = 0 (a pass is correct: the column is 1 - false-negative rate);
non-ergodic rows are CV >= 50 % or a mixture of bouncing and creeping particles (a pass
is a false positive).  CV 5-25 % rows are reported, not scored.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import sys
import time

import numpy as np

from bbb.stats import RULES, ergodic_verdict
from bbb.stats import synthetic as syn

T_MAX, DT = 50.0, 0.5
N_SAMPLES = round(T_MAX / DT) + 1
FAMILIES = ("rest", "dropped", "launched")
FIT = dict(fit_from=0.05 * 45.0, fit_to=0.25 * 45.0, discard=0.10)
EB_LAG = 0.05 * 45.0

# population name -> (truth, generator(rng, n) -> positions); truth: "ergodic",
# "non-ergodic" or "grey" (reported, not scored)
CVS = (0.0, 0.05, 0.10, 0.25, 0.50)


# persistent: velocity correlation time 3 s (EB ~ 3x the Brownian level at T = 45 s, like
# the spiral modes); jumpy: 3 mm jumps, ~10 per particle in T (EB ~ 5x the Brownian level)
LAW_OPTIONS = {"brownian": {}, "persistent": {"tau": 3.0}, "jumpy": {"jump": 3.0}}


def _law(law: str, cv: float):
    def make(rng: np.random.Generator, n: int) -> np.ndarray:
        return syn.LAWS[law](rng, syn.gamma_D(rng, n, 1.0, cv), N_SAMPLES, DT,
                             **LAW_OPTIONS[law])
    return make


def _truth(cv: float) -> str:
    return "ergodic" if cv == 0 else ("non-ergodic" if cv >= 0.5 else "grey")


POPULATIONS: dict[str, tuple[str, object]] = {}
for _law_name in ("brownian", "persistent", "jumpy"):
    for _cv in CVS:
        POPULATIONS[f"{_law_name} CV {_cv:.0%}"] = (_truth(_cv), _law(_law_name, _cv))
for _q in (0.9, 0.5, 0.1):
    POPULATIONS[f"mixture {_q:.0%} bouncing"] = (
        "non-ergodic",
        (lambda q: lambda rng, n: syn.mixture(rng, n, N_SAMPLES, DT, 1.0, q))(_q))
POPULATIONS["families differ (D x1, x1.1, x1.2)"] = ("non-ergodic", None)

COMPONENTS = ("agree", "level", "decay", "spread")


def one(pop: str, n: int, n_fam: int, seed: int) -> tuple[dict[str, bool], float, float]:
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(n, n_fam, len(pop))))
    _, make = POPULATIONS[pop]
    if make is None:  # homogeneous Brownian families whose D differ by 10 % steps
        fams = {name: syn.brownian(rng, np.full(n, 1.0 + 0.1 * k), N_SAMPLES, DT)
                for k, name in enumerate(FAMILIES[:n_fam])}
    else:
        fams = {name: make(rng, n) for name in FAMILIES[:n_fam]}
    times = np.arange(N_SAMPLES) * DT
    v = ergodic_verdict(fams, times, lag=EB_LAG, n_resamples=400, seed=seed, **FIT)
    parts = {"agree": v.agreement_ok, "level": v.level_ok, "decay": v.decay_ok,
             "spread": v.spread_ok}
    key = "(pooled)" if "(pooled)" in v.cv_hat else next(iter(v.cv_hat))
    out = dict(parts)
    for rule, (decide, _) in RULES.items():
        out[f"R:{rule}"] = bool(decide(parts))
    return out, v.cv_hat[key], v.cv_upper


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--sizes", default="64x3,1024x3,4096x1",
                    help="comma-separated N x families, e.g. 1024x3")
    args = ap.parse_args(argv)
    sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    print(f"# bbb ergodicity-rule calibration  {datetime.datetime.now():%Y-%m-%dT%H:%M:%S}")
    print(f"# CPU: {platform.processor() or platform.machine()}  ({os.cpu_count()} cores)  "
          f"python {platform.python_version()}  numpy {np.__version__}")
    print(f"# {args.seeds} seeds per cell; t_max {T_MAX:g} s, sample_dt {DT:g} s, discard 10 %,"
          f" fit 5-25 % of T = 45 s, EB lag {EB_LAG:g} s (rounded to the grid), tolerance 2,"
          " cv_max 0.25, 95 % CIs")
    print("# columns: fraction of seeds declared ergodic by each component / rule; "
          "'cv' = mean estimated CV(D_i) of the pool, 'cv95' = mean 95 % upper bound")
    cols = list(COMPONENTS) + [f"R:{r}" for r in RULES]
    summary: dict[tuple[int, int], dict[str, list[float]]] = {}
    for n, n_fam in sizes:
        print(f"\n## N = {n} particles x {n_fam} famil{'ies' if n_fam > 1 else 'y'}")
        print(f"{'population':38s} {'truth':11s} " + " ".join(f"{c:>16s}" for c in cols)
              + f" {'cv':>6s} {'cv95':>6s}")
        t0 = time.perf_counter()
        agg = summary.setdefault((n, n_fam), {"fn": [], "fp": []})
        for pop, (truth, _) in POPULATIONS.items():
            if pop.startswith("families differ") and n_fam == 1:
                continue
            rows = [one(pop, n, n_fam, s) for s in range(args.seeds)]
            frac = {c: np.mean([r[0][c] for r in rows]) for c in cols}
            cv = np.mean([r[1] for r in rows])
            cvu = np.mean([r[2] for r in rows])
            print(f"{pop:38s} {truth:11s} " + " ".join(f"{frac[c]:16.2f}" for c in cols)
                  + f" {cv:6.3f} {cvu:6.3f}")
            if truth == "ergodic":
                agg["fn"].append({c: 1 - frac[c] for c in cols})
            elif truth == "non-ergodic":
                agg["fp"].append({c: frac[c] for c in cols})
            sys.stdout.flush()
        print(f"# {time.perf_counter() - t0:.0f} s")
    print("\n## Worst-case error rates per rule (max over the scored populations)")
    print(f"{'size':10s} " + " ".join(f"{c:>16s}" for c in cols))
    for (n, n_fam), agg in summary.items():
        for kind in ("fn", "fp"):
            worst = {c: max(r[c] for r in agg[kind]) for c in cols}
            print(f"{f'{n}x{n_fam} {kind}':10s} " + " ".join(f"{worst[c]:16.2f}" for c in cols))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
