"""Calibration of the contrast rule (``bbb.analysis.gk_contrast.carrier``) on jump sequences with a
known split of the log contrast into random walk and memory.

    .venv/bin/python -m benchmarks.calibrations.contrast_calibration [--replicates 100] [--particles 1024]
        [--steps 3000] [--write]

Prints a table; with ``--write`` also writes it to benchmarks/results/contrast-calibration-
<date>.txt and the rule's numbers (θ, the CI level, the measured rates) to
bbb/analysis/gk_contrast_rule.json (``bbb.analysis.gk_contrast.calibrated_rule``), which the mechanisms
table and claims read.

Synthetic "frequencies": each particle's jumps are a stationary AR(1) sequence,
C(k) = σ_i² ρ^k, so D_0 = ⟨σ²⟩/(2T) and D_∞ = D_0 m with the memory factor m = (1+ρ)/(1−ρ).
An extremum a (a maximum, ln D_∞(a)/D_∞(b) = L > 0) is contrasted with neighbours b built
with a known memory share s of L: D_0(b) = D_0(a) e^{−(1−s)L}, m(b) = m(a) e^{−sL}:
s = 1 all memory (same jump variance, less correlation), s = 0 all random walk (same
correlation, smaller variance), s = 0.5 mixed, s = 1.3 / −0.3 memory / random walk working
against a smaller other part; "null": b = a (no contrast, whatever the L of the row).  Three
regimes: "per period" (m(a) = 60, ρ = 0.967, identical particles, T fixed: the memory of the
scene's 58-62 Hz, K ≈ 140 periods), "per period, long memory" (m(a) = 200, ρ = 0.990: 80 Hz,
K ≈ 450) and "per collision" (m(a) = 8, ρ = 0.78, per-particle σ_i log-normal with sd 0.3 of
ln σ and per-particle mean steps T_i with CV 0.2, as the collision rate differs between
particles), each at L = 0.25 and L = ln 2.

The rule: θ = 2/3 (a definition: the carrier holds at least two thirds of the log contrast,
twice the other part); the CI level is chosen here: the lowest of 0.90, 0.95, 0.99 at which
no case gives a wrong verdict (a split other than the true one, or "wrong sign"; in the null
case any split) in more than 5 % of the replicates.  "undecided" and "not resolved" are no
decision, not errors.  Sizes as in the mechanisms scene: 1024 particles, ~2600-4400 jumps per
period and ≤ 4000 per collision; 1000 bootstrap resamples.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np

from bbb.analysis.gk_contrast import RULE_FILE, SPLITS, carrier, contrast
from bbb.analysis.greenkubo import expansion
from benchmarks.common import ROOT, cpu_name

THETA = 2.0 / 3.0
LEVELS = (0.90, 0.95, 0.99)
MAX_WRONG = 0.05
N_RESAMPLES = 1000
SHARES = (-0.3, 0.0, 0.5, 1.0, 1.3)
# regime -> (memory factor of a, sd of ln σ_i, CV of the per-particle step)
REGIMES = {"per period": (60.0, 0.0, 0.0), "per period, long memory": (200.0, 0.0, 0.0),
           "per collision": (8.0, 0.3, 0.2)}
CONTRASTS = (0.25, math.log(2.0))


def expected(share: float | None) -> str:
    """The true verdict of a case: None is the null case (no contrast)."""
    if share is None:
        return "not resolved"
    return "memory" if share >= THETA else "random walk" if share <= 1 - THETA else "both"


def ar1(rng: np.random.Generator, sigma: np.ndarray, m: float, n_steps: int) -> np.ndarray:
    """Stationary AR(1) jumps, per-particle σ_i, memory factor m = (1+ρ)/(1−ρ)."""
    rho = (m - 1.0) / (m + 1.0)
    eps = rng.standard_normal((sigma.size, n_steps)) * math.sqrt(1.0 - rho * rho)
    x = np.empty((sigma.size, n_steps))
    x[:, 0] = rng.standard_normal(sigma.size)
    for n in range(1, n_steps):
        x[:, n] = rho * x[:, n - 1] + eps[:, n]
    return x * sigma[:, None]


def frequency(rng, n_p, n_steps, var, m, sd_sigma, cv_step, seed):
    """One synthetic frequency's expansion: ⟨σ²⟩ = var, memory factor m."""
    # log-normal σ_i with ⟨σ²⟩ = var exactly: E[exp(2 sd z)] = exp(2 sd²)
    sigma = math.sqrt(var) * np.exp(sd_sigma * rng.standard_normal(n_p) - sd_sigma**2)
    step = np.clip(1.0 + cv_step * rng.standard_normal(n_p), 0.2, None) if cv_step else 1.0
    return expansion(ar1(rng, sigma, m, n_steps), step, n_resamples=N_RESAMPLES, seed=seed)


def run(n_rep: int, n_p: int, n_steps: int) -> tuple[dict, float]:
    """verdict counts[(regime, L, share)][level][verdict] and share-CI coverage counts."""
    counts: dict = {}
    t0 = time.perf_counter()
    for rep in range(n_rep):
        for ri, (regime, (m_a, sd, cv)) in enumerate(REGIMES.items()):
            for li, L in enumerate(CONTRASTS):
                ss = np.random.SeedSequence(2004, spawn_key=(rep, ri, li))
                rng = np.random.default_rng(ss)
                seeds = iter(ss.generate_state(len(SHARES) + 2))
                a = frequency(rng, n_p, n_steps, 1.0, m_a, sd, cv, int(next(seeds)))
                cases = [(None, 1.0, m_a)] + [(s, math.exp(-(1 - s) * L), m_a * math.exp(-s * L))
                                              for s in SHARES]
                for s, var_b, m_b in cases:
                    b = frequency(rng, n_p, n_steps, var_b, m_b, sd, cv, int(next(seeds)))
                    key = (regime, L, s)
                    cell = counts.setdefault(key, {lv: {} for lv in LEVELS} | {"cover": {}})
                    true_share = s
                    for lv in LEVELS:
                        c = contrast(a, b, lv)
                        v = carrier(c, "max", THETA)
                        cell[lv][v] = cell[lv].get(v, 0) + 1
                        if true_share is not None:
                            inside = c.share[1] <= true_share <= c.share[2]
                            cell["cover"][lv] = cell["cover"].get(lv, 0) + int(inside)
        print(f"# replicate {rep + 1}/{n_rep}  {time.perf_counter() - t0:.0f} s", file=sys.stderr,
              flush=True)
    return counts, time.perf_counter() - t0


def wrong(share: float | None, verdicts: dict) -> int:
    exp = expected(share)
    if share is None:
        return sum(n for v, n in verdicts.items() if v in SPLITS or v == "wrong sign")
    return sum(n for v, n in verdicts.items()
               if (v in SPLITS and v not in ("undecided", exp)) or v == "wrong sign")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--replicates", type=int, default=100)
    ap.add_argument("--particles", type=int, default=1024)
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--write", action="store_true",
                    help=f"write the table to benchmarks/results/ and the rule to {RULE_FILE.name}")
    ap.add_argument("--json", type=Path, help="write the calibration JSON here (make calibrate)")
    args = ap.parse_args()
    counts, seconds = run(args.replicates, args.particles, args.steps)
    n = args.replicates
    today = datetime.date.today().isoformat()
    L = [f"# bbb contrast-rule calibration  {today}",
         f"# CPU: {cpu_name()} ({os.cpu_count()} cores)  python {platform.python_version()}  "
         f"numpy {np.__version__};  {seconds:.0f} s",
         f"# {n} replicates x {args.particles} particles x {args.steps} jumps, "
         f"{N_RESAMPLES} bootstrap resamples; θ = {THETA:.4f}; rates are fractions of the "
         "replicates", "",
         "| regime | L | true share | expected | level | memory | random walk | both | undecided "
         "| not resolved | wrong sign | wrong | share CI covers |",
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    worst = {lv: 0.0 for lv in LEVELS}
    cases = []
    for (regime, Lc, s), cell in counts.items():
        for lv in LEVELS:
            v = cell[lv]
            w = wrong(s, v) / n
            worst[lv] = max(worst[lv], w)
            cover = cell["cover"].get(lv, 0) / n if s is not None else math.nan
            rates = {k: v.get(k, 0) / n for k in ("memory", "random walk", "both", "undecided",
                                                  "not resolved", "wrong sign")}
            cases.append({"regime": regime, "L": Lc, "share": s, "expected": expected(s),
                          "level": lv, "wrong": w, "share_cover": cover, **rates})
            L.append(f"| {regime} | {Lc:.3f} | {'null (b = a)' if s is None else f'{s:g}'} | "
                     f"{expected(s)} | {lv:g} | "
                     + " | ".join(f"{r:.2f}" for r in rates.values())
                     + f" | {w:.2f} | {'' if s is None else f'{cover:.2f}'} |")
    ok = [lv for lv in LEVELS if worst[lv] <= MAX_WRONG]
    level = min(ok) if ok else max(LEVELS)
    L += ["", "worst wrong-verdict rate per level: "
          + ", ".join(f"{lv:g}: {worst[lv]:.3f}" for lv in LEVELS),
          f"chosen level: {level:g} (the lowest whose worst wrong rate ≤ {MAX_WRONG:g}"
          + ("" if ok else "; none met it: the highest is used") + ")"]
    decided = {e: float(np.mean([c[e] for c in cases if c["level"] == level
                                 and c["expected"] == e and c["share"] is not None]))
               for e in ("memory", "random walk", "both")}
    L.append("right-verdict rate at that level, mean over regimes and L: "
             + ", ".join(f"{e} {r:.2f}" for e, r in decided.items()))
    text = "\n".join(L)
    print(text)
    out = ROOT / "benchmarks" / "results" / f"contrast-calibration-{today}.txt"
    if args.write:
        out.write_text(text + "\n")
        print(f"wrote {out.relative_to(ROOT)}", file=sys.stderr)
    path = RULE_FILE if args.write else args.json
    if path:
        rule = {"theta": THETA, "ci": level, "max_wrong": MAX_WRONG,
                "worst_wrong": worst[level], "right_rate": decided,
                "replicates": n, "particles": args.particles, "steps": args.steps,
                "n_resamples": N_RESAMPLES, "source": f"benchmarks/results/{out.name}",
                "cases": [c for c in cases if c["level"] == level]}
        Path(path).write_text(json.dumps(rule, indent=1) + "\n")
        print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
