"""The D(f, α) map read line by line: which α lines are whole D(f) curves, and the features
located on each (the onset of diffusion, the first maximum above it, where k_max reaches n).

Refinement adds α values between grid lines only at the frequencies where D(α) jumps or
has an extremum, so a refined α holds a few points, not a curve.  The *judged* lines are the
α values the scene lists in its ``[grid]`` (:func:`listed_alphas`), whatever refinement added;
their features use every point they hold, refined frequencies included.  Units: f in Hz, D in
mm²/s.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from bbb import Params
from bbb.analysis.period1 import frequency_at, gamma_1, gamma_prime

from ...claims.claim import Quantity
from ...claims.curves import curve_extrema
from ...claims.measures import grid_step, onset_ci

__all__ = ["COLS", "THRESHOLDS", "threshold_frequency", "listed_alphas", "judged_lines", "onset",
           "first_max_above", "first_reaching", "cut"]

COLS = ("D", "D_lo", "D_hi")
#: the flat-floor thresholds the onset is judged against: name -> (symbol, Γ(α))
THRESHOLDS = {"gamma_prime": ("Γ'", gamma_prime), "gamma_1": ("Γ₁", gamma_1)}


def threshold_frequency(name: str, alpha, preset: str = "klages2004"):
    """f (Hz) at which the preset's floor (A, g) reaches the threshold ``name`` (gamma_prime,
    gamma_1) at restitution ``alpha``."""
    p = Params.preset(preset, f=1.0)
    return frequency_at(THRESHOLDS[name][1](alpha), p.A, p.g)


def listed_alphas(scene: str = "dissipation") -> tuple[float, ...]:
    """The α values the scene ``scene`` lists in its ``[grid]`` (the shipped scene, not its
    draft: a draft lists some of them)."""
    from ...workflow.scenes import load_scene

    return tuple(float(v) for v in dict(load_scene(scene).grid)["alpha"])


def judged_lines(table: pd.DataFrame | None, listed, axis: str = "alpha"
                 ) -> dict[float, pd.DataFrame]:
    """{α: the line's rows sorted by f, index 0..n-1} for every α of ``listed`` that the long
    table ``table`` (columns f, ``axis``, ...) holds, in increasing α; {} if None."""
    if table is None or table.empty or axis not in table:
        return {}
    out = {}
    for a in sorted(float(v) for v in listed):
        rows = table[np.isclose(table[axis].to_numpy(float), a, rtol=0, atol=1e-9)]
        if len(rows):
            out[a] = rows.sort_values("f").reset_index(drop=True)
    return out


def onset(line: pd.DataFrame) -> Quantity:
    """The onset of diffusion on one line: the lowest f whose D_lo exceeds 1 % of the line's
    largest D, with the CI of :func:`pipeline.claims.measures.onset_ci` (Hz)."""
    return onset_ci(line, COLS)


def first_max_above(line: pd.DataFrame, f_from: float) -> Quantity:
    """The first significant maximum of D(f) above ``f_from`` Hz (the extrema rule of the
    paper's claims: family-wise α = 0.05, depth ≥ 1 % of the line's max D), located by its
    position range ± half the grid spacing (Hz); NaN if there is none."""
    if not math.isfinite(f_from):
        return Quantity(math.nan)
    h = grid_step(line) / 2
    for e in curve_extrema(line, COLS):
        if e.kind == "max" and e.f > f_from:
            return Quantity(e.f, e.f_lo - h, e.f_hi + h, "Hz",
                            "position range ± half the grid spacing")
    return Quantity(math.nan)


def first_reaching(line: pd.DataFrame, column: str, n: float) -> Quantity:
    """The lowest f (Hz) where ``column`` (k_max) reaches n, with the CI where its bootstrap
    upper / lower bound (``<column>_hi`` / ``_lo``) first does, ± half the grid spacing; NaN if
    never (the rule of the paper's claim on the spiral's loops)."""
    f = line["f"].to_numpy(float)
    h = grid_step(line) / 2

    def first(col):
        if col not in line:
            return math.nan
        i = np.flatnonzero(np.nan_to_num(line[col].to_numpy(float), nan=-1.0) >= n)
        return float(f[i[0]]) if i.size else math.nan

    v, early, late = first(column), first(f"{column}_hi"), first(f"{column}_lo")
    return Quantity(v, early - h if math.isfinite(early) else math.nan,
                    late + h if math.isfinite(late) else math.inf, "Hz",
                    f"{column}'s bootstrap CI reaching {n:g}, ± half the grid spacing")


def cut(table: pd.DataFrame | None, axis: str, value: float) -> pd.DataFrame | None:
    """The rows of ``table`` at ``axis`` = value (to 1e-9), sorted by f; None if none."""
    if table is None or axis not in table:
        return None
    rows = table[np.isclose(table[axis].to_numpy(float), value, rtol=0, atol=1e-9)]
    return rows.sort_values("f").reset_index(drop=True) if len(rows) else None
