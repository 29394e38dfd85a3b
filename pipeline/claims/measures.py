"""Generic measures for claims (:mod:`pipeline.claims.claim`) on D(f) curves and locking tables.

Each takes (claim, ctx) and returns a :class:`~pipeline.claims.claim.Measured`.  ctx holds
``tables`` (name -> DataFrame), ``curves`` (label -> (table, (D, lo, hi) columns)),
``curve_meta`` (label -> (scene, family)) and ``extrema`` (label -> significant extrema).
Where a CI comes from is stated in each docstring and in the Quantity.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from bbb.analysis.extrema import nearest

from .claim import Claim, Measured, Part, Quantity, measure

__all__ = ["ONSET_FRACTION", "onset", "onset_ci", "row_at", "grid_step", "fmt_d"]

ONSET_FRACTION = 0.01  # onset: D_lo above this fraction of the curve's largest D
#: |D| below this (mm²/s) is printed as 0: particles that never move give D ~ 1e-30 from rounding
D_ZERO = 1e-6


def fmt_d(v: float, digits: int = 4) -> str:
    """A diffusion coefficient (mm²/s) for the report: rounding noise of a still ensemble as 0."""
    return "0" if abs(v) < D_ZERO else f"{v:.{digits}g}"


def grid_step(table: pd.DataFrame) -> float:
    """The median spacing of the table's frequencies, Hz."""
    f = np.unique(table["f"].to_numpy(float))
    return float(np.median(np.diff(f))) if f.size > 1 else 0.0


def row_at(table: pd.DataFrame | None, f0: float, family: str | None = None,
           tol: float = 0.5) -> pd.Series | None:
    """The row of ``table`` nearest f0 (within ``tol`` Hz), of ``family`` if the table has
    families; None if there is none."""
    if table is None or table.empty:
        return None
    t = table if family is None or "family" not in table else table[table["family"] == family]
    if t.empty:
        return None
    i = int(np.argmin(np.abs(t["f"].to_numpy(float) - f0)))
    row = t.iloc[i]
    return row if abs(float(row["f"]) - f0) <= tol else None


def _first_above(t: pd.DataFrame, col: str, thr: float) -> float:
    v = np.nan_to_num(t[col].to_numpy(float), nan=-np.inf)
    i = np.flatnonzero(v > thr)
    return float(t["f"].iloc[i[0]]) if i.size else math.nan


def onset(table: pd.DataFrame, cols: tuple[str, str, str]) -> float:
    """Lowest f (Hz) at which D_lo > 1 % of the curve's largest D; NaN if never."""
    t = table.sort_values("f")
    D = t[cols[0]].to_numpy(float)
    if not np.isfinite(D).any():
        return math.nan
    return _first_above(t, cols[1], ONSET_FRACTION * np.nanmax(D))


def onset_ci(table: pd.DataFrame, cols: tuple[str, str, str]) -> Quantity:
    """The onset with a CI: from the lowest f whose D_hi exceeds the threshold (the earliest
    the curve may rise) to the lowest f whose D_lo does, widened by half the grid spacing
    (the onset lies between grid points); lo = -inf when it is at the lowest f studied."""
    t = table.sort_values("f")
    D = t[cols[0]].to_numpy(float)
    if not np.isfinite(D).any():
        return Quantity(math.nan)
    thr = ONSET_FRACTION * np.nanmax(D)
    on, early = _first_above(t, cols[1], thr), _first_above(t, cols[2], thr)
    h = grid_step(t) / 2
    lowest = float(t["f"].iloc[0])
    lo = -math.inf if early <= lowest else early - h
    return Quantity(on, lo, on + h if math.isfinite(on) else math.nan, "Hz",
                    "from D_hi and D_lo crossing the threshold, ± half the grid spacing")


def _curves_of(claim: Claim, ctx) -> list[tuple[str, pd.DataFrame, tuple, bool]]:
    out = []
    for label, (table, cols) in ctx["curves"].items():
        scene, fam = ctx["curve_meta"][label]
        out.append((label, table, cols, scene == claim.scene and fam == claim.family))
    return out


@measure("extremum")
def extremum(claim: Claim, ctx) -> Measured:
    """A significant extremum (options kind: "max"/"min") of every D(f) curve near f0.

    Location CI: the extremum's position range (the contiguous points whose D CIs overlap
    its own, bbb.analysis.extrema) widened by half the grid spacing -- not a bootstrap of the curve.
    Searched within 2 windows of f0 so that one just outside the band is reported.
    """
    kind = claim.options["kind"]
    f0, w = claim.f0, claim.window
    curves = [c for c in _curves_of(claim, ctx)
              if c[1]["f"].min() <= f0 - w and c[1]["f"].max() >= f0 + w]
    if not curves:
        return Measured(missing=f"no D(f) curve spans {f0 - w:g}–{f0 + w:g} Hz")
    parts = []
    for label, table, _cols, main in curves:
        e = nearest(ctx["extrema"][label], kind, f0, 2 * w)
        if e is None:
            if main:
                parts.append(Part(label, Quantity(math.nan), f"no significant {kind} within "
                                  f"{2 * w:g} Hz of {f0:g} Hz", main=True, found=False))
            continue
        h = grid_step(table) / 2
        q = Quantity(e.f, e.f_lo - h, e.f_hi + h, "Hz", "position range ± half grid spacing")
        parts.append(Part(label, q, f"{kind} at f = {q.text('g')} (position range ± "
                          f"{h:g} Hz), D = {fmt_d(e.D)} [{fmt_d(e.lo)}, {fmt_d(e.hi)}]"
                          + stationarity_mark(table, e.f), main=main))
    note = ""
    if not any(p.found for p in parts):
        parts = [p for p in parts if p.main]
        note = trend(f0, w, ctx)
    return Measured(parts, note=note)


def trend(f0: float, window: float, ctx) -> str:
    """What every curve does near f0: D at the grid points nearest f0 - window, f0, f0 + window."""
    out = []
    for label, (table, cols) in ctx["curves"].items():
        vals = []
        for fx in (f0 - window, f0, f0 + window):
            r = row_at(table, fx, tol=0.6)
            if r is not None and math.isfinite(r[cols[0]]):
                vals.append(f"D({r['f']:g}) = {fmt_d(r[cols[0]], 3)}")
        if vals:
            out.append(f"{label}: " + ", ".join(vals))
    return "What the curves do there: " + "; ".join(out) + "."


@measure("onset")
def onset_measure(claim: Claim, ctx) -> Measured:
    """Onset of diffusion on every curve (:func:`onset_ci`)."""
    if not ctx["curves"]:
        return Measured(missing="no D(f) table")
    parts = []
    for label, table, cols, main in _curves_of(claim, ctx):
        q = onset_ci(table, cols)
        lowest = float(table["f"].min())
        txt = ("never" if math.isnan(q.value) else
               f"≤ {q.value:g} Hz (lowest f studied)" if q.value <= lowest else q.text("g"))
        parts.append(Part(label, q, txt, main=main, found=not math.isnan(q.value)))
    return Measured(parts)


@measure("table_value")
def table_value(claim: Claim, ctx) -> Measured:
    """options column (with column_lo / column_hi as its CI) of the scene's table at f0, for
    every family (the claim's family is the main one); options unit, fmt."""
    col = claim.options["column"]
    table = ctx["tables"].get(claim.scene)
    if table is None:
        return Measured(missing=f"no {claim.scene} table")
    fams = table["family"].unique() if "family" in table else [None]
    if not claim.options.get("all_families", True):
        fams = [claim.family]
    parts = []
    for fam in fams:
        r = row_at(table, claim.f0, fam)
        if r is None:
            continue
        lo, hi = (float(r.get(f"{col}_{s}", math.nan)) for s in ("lo", "hi"))
        q = Quantity(float(r[col]), lo, hi, claim.options.get("unit", ""),
                     "bootstrap over particles")
        extra = claim.options.get("extra")
        label = f"{fam or ''} (f = {r['f']:g})".strip()
        txt = (f"{col} = {q.text(claim.options.get('fmt', '.3g'))}"
               + (f"; {extra(r)}" if extra else ""))
        parts.append(Part(label, q, txt, main=fam in (None, claim.family),
                          found=math.isfinite(q.value)))
    if not parts:
        return Measured(missing=f"f = {claim.f0:g} not in the {claim.scene} table")
    return Measured(parts)


@measure("growth")
def growth(claim: Claim, ctx) -> Measured:
    """Ratio of the largest D in [f0, f0 + window] to D(f0), main curve of the scene; CI from
    the two points' CIs (largest lo / hi, largest hi / lo): conservative, not a bootstrap."""
    t = ctx["tables"].get(claim.scene)
    if t is None:
        return Measured(missing="no D(f) table")
    r0 = row_at(t, claim.f0)
    s = t[(t["f"] >= claim.f0) & (t["f"] <= claim.f0 + claim.window)]
    if r0 is None or s.empty:
        return Measured(missing=f"{claim.f0:g}–{claim.f0 + claim.window:g} Hz not in the table")
    top = s.loc[s["D"].idxmax()]

    def div(a, b):
        return a / b if b > 0 else math.inf
    q = Quantity(div(top["D"], r0["D"]), div(top["D_lo"], r0["D_hi"]),
                 div(top["D_hi"], r0["D_lo"]), "", "from the two points' CIs")
    txt = (f"D({r0['f']:g}) = {fmt_d(r0['D'])} [{fmt_d(r0['D_lo'])}, {fmt_d(r0['D_hi'])}] → "
           f"largest D in {claim.f0:g}–{claim.f0 + claim.window:g} Hz: D({top['f']:g}) = "
           f"{fmt_d(top['D'])} [{fmt_d(top['D_lo'])}, {fmt_d(top['D_hi'])}], ratio "
           f"{q.text('.2f')}")
    return Measured([Part("rest (Fig. 2 scene)", q, txt)])


def stationarity_mark(table: pd.DataFrame, f: float) -> str:
    """' (D depends on the run length: ...)' where the reduce table flags the point at f."""
    r = row_at(table, f, tol=1e-6)
    if r is None or "stationary" not in r or pd.isna(r["stationary"]) or bool(r["stationary"]):
        return ""
    pooled = " (all families pooled)" if any(c.endswith("_lo") and c.startswith("D_") and
                                             c not in ("D_lo", "dD_lo") for c in r.index) else ""
    return (f" ⚠ D depends on the run length here{pooled}: D of the 2nd half − 1st half = "
            f"{r['dD']:.3g} [{r['dD_lo']:.3g}, {r['dD_hi']:.3g}] mm²/s")
