"""Synthetic D(f, α) maps with known onsets, maxima and ergodicity, for the study's tests."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.studies.dissipation.claims import threshold_frequency

ALPHAS = (0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75, 0.80, 0.85, 0.90, 0.95)
F = np.arange(46.0, 100.5, 1.0)


def line(f_on: float, f_max: float, alpha: float, rel: float = 0.03,
         nonergodic=lambda f, f_on: False) -> pd.DataFrame:
    """One α line: D = 0 (resolved zero) below f_on; above it a peak of 300 mm²/s at f_max on
    a rise to 3000 mm²/s at 100 Hz, CI ± rel; ``ergodic`` False where nonergodic(f, f_on)."""
    rows = []
    for f in F:
        if f < f_on:
            D, lo, hi, stop = 1e-7, 0.0, 2e-7, "resolved zero"
        else:
            D = 300.0 * np.exp(-0.5 * ((f - f_max) / 1.5) ** 2) + 3000.0 * ((f - f_on) / 54.0) ** 2 + 50.0
            lo, hi, stop = D * (1 - rel), D * (1 + rel), "target met"
        rows.append({"f": f, "alpha": alpha, "D": D, "D_lo": lo, "D_hi": hi, "stop": stop,
                     "ergodic": not nonergodic(f, f_on)})
    return pd.DataFrame(rows)


def dmap(onset_of=lambda a: float(np.ceil(threshold_frequency("gamma_prime", a))),
         max_of=lambda a, on: on + 5.0, nonergodic=lambda f, f_on: False,
         refined: bool = True) -> pd.DataFrame:
    """A map over ALPHAS × F; with ``refined``, a few points at α midpoints as refinement adds."""
    parts = [line(onset_of(a), max_of(a, onset_of(a)), a, nonergodic=nonergodic) for a in ALPHAS]
    if refined:
        extra = line(60.0, 65.0, 0.425)
        parts.append(extra[extra["f"].isin([60.0, 61.0, 62.0])])
    return pd.concat(parts, ignore_index=True)
