"""What ``bbb reduce`` says about its D(f) table beyond writing it: one line per kind of
result that must not be read as a value (stderr; :func:`pipeline.tables.reduce.reduce_store`).

estimator failed   D (pooled or a family's) significantly below 0: its 95 % CI lies entirely
                   below 0 -- impossible for a diffusion coefficient, so the fit window sees
                   settling or rocking, not diffusion.  The table leaves D, D_lo, D_hi blank
                   there and keeps the fit's numbers in D_status; ``bbb plot`` marks the
                   frequency with an ``x`` ("estimator failed").
D_drift failed     the same for D about the drift (D_drift_status).
drift included     on a floor that drifts (a row with a significant v: its CI excludes 0) the
                   column D is the raw MSD's slope, drift included (9.8e3 mm²/s where
                   D_drift = 0.12 mm²/s: throw 30°, Coulomb, 80 Hz); the diffusion
                   coefficient about the drift is D_drift.  D_status says so on the row
                   (:data:`DRIFT_TEXT`), so the table cannot be misread without the note.
accelerating       the drift of the run's second half differs from the first half's beyond
                   the calibrated band (v_status "accelerating": the particles speed up, such
                   as particles running away down a tilted floor): v is no drift.  The table
                   keeps v (the mean velocity over the analysed run), leaves v_lo, v_hi and Pe
                   blank and reports the acceleration
                   a [a_lo, a_hi] (mm/s²); D_status says :data:`ACCEL_TEXT`; ``bbb plot``
                   marks the point with a triangle ("accelerating").
"""

from __future__ import annotations

import pandas as pd

__all__ = ["FAILED_TEXT", "DRIFT_TEXT", "ACCEL_TEXT", "failed_points", "drift_points",
           "accelerating_points", "reduce_notes"]

#: the words of bbb.analysis.stats.interval's note for a CI below 0
FAILED_TEXT = "estimator failed"
#: what D_status adds on a row whose v is significant: D there is not the diffusion coefficient
DRIFT_TEXT = "drift included (v significant): read D_drift"
#: what D_status adds on a row whose drift accelerates (v_status): D is no diffusion coefficient
ACCEL_TEXT = "accelerating (v_status): D includes the acceleration"


def _labels(df: pd.DataFrame, rows: pd.Series) -> list[str]:
    """``f = 80 Hz`` (plus the grid axes: the columns between f and Gamma) of each row picked."""
    cols = list(df.columns)
    axes = cols[cols.index("f") + 1: cols.index("Gamma")] if "Gamma" in cols else []
    out = []
    for _, r in df[rows].iterrows():
        extra = "".join(f", {a} = {r[a]}" for a in axes)
        out.append(f"{r['f']:g} Hz{extra}")
    return out


def _listing(labels: list[str], most: int = 6) -> str:
    shown = "; ".join(labels[:most])
    more = f"; and {len(labels) - most} more" if len(labels) > most else ""
    return f"{len(labels)} point{'s' if len(labels) > 1 else ''} ({shown}{more})"


def failed_points(df: pd.DataFrame, status: str = "D_status") -> pd.Series:
    """Rows whose ``status`` column reports a failed estimator (pooled or a family's)."""
    if status not in df:
        return pd.Series(False, index=df.index)
    return df[status].astype("string").str.contains(FAILED_TEXT, regex=False).fillna(False)


def drift_points(df: pd.DataFrame) -> pd.Series:
    """Rows with a significant drift: v's CI excludes 0 (``v_lo > 0`` or ``v_hi < 0``)."""
    if not {"v_lo", "v_hi"} <= set(df.columns):
        return pd.Series(False, index=df.index)
    return ((df["v_lo"] > 0) | (df["v_hi"] < 0)).fillna(False)


def accelerating_points(df: pd.DataFrame) -> pd.Series:
    """Rows whose drift accelerates (``v_status`` "accelerating")."""
    from bbb.analysis.transport import ACCELERATING

    if "v_status" not in df:
        return pd.Series(False, index=df.index)
    return (df["v_status"] == ACCELERATING).fillna(False).astype(bool)


def reduce_notes(name: str, df: pd.DataFrame) -> list[str]:
    """The lines ``bbb reduce`` prints about the D(f) table ``df`` of study ``name``."""
    out = []
    failed = failed_points(df)
    if failed.any():
        out.append(f"{name}: warning: D < 0 significantly (CI below 0: estimator failed) at "
                   f"{_listing(_labels(df, failed))}; left blank in D, the fit's numbers in "
                   "D_status")
    failed = failed_points(df, "D_drift_status")
    if failed.any():
        out.append(f"{name}: warning: D_drift < 0 significantly (CI below 0: estimator "
                   f"failed) at {_listing(_labels(df, failed))}; left blank, the fit's "
                   "numbers in D_drift_status")
    drift = drift_points(df)
    if drift.any():
        top = df.loc[drift, "D"].abs().max()
        size = f", D up to {top:.2g} mm^2/s there" if pd.notna(top) else ""
        out.append(f"{name}: note: D includes the drift (v significant) at "
                   f"{_listing(_labels(df, drift))}{size}; the diffusion coefficient about "
                   "the drift is D_drift")
    acc = accelerating_points(df)
    if acc.any():
        lo, hi = df.loc[acc, "a"].abs().min(), df.loc[acc, "a"].abs().max()
        out.append(f"{name}: warning: the drift accelerates (v of the run's halves differ beyond "
                   f"their CIs; |a| {lo:.3g}-{hi:.3g} mm/s^2) at {_listing(_labels(df, acc))}; "
                   "v there is the mean velocity over the run, not a drift: its CI and Pe left "
                   "blank, the acceleration in a, a_lo, a_hi")
    return out
