"""Calibration of the ergodicity rule on synthetic populations with a known D spread.

    .venv/bin/python -m benchmarks.calibrations.ergodicity_calibration [--seeds 100] [--sizes 64x3,1024x3]
        [--json bbb/analysis/stats/ergodicity_calibration.json]

Prints a table; commit the output as benchmarks/results/ergodicity-calibration-<date>.txt
(docs/statistics.md explains it); with --json also the worst error rates per rule and size
(``bbb.analysis.stats.RULE_ERROR_RATES`` reads them from bbb/analysis/stats/ergodicity_calibration.json) and
the coverage of the CV² interval per population.  For every population (law x per-particle D spread) and
ensemble size, ``bbb.analysis.stats.ergodic_verdict`` runs on ``--seeds`` independent samples with
the real scenes' sampling: t_max = 50 s, sample_dt = 0.5 s, discard 10 %, fit lags 5-25 %
and EB lag 5 % of the analysed T = 45 s; three families (rest/dropped/launched) of N
particles each (ergodicity scene: N = 1024; draft: 64) or one family of 4096 (Fig. 2).
Each column is the fraction of samples a rule component (or rule) declares ergodic.
'cv2' is the mean signed CV² = 2 EB - EB(T/2) of the pool, 'cov2' the share of samples whose
95 % CI of it holds the population's true CV² (Gamma spread: CV²; mixtures: their exact
value; families differing: that of D = 1, 1.1, 1.2 pooled).

Truth: every population but ``families differ`` has the same law in every family.
'ergodic' rows are CV = 0 (a pass is correct: the column is 1 - false-negative rate);
non-ergodic rows are CV >= 50 % or a mixture of bouncing and creeping particles (a pass
is a false positive).  CV 5-25 % rows are reported, not scored.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import sys
import time

import numpy as np

from bbb.analysis.stats import RULES, ergodic_verdict
from bbb.analysis.stats import synthetic as syn

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


def _cv2_mixture(q: float, creep: float = 0.01) -> float:
    """CV² of D_i for a share q at D = 1 and the rest at creep (exact shares)."""
    d = np.array([1.0, creep])
    w = np.array([q, 1.0 - q])
    m = float(w @ d)
    return float(w @ (d - m) ** 2) / m**2


# name -> (truth, generator or None, true CV² of the pooled D_i)
POPULATIONS: dict[str, tuple[str, object, float]] = {}
for _law_name in ("brownian", "persistent", "jumpy"):
    for _cv in CVS:
        POPULATIONS[f"{_law_name} CV {_cv:.0%}"] = (_truth(_cv), _law(_law_name, _cv), _cv**2)
for _q in (0.9, 0.5, 0.1):
    POPULATIONS[f"mixture {_q:.0%} bouncing"] = (
        "non-ergodic",
        (lambda q: lambda rng, n: syn.mixture(rng, n, N_SAMPLES, DT, 1.0, q))(_q),
        _cv2_mixture(_q))
POPULATIONS["families differ (D x1, x1.1, x1.2)"] = (
    "non-ergodic", None, float(np.var([1.0, 1.1, 1.2]) / 1.1**2))

COMPONENTS = ("agree", "level", "decay", "spread")


def one(pop: str, n: int, n_fam: int, seed: int) -> tuple[dict[str, bool], float, float, bool]:
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(n, n_fam, len(pop))))
    _, make, cv2_true = POPULATIONS[pop]
    if make is None:  # homogeneous Brownian families whose D differ by 10 % steps
        fams = {name: syn.brownian(rng, np.full(n, 1.0 + 0.1 * k), N_SAMPLES, DT)
                for k, name in enumerate(FAMILIES[:n_fam])}
    else:
        fams = {name: make(rng, n) for name in FAMILIES[:n_fam]}
    times = np.arange(N_SAMPLES) * DT
    v = ergodic_verdict(fams, times, lag=EB_LAG, n_resamples=400, seed=seed, **FIT)
    parts = {"agree": v.agreement_ok, "level": v.level_ok, "decay": v.decay_ok,
             "spread": v.spread_ok}
    key = "(pooled)" if "(pooled)" in v.cv2_hat else next(iter(v.cv2_hat))
    out = dict(parts)
    for rule, (decide, _) in RULES.items():
        out[f"R:{rule}"] = bool(decide(parts))
    return out, v.cv2_hat[key], v.cv_upper, bool(v.cv2_lo <= cv2_true <= v.cv2_hi)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--sizes", default="64x3,1024x3,4096x1",
                    help="comma-separated N x families, e.g. 1024x3")
    ap.add_argument("--json", help="also write the worst error rates and CV² coverage here")
    args = ap.parse_args(argv)
    sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    print(f"# bbb ergodicity-rule calibration  {datetime.datetime.now():%Y-%m-%dT%H:%M:%S}")
    print(f"# CPU: {platform.processor() or platform.machine()}  ({os.cpu_count()} cores)  "
          f"python {platform.python_version()}  numpy {np.__version__}")
    print(f"# {args.seeds} seeds per cell; t_max {T_MAX:g} s, sample_dt {DT:g} s, discard 10 %,"
          f" fit 5-25 % of T = 45 s, EB lag {EB_LAG:g} s (rounded to the grid), tolerance 2,"
          " cv_max 0.25, 95 % CIs")
    print("# columns: fraction of seeds declared ergodic by each component / rule; "
          "'cv2' = mean signed CV² = 2 EB - EB(T/2) of the pool, 'cv95' = mean 95 % upper "
          "bound of CV (NaN bounds left out), 'cov2' = share of seeds whose 95 % CI of CV² "
          "holds the true CV²")
    cols = list(COMPONENTS) + [f"R:{r}" for r in RULES]
    summary: dict[tuple[int, int], dict[str, list[float]]] = {}
    coverage: dict[str, dict[str, float]] = {}
    for n, n_fam in sizes:
        print(f"\n## N = {n} particles x {n_fam} famil{'ies' if n_fam > 1 else 'y'}")
        print(f"{'population':38s} {'truth':11s} " + " ".join(f"{c:>16s}" for c in cols)
              + f" {'cv2':>7s} {'cv95':>6s} {'cov2':>5s}")
        t0 = time.perf_counter()
        agg = summary.setdefault((n, n_fam), {"fn": [], "fp": []})
        for pop, (truth, _, _) in POPULATIONS.items():
            if pop.startswith("families differ") and n_fam == 1:
                continue
            rows = [one(pop, n, n_fam, s) for s in range(args.seeds)]
            frac = {c: np.mean([r[0][c] for r in rows]) for c in cols}
            cv2 = np.mean([r[1] for r in rows])
            cvu = np.nanmean([r[2] for r in rows])
            cov2 = np.mean([r[3] for r in rows])
            coverage.setdefault(f"{n}x{n_fam}", {})[pop] = round(float(cov2), 3)
            print(f"{pop:38s} {truth:11s} " + " ".join(f"{frac[c]:16.2f}" for c in cols)
                  + f" {cv2:7.4f} {cvu:6.3f} {cov2:5.2f}")
            if truth == "ergodic":
                agg["fn"].append({c: 1 - frac[c] for c in cols})
            elif truth == "non-ergodic":
                agg["fp"].append({c: frac[c] for c in cols})
            sys.stdout.flush()
        print(f"# {time.perf_counter() - t0:.0f} s")
    print("\n## Worst-case error rates per rule (max over the scored populations)")
    print(f"{'size':10s} " + " ".join(f"{c:>16s}" for c in cols))
    rates: dict[str, dict[str, dict[str, float]]] = {r: {} for r in RULES}
    for (n, n_fam), agg in summary.items():
        for kind in ("fn", "fp"):
            worst = {c: max(r[c] for r in agg[kind]) for c in cols}
            print(f"{f'{n}x{n_fam} {kind}':10s} " + " ".join(f"{worst[c]:16.2f}" for c in cols))
            for r in RULES:
                rates[r].setdefault(f"{n}x{n_fam}", {})[kind] = round(float(worst[f"R:{r}"]), 2)
    if args.json:
        out = {"benchmark": "benchmarks/calibrations/ergodicity_calibration.py",
               "date": f"{datetime.date.today()}", "seeds": args.seeds,
               "worst_error_rates": rates, "cv2_ci_coverage": coverage}
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1)
            fh.write("\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
