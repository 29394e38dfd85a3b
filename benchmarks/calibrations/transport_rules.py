"""Calibration of bbb.analysis.transport's two checks on synthetic ensembles with known answers.

    .venv/bin/python -m benchmarks.calibrations.transport_rules [--seeds 1000] [--write]

Prints the tables (commit them as benchmarks/results/transport-rules-<date>.txt); with
``--write`` also writes the chosen numbers and their error rates to bbb/analysis/transport_rules.json,
which bbb.analysis.transport reads.  Sampling as the transport scenes: t_max = 50 s every 0.5 s,
discard 10 %, fit lags 5-25 % of the analysed T = 45 s, 1000 bootstrap resamples, ensembles
of 128 and 256 particles (the sliding and the hopping scenes).

The rules, and how their numbers are chosen (fixed before any store was reduced with them):

steady     not steady when the CI of dv = v(2nd half) − v(1st half) lies beyond
           ±(5 % |v| + k SE(v) + 1e-6 mm/s), SE(v) read off v's 95 % CI.  k = the smallest
           value of K_GRID whose false-flag rate is ≤ 1 % on every steady population at both
           sizes.  Detection is reported for accelerations x += a t²/2 whose true dv is m
           standard errors of v (m = 2 … 32) and for a runaway (a = 50 mm/s²).
diffusive  D about the drift is not diffusive when the 95 % CI of its MSD's slope ratio (the
           slope over the upper half of the fit lags / over the lower half; 1 for any MSD
           linear in the lag, ~1.9 for ballistic spread) lies above 1 + τ.  τ = the smallest
           value of TAU_GRID whose false-flag rate is ≤ 1 % on every diffusive population at
           both sizes; detection is reported on populations of particles that run at different
           speeds (stuck and running, a spread of running speeds, switching slower than the
           run).
Populations marked "grey" are reported, not scored.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import sys
import time
import zlib
from pathlib import Path

import numpy as np

from bbb.analysis.stats import synthetic as syn
from bbb.analysis.transport import drift_change, drift_velocity, msd_slope_ratio, per_particle_drift
from benchmarks.common import ROOT

T_MAX, DT = 50.0, 0.5
TIMES = np.arange(round(T_MAX / DT) + 1) * DT
FIT = dict(fit_from=0.05 * 45.0, fit_to=0.25 * 45.0, discard=0.10)
SIZES = (128, 256)
N_RESAMPLES = 1000
K_GRID = (0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0)
TAU_GRID = (0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5)
MAX_FALSE = 0.01
OUT = ROOT / "bbb" / "analysis" / "transport_rules.json"


def _drifting(law: str, D: float, v: float, cv: float = 0.0, **opt):
    def make(rng, n):
        return syn.LAWS[law](rng, syn.gamma_D(rng, n, D, cv), TIMES.size, DT, **opt) + v * TIMES
    return make


def _stuck_runners(p_stuck: float, spread: float = 40.0, v_run: float = -300.0):
    """A fraction p_stuck at rest (D = 1e-3 mm²/s), the rest running at N(v_run, spread²)
    mm/s each, D = 100 mm²/s about it: tilt 2°, 58 Hz (a fixed speed per particle)."""
    def make(rng, n):
        stuck = rng.random(n) < p_stuck
        v = np.where(stuck, 0.0, rng.normal(v_run, spread, n))
        d = np.where(stuck, 1e-3, 100.0)
        return syn.brownian(rng, d, TIMES.size, DT) + v[:, None] * TIMES
    return make


def _telegraph(dwell: float, v_run: float = -300.0, D: float = 1.0):
    """Switching between stuck and running at v_run with a mean dwell (s) in each state."""
    def make(rng, n):
        sub = 20
        h = DT / sub
        running = rng.random(n) < 0.5
        steps = np.empty((n, (TIMES.size - 1) * sub))
        flip = rng.random(steps.shape) < h / dwell
        for k in range(steps.shape[1]):
            running ^= flip[:, k]
            steps[:, k] = np.where(running, v_run * h, 0.0)
        x = np.concatenate([np.zeros((n, 1)), np.cumsum(steps, axis=1)[:, sub - 1 :: sub]], 1)
        return x + syn.brownian(rng, np.full(n, D), TIMES.size, DT)
    return make


# name -> (truth, generator); truth: the right answer of the check, or "grey"
WALKS = {  # steady and diffusive: both checks must pass them
    "brownian D 2, v 3": (True, _drifting("brownian", 2.0, 3.0)),
    "brownian D Gamma(2, CV 1), v 0": (True, _drifting("brownian", 2.0, 0.0, cv=1.0)),
    "jumpy (1 mm jumps) D 2, v -5": (True, _drifting("jumpy", 2.0, -5.0)),
}
STEADY = {
    **WALKS,
    "persistent tau 1 s D 5, v 10": (True, _drifting("persistent", 5.0, 10.0, tau=1.0)),
    "7 % stuck, runners -300 +- 40": (True, _stuck_runners(0.07)),
}
DIFFUSIVE = {
    **WALKS,
    "persistent tau 0.5 s D 5": (True, _drifting("persistent", 5.0, 10.0, tau=0.5)),
    "stuck/running, dwell 0.25 s": (True, _telegraph(0.25)),
    "stuck/running, dwell 2 s": ("grey", _telegraph(2.0)),
    "2 % stuck, runners -300 +- 40": (False, _stuck_runners(0.02)),
    "7 % stuck, runners -300 +- 40": (False, _stuck_runners(0.07)),
    "20 % stuck, runners -300 +- 40": (False, _stuck_runners(0.20)),
    "no stuck, runners -300 +- 40": (False, _stuck_runners(0.0)),
    "no stuck, runners -300 +- 10": (False, _stuck_runners(0.0, spread=10.0)),
    "stuck/running, dwell 200 s": (False, _telegraph(200.0)),
}
ACCEL_M = (4.0, 8.0, 16.0, 32.0, 64.0)


def _se(lo: float, hi: float) -> float:
    return (hi - lo) / (2 * 1.959963984540054)


def steady_runs(seeds: int) -> dict:
    """{(population, n): array (seeds, 4) of v, SE(v), dv_lo, dv_hi}."""
    out = {}
    one = drift_change(np.repeat(0.5 * TIMES[None, :] ** 2, 2, 0), TIMES, n_resamples=10, seed=0,
                       **FIT)[0]  # the dv of a = 1 mm/s²
    for n in SIZES:
        for name, (_, make) in STEADY.items():
            out[name, n] = _steady_cells(make, n, seeds, name)
        # accelerations from v = 3 (where 5 % |v| dominates the band) and from v = 0 (where
        # k SE(v) does): a t²/2 whose true dv is m SE(v) of the steady walks
        for v0 in (3.0, 0.0):
            base = _drifting("brownian", 2.0, v0)
            ref = out["brownian D 2, v 3", n] if v0 else _steady_cells(base, n, seeds, "v0")
            se_ref = float(np.median(ref[:, 1]))
            for m in ACCEL_M:
                a = m * se_ref / one
                out[f"from v = {v0:g}: accelerating, dv = {m:g} SE(v)", n] = _steady_cells(
                    lambda rng, k, a=a, base=base: base(rng, k) + 0.5 * a * TIMES**2, n, seeds,
                    f"acc {m}" + (f" v0 {v0:g}" if not v0 else ""))
        out["runaway a = 50 mm/s^2", n] = _steady_cells(
            lambda rng, k: STEADY["brownian D 2, v 3"][1](rng, k) - 25.0 * TIMES**2, n, seeds,
            "runaway")
    return out


def _steady_cells(make, n: int, seeds: int, tag: str) -> np.ndarray:
    rows = []
    for s in range(seeds):
        rng = np.random.default_rng([n, s, zlib.crc32(tag.encode())])
        x = make(rng, n)
        v = drift_velocity(x, TIMES, n_resamples=N_RESAMPLES, seed=s, **FIT)
        dv = drift_change(x, TIMES, n_resamples=N_RESAMPLES, seed=s + 10**6, **FIT)
        rows.append((v[0], _se(v[1], v[2]), dv[1], dv[2]))
    return np.array(rows)


def flagged(cells: np.ndarray, k: float) -> float:
    v, se, lo, hi = cells.T
    tol = 0.05 * np.abs(v) + k * se + 1e-6
    return float(np.mean((lo > tol) | (hi < -tol)))


def exponent_runs(seeds: int) -> dict:
    """{(population, n): array (seeds, 3) of the MSD slope ratio ρ, lo, hi}."""
    out = {}
    for n in SIZES:
        for name, (_, make) in DIFFUSIVE.items():
            rows = []
            for s in range(seeds):
                rng = np.random.default_rng([n, s, 7, zlib.crc32(name.encode())])
                x = make(rng, n)
                v = per_particle_drift(x, TIMES, **FIT).mean()
                rows.append(msd_slope_ratio(x - v * TIMES, TIMES, n_resamples=N_RESAMPLES,
                                            seed=s, **FIT))
            out[name, n] = np.array(rows)
    return out


def choose(rates: dict, truth: dict, grid, what: str) -> float:
    """The smallest grid value whose false-flag rate is ≤ MAX_FALSE on every scored true
    population (rates: {(pop, n): {value: flag rate}})."""
    for g in grid:
        if all(r[g] <= MAX_FALSE for (pop, _), r in rates.items() if truth.get(pop) is True):
            return g
    raise SystemExit(f"no {what} in {grid} keeps false flags ≤ {MAX_FALSE:.0%}")


def machine() -> str:
    """Date, CPU and cores of this run, for the results header."""
    return (f"{datetime.date.today()}, {platform.processor() or platform.machine()}, "
            f"{os.cpu_count()} CPUs, python {sys.version.split()[0]}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=1000)
    ap.add_argument("--write", action="store_true", help=f"write {OUT.name}")
    ap.add_argument("--json", type=Path, help="write the calibration JSON here (make calibrate)")
    args = ap.parse_args(argv)
    t0 = time.time()
    print(f"# bbb.analysis.transport rule calibration, {machine()}; {args.seeds} ensembles per cell")

    st = steady_runs(args.seeds)
    st_rates = {key: {k: flagged(c, k) for k in K_GRID} for key, c in st.items()}
    k = choose(st_rates, {p: t for p, (t, _) in STEADY.items()}, K_GRID, "k")
    print("\n## steady: fraction flagged 'not steady' (tol = 5 % |v| + k SE(v) + 1e-6 mm/s)\n")
    print("| population | N | " + " | ".join(f"k = {g:g}" for g in K_GRID) + " |")
    print("| --- | --- |" + " --- |" * len(K_GRID))
    for (pop, n), r in st_rates.items():
        print(f"| {pop} | {n} | " + " | ".join(f"{r[g]:.3f}" for g in K_GRID) + " |")
    print(f"\nchosen k = {k:g} (smallest with ≤ {MAX_FALSE:.0%} false flags on every steady "
          "population)")

    ex = exponent_runs(args.seeds)
    ex_rates = {key: {t: float(np.mean(c[:, 1] > 1 + t)) for t in TAU_GRID}
                for key, c in ex.items()}
    truth = {p: t for p, (t, _) in DIFFUSIVE.items()}
    tau = choose(ex_rates, truth, TAU_GRID, "tau")
    print("\n## diffusive: fraction flagged 'not diffusive' (CI of the MSD slope ratio above "
          "1 + tau); median ratio\n")
    print("| population | truth | N | median ratio | " + " | ".join(f"tau = {g:g}" for g in TAU_GRID)
          + " |")
    print("| --- | --- | --- | --- |" + " --- |" * len(TAU_GRID))
    for (pop, n), r in ex_rates.items():
        t = truth[pop]
        lab = "grey" if t == "grey" else ("diffusive" if t else "ballistic")
        print(f"| {pop} | {lab} | {n} | {np.median(ex[pop, n][:, 0]):.3f} | "
              + " | ".join(f"{r[g]:.3f}" for g in TAU_GRID) + " |")
    print(f"\nchosen tau = {tau:g} (smallest with ≤ {MAX_FALSE:.0%} false flags on every "
          "diffusive population)")
    print(f"\n{time.time() - t0:.0f} s")
    path = OUT if args.write else args.json
    if path:
        rules = {
            "source": "benchmarks/calibrations/transport_rules.py", "date": str(datetime.date.today()),
            "ensembles_per_cell": args.seeds, "sizes": list(SIZES), "max_false_flags": MAX_FALSE,
            "steady": {"se_factor": k,
                       "false_flags": {f"{p} (N={n})": r[k] for (p, n), r in st_rates.items()
                                       if STEADY.get(p, (None,))[0] is True},
                       "detection": {f"{p} (N={n})": r[k] for (p, n), r in st_rates.items()
                                     if p not in STEADY}},
            "diffusive": {"tolerance": tau,
                          "false_flags": {f"{p} (N={n})": r[tau] for (p, n), r in ex_rates.items()
                                          if truth[p] is True},
                          "detection": {f"{p} (N={n})": r[tau] for (p, n), r in ex_rates.items()
                                        if truth[p] is False},
                          "grey": {f"{p} (N={n})": r[tau] for (p, n), r in ex_rates.items()
                                   if truth[p] == "grey"}},
        }
        Path(path).write_text(json.dumps(rules, indent=1) + "\n", encoding="utf-8")
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
