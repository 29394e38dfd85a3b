"""The D(f, α) map read line by line: which α lines are whole D(f) curves, and the features
located on each (the onset of diffusion, the first maximum above it, where k_max reaches n).

Refinement adds α values between grid lines only at the frequencies where D(α) jumps or
has an extremum, so a refined α holds a few points, not a curve.  A line is *judged* when it
holds every *base* frequency -- those present on at least :data:`BASE_SHARE` of the α values
(the scene's ``[frequencies]``): the scene's own α values, whatever refinement added.  Its
features use every point it has, refined frequencies included.  Units: f in Hz, D in mm²/s.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ...claims.measures import grid_step, onset_ci
from ...claims.record import Quantity
from ..klages2004.measures import curve_extrema

__all__ = ["BASE_SHARE", "COLS", "judged_lines", "onset", "first_max_above", "first_reaching",
           "cut"]

#: a frequency is a base frequency when at least this share of the α values hold it
BASE_SHARE = 0.9
COLS = ("D", "D_lo", "D_hi")


def _f_keys(f) -> np.ndarray:
    return np.round(np.asarray(f, dtype=float) * 1000.0).astype(np.int64)  # 1 mHz


def judged_lines(table: pd.DataFrame | None, axis: str = "alpha") -> dict[float, pd.DataFrame]:
    """{α: the line's rows sorted by f, index 0..n-1} for every judged line (module docstring)
    of the long table ``table`` (columns f, ``axis``, ...), in increasing α; {} if None."""
    if table is None or table.empty or axis not in table:
        return {}
    values = np.unique(table[axis].to_numpy(float))
    keys = _f_keys(table["f"])
    holders = pd.Series(table[axis].to_numpy(float)).groupby(keys).nunique()
    base = set(holders.index[holders >= BASE_SHARE * values.size])
    out = {}
    for a in values:
        rows = table[np.isclose(table[axis].to_numpy(float), a, rtol=0, atol=1e-9)]
        if base <= set(_f_keys(rows["f"])):
            out[float(a)] = rows.sort_values("f").reset_index(drop=True)
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
