"""A line of the D(f, α) map against the committed D(f) curve of the scene without a grid at the
same parameters: where they share frequencies, do they agree within their combined CIs?

At a shared frequency the two D's agree when |D_map − D_ref| ≤ sqrt(h_map² + h_ref²), each h
the half-width of the 95 % CI on the side facing the other value (the CI of a difference of
two independent estimates; where the two runs share chunks, as a map line and the scene with
its seed do, the estimates are positively correlated and the test is lenient, a consistency
check).  A point whose run stopped as "resolved to ±d_resolved" (CI half-width ≤
``d_resolved`` before it was ≤ target_ci · D) is judged at its scene's resolution: its h is at
least that ``d_resolved``.  A frequency where either estimator failed (no D) is not compared and is
counted as such.  Units: f in Hz, D in mm²/s.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ...store.layout import STOP_LEGEND, ZERO

__all__ = ["RESOLVED", "CUT_COLUMNS", "CUT_UNITS", "compare_cut"]

#: the stop of a point whose D is known to ± d_resolved (pipeline.store.layout.STOP_LEGEND)
RESOLVED = STOP_LEGEND[ZERO]
CUT_COLUMNS = ("f", "D", "D_lo", "D_hi", "stop", "D_ref", "D_ref_lo", "D_ref_hi", "stop_ref",
               "d_resolved", "d_resolved_ref", "agree")
#: the units of the cuts table's own columns (``cut`` names the committed scene; ``agree`` 1/0)
CUT_UNITS = {"cut": "", "D_ref": "mm^2/s", "D_ref_lo": "mm^2/s", "D_ref_hi": "mm^2/s",
             "stop_ref": "", "d_resolved": "mm^2/s", "d_resolved_ref": "mm^2/s", "agree": "1"}


def _half(D, lo, hi, other, stop, d_res):
    h = np.where(other >= D, hi - D, D - lo)
    return np.where(stop == RESOLVED, np.maximum(h, d_res), h)


def compare_cut(line: pd.DataFrame, ref: pd.DataFrame, d_resolved: float,
                d_resolved_ref: float) -> pd.DataFrame:
    """One row per frequency the map's ``line`` and the reference table ``ref`` share (to
    1 mHz; columns f, D, D_lo, D_hi, and stop where the scene has a target):
    :data:`CUT_COLUMNS`, ``agree`` 1/0, NaN
    where either D is missing (estimator failed)."""
    # a fixed-size scene (a draft) has no stop column: none of its points stopped at the resolution
    a = line.assign(_k=np.round(line["f"].to_numpy(float) * 1000).astype(np.int64),
                    stop=line["stop"] if "stop" in line else "")
    b = ref.assign(_k=np.round(ref["f"].to_numpy(float) * 1000).astype(np.int64),
                   stop_ref=ref["stop"] if "stop" in ref else "")
    m = a[["_k", "f", "D", "D_lo", "D_hi", "stop"]].merge(
        b[["_k", "D", "D_lo", "D_hi", "stop_ref"]].rename(
            columns={"D": "D_ref", "D_lo": "D_ref_lo", "D_hi": "D_ref_hi"}), on="_k")
    D, Dr = m["D"].to_numpy(float), m["D_ref"].to_numpy(float)
    h = _half(D, m["D_lo"].to_numpy(float), m["D_hi"].to_numpy(float), Dr,
              m["stop"].to_numpy(str), d_resolved)
    hr = _half(Dr, m["D_ref_lo"].to_numpy(float), m["D_ref_hi"].to_numpy(float), D,
               m["stop_ref"].to_numpy(str), d_resolved_ref)
    with np.errstate(invalid="ignore"):
        agree = (np.abs(D - Dr) <= np.hypot(h, hr)).astype(float)
    agree[~(np.isfinite(D) & np.isfinite(Dr) & np.isfinite(h) & np.isfinite(hr))] = math.nan
    m = m.assign(d_resolved=d_resolved, d_resolved_ref=d_resolved_ref, agree=agree)
    return m[list(CUT_COLUMNS)].sort_values("f").reset_index(drop=True)
