"""D(f) curves in a reduce table and their significant extrema: the columns of a family's
curve, the families a table holds, and the extrema rule the claims and reports read.  f in Hz,
D in mm²/s."""

from __future__ import annotations

import numpy as np
import pandas as pd

from bbb.analysis.extrema import Extremum, find_extrema

__all__ = ["DEPTH_FRACTION", "curve_columns", "curve_extrema", "families"]

DEPTH_FRACTION = 0.01  # extrema: differences below this fraction of max D do not count


def curve_columns(table: pd.DataFrame, family: str | None) -> tuple[str, str, str]:
    """The (D, lo, hi) columns of ``family``'s curve in a reduce table (None: the pooled D)."""
    if family is None:
        return "D", "D_lo", "D_hi"
    return f"D_{family}", f"D_{family}_lo", f"D_{family}_hi"


def curve_extrema(table: pd.DataFrame, cols: tuple[str, str, str]) -> list[Extremum]:
    """Significant extrema of one D(f) curve (D in mm²/s, f in Hz; differences below 1 % of
    its max D ignored): the extrema rule of the claims and the report."""
    D = table[cols[0]].to_numpy(float)
    depth = DEPTH_FRACTION * float(np.nanmax(D)) if np.isfinite(D).any() else 0.0
    return find_extrema(table["f"], D, table[cols[1]], table[cols[2]], min_depth=max(depth, 0.0))


def families(table: pd.DataFrame) -> list[str]:
    """The initial-condition families of a reduce table (from its D_<fam>_lo columns)."""
    return [c[2:-3] for c in table.columns if c.startswith("D_") and c.endswith("_lo")
            and c != "D_lo" and not c.startswith("D_half")]
