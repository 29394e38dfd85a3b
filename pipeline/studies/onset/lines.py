"""The onset maps read line by line: a map's long D table split into its grid lines (α, R)
or (α, depth), each a D(f) curve, and the onset located on each as the D(f, α) map locates
it (:func:`pipeline.claims.measures.onset_ci`: the lowest f whose D_lo exceeds 1 % of the
line's largest D, with its CI).  Units: f in Hz, R and depth in mm, D in mm²/s."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ...claims.claim import Quantity
from ...claims.measures import onset_ci

__all__ = ["COLS", "AXES", "grid_lines", "onset", "step_of"]

COLS = ("D", "D_lo", "D_hi")
#: each scene's second grid axis (the first is alpha)
AXES = {"onset_map": "R", "onset_sine": "depth"}


def grid_lines(table: pd.DataFrame | None, axis: str) -> dict[tuple[float, float], pd.DataFrame]:
    """{(α, axis value): that line's rows sorted by f} of the long table (columns f, alpha,
    ``axis``, D, ...); {} if None or without the columns."""
    if table is None or table.empty or "alpha" not in table or axis not in table:
        return {}
    out = {}
    for (a, v), rows in table.groupby(["alpha", axis], sort=True):
        out[(float(a), float(v))] = rows.sort_values("f").reset_index(drop=True)
    return out


def onset(line: pd.DataFrame) -> Quantity:
    """The onset of diffusion on one line (Hz) with its CI (:func:`onset_ci`); NaN when no
    point of the line rises above the threshold."""
    if line is None or line.empty or not np.isfinite(line["D"].to_numpy(float)).any():
        return Quantity(math.nan)
    return onset_ci(line, COLS)


def step_of(scene: str) -> float:
    """The grid step along f (Hz) of the shipped scene ``scene``: the claims' band."""
    from ...workflow.scenes import load_scene

    f = np.asarray(load_scene(scene).frequencies, dtype=float)
    return float(np.median(np.diff(f)))
