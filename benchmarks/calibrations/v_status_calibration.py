"""Calibration of v_status "accelerating" and of the acceleration a's CI (bbb.analysis.transport)
on synthetic ensembles with known answers, at the small ensembles a conveyor row may hold.

    .venv/bin/python -m benchmarks.calibrations.v_status_calibration [--seeds 1000]

Prints a table (commit it as benchmarks/results/v-status-calibration-<date>.txt).  The rule
itself -- "accelerating" where the CI of dv = v(2nd half) − v(1st half) lies beyond ±(5 % |v| +
k SE(v) + 1e-6 mm/s), k from bbb/analysis/transport_rules.json -- was fixed by
benchmarks/calibrations/transport_rules.py on ensembles of 128 and 256 particles; this script runs the very
functions ``transport`` runs (drift_velocity, drift_change, steady_tolerance, v_status, a =
2 dv / T_a) and measures, before the rule is applied to a table:

false flags   the share of steady drifting ensembles (transport_rules.STEADY: Brownian, a
              spread of D, jumpy, persistent, stuck and running particles) called
              "accelerating", with its Wilson 95 % upper bound, at N = 8, 32, 128 particles;
              the stated rate is transport_rules.MAX_FALSE (1 %);
detection     the share of uniformly accelerating ensembles (Brownian D = 2 mm²/s plus a t²/2,
              a per particle drawn around a mean, or all alike) called "accelerating";
coverage      the share of those whose a CI [a_lo, a_hi] holds the population's mean
              acceleration (nominal 95 %).

Sampling as the transport scenes (transport_rules: 50 s every 0.5 s, discard 10 %, fit lags
5-25 % of the analysed 45 s), 1000 bootstrap resamples.
"""

from __future__ import annotations

import argparse
import sys
import time
import zlib

import numpy as np

from bbb.analysis.stats.proportion import wilson
from bbb.analysis.transport import (
    ACCELERATING,
    INDEPENDENT,
    drift_change,
    drift_velocity,
    steady_tolerance,
    v_status,
)
from benchmarks.calibrations.transport_rules import FIT, MAX_FALSE, N_RESAMPLES, STEADY, TIMES, machine

SIZES = (8, 32, 128)
T_A = TIMES[-1] - FIT["discard"] * TIMES[-1]  # s, the analysed duration
#: name -> (mean acceleration a mm/s², spread of a over particles mm/s²)
ACCELERATIONS = {
    "a = -0.005 (slight), alike": (-0.005, 0.0),
    "a = -0.02, alike": (-0.02, 0.0),
    "a = -0.05 (mild), alike": (-0.05, 0.0),
    "a = -0.2, alike": (-0.2, 0.0),
    "a = -1, spread 0.5": (-1.0, 0.5),
    "a = -25 (runaway), spread 10": (-25.0, 10.0),
}


def _brownian_plus(a: float, spread: float):
    make = STEADY["brownian D 2, v 3"][1]

    def gen(rng, n):
        ai = a + spread * rng.standard_normal(n)
        return make(rng, n) + 0.5 * ai[:, None] * TIMES[None, :] ** 2
    return gen


def _one(x: np.ndarray, s: int) -> tuple[bool, float, float, float]:
    """(called accelerating, a, a_lo, a_hi) as transport() computes them."""
    v = drift_velocity(x, TIMES, n_resamples=N_RESAMPLES, seed=s, **FIT)
    dv = drift_change(x, TIMES, n_resamples=N_RESAMPLES, seed=s + 10**6, **FIT)
    status = v_status(x.shape[0], INDEPENDENT, dv, steady_tolerance(*v))
    return (status == ACCELERATING, *(2.0 * q / T_A for q in dv))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=1000)
    args = ap.parse_args(argv)
    t0 = time.time()
    print(f"# v_status calibration, {machine()}; {args.seeds} ensembles per cell")
    print("\n## false flags: steady drifts called 'accelerating' (stated rate "
          f"{MAX_FALSE:.0%})\n")
    print("| population | N | flagged | Wilson 95 % upper |")
    print("| --- | --- | --- | --- |")
    worst = 0.0
    for n in SIZES:
        for name, (_, make) in STEADY.items():
            k = 0
            for s in range(args.seeds):
                rng = np.random.default_rng([n, s, zlib.crc32(name.encode())])
                k += _one(make(rng, n), s)[0]
            share, _, hi = wilson(k, args.seeds)
            worst = max(worst, share)
            print(f"| {name} | {n} | {share:.3f} | {hi:.3f} |")
    print(f"\nworst false-flag rate {worst:.3f} (stated {MAX_FALSE:.0%})")
    print("\n## accelerations: detection and coverage of a's 95 % CI\n")
    print("| population | N | flagged | a's CI covers the population's mean a |")
    print("| --- | --- | --- | --- |")
    for n in SIZES:
        for name, (a, spread) in ACCELERATIONS.items():
            gen = _brownian_plus(a, spread)
            flags = hits = 0
            for s in range(args.seeds):
                rng = np.random.default_rng([n, s, 3, zlib.crc32(name.encode())])
                acc, _, lo, hi = _one(gen(rng, n), s)
                flags += acc
                hits += lo <= a <= hi  # the population's mean acceleration
            print(f"| {name} | {n} | {flags / args.seeds:.3f} | {hits / args.seeds:.3f} |")
    print(f"\n{time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
