"""The measures only Klages, Barna & Mátyás (2004) needs, each held by its claims
(:mod:`.claims`) -- the loops of the spiral, where the families' D disagree (ergodicity), how
close the collision states lie to the spiral approximation, integer lockings of Mátyás &
Klages 2004, the extrema the finer scales show -- and the D(f) curves and extrema rule that
they and the report read.  f in Hz, v in mm/s, D in mm²/s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from bbb.analysis.approx import spiral
from bbb.analysis.locking import creep_speed, flight_time_max, flight_times

from ...claims.claim import Band, Claim, Measured, Part, Quantity, combine, judge, measure
from ...claims.curves import DEPTH_FRACTION, curve_columns, curve_extrema, families
from ...claims.measures import row_at
from ...tables.collisions import as_store, states

__all__ = ["MAIN", "context", "K_TOL", "DEPTH_FRACTION", "families", "spiral_closeness", "curve_columns",
           "curves", "curves_and_meta", "curve_extrema", "loops", "nonergodic_near_55",
           "ergodic_above_58", "spiral_approx", "matyas_integer", "finescale_extrema"]

MAIN = "rest"  # the main initial-condition family (Fig. 2's curve)
K_TOL = 0.15  # k: the paper quotes k to 2 decimals read off Fig. 3


def curves_and_meta(tables: Mapping[str, pd.DataFrame]) -> tuple[dict, dict]:
    """The D(f) curves to look at: the main one (Fig. 2 scene) and every family of the
    ergodicity scene: ({label: (table, (D, lo, hi) columns)}, {label: (scene, family)})."""
    out, meta = {}, {}
    main = tables.get("figure2")
    if main is not None and "D" in main:
        label = f"{MAIN} (Fig. 2 scene)"
        out[label], meta[label] = (main, curve_columns(main, None)), ("figure2", MAIN)
    ergo = tables.get("ergodicity")
    if ergo is not None:
        for fam in families(ergo):
            label = f"{fam} (ergodicity scene)"
            out[label], meta[label] = (ergo, curve_columns(ergo, fam)), ("ergodicity", fam)
    return out, meta


def curves(tables: Mapping[str, pd.DataFrame]) -> dict[str, tuple[pd.DataFrame, tuple[str, str, str]]]:
    """{label: (table, (D, lo, hi) columns)} of every D(f) curve in the tables."""
    return curves_and_meta(tables)[0]


def context(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str] | None = None,
            f_gamma1: float | None = None, params: Mapping[str, float] | None = None) -> dict:
    """The context the paper's claims are judged in (by :func:`pipeline.claims.claim.evaluate`),
    with the significant extrema of every D(f) curve under ``"extrema"``.

    tables   -- the study's reduce tables by scene ("figure2", "locking", ...)
    stores   -- store paths by scene, for the claims that read post-collision states
    f_gamma1 -- f (Hz) at which Γ = 1, for explanatory notes
    params   -- the Fig. 2 scene's parameters (g, A, alpha, ...), for explanatory notes
    """
    cv, meta = curves_and_meta(tables)
    return {"tables": tables, "stores": dict(stores or {}), "curves": cv, "curve_meta": meta,
            "extrema": {label: curve_extrema(t, cols) for label, (t, cols) in cv.items()},
            "f_gamma1": f_gamma1, "params": params}


@measure("klages2004.loops")
def loops(claim: Claim, ctx) -> Measured:
    """f where k_max first reaches n = 2..5 (CI: where k_max_hi / k_max_lo first do, ± half
    the grid spacing), each against the paper's start ± 2.5 Hz; and 2 ≤ k_max(72) < 3."""
    lock = ctx["tables"].get("locking")
    if lock is None:
        return Measured(missing="no locking table")
    t = lock[lock["family"] == MAIN].sort_values("f")
    t = t[t["f"] > 58]
    f = t["f"].to_numpy(float)
    h = float(np.median(np.diff(f))) / 2 if f.size > 1 else 0.0
    parts = []

    def first(col, n):
        i = np.flatnonzero(np.nan_to_num(t[col].to_numpy(float), nan=-1.0) >= n) if col in t \
            else np.zeros(0, int)
        return float(f[i[0]]) if i.size else math.nan

    why = "the frequency the paper names for the new loop ('from 76'), ± 2.5 Hz read off Fig. 2/3"
    for n, f0 in {2: 66.0, 3: 76.0, 4: 86.0, 5: 96.0}.items():
        v = first("k_max", n)
        lo, hi = first("k_max_hi", n), first("k_max_lo", n)
        q = Quantity(v, lo - h if math.isfinite(lo) else math.nan,
                     hi + h if math.isfinite(hi) else math.inf, "Hz",
                     "k_max's bootstrap CI reaching n, ± half the grid spacing")
        parts.append(Part(f"k_max reaches {n}", q, "not reached" if math.isnan(v) else q.text("g"),
                          band=Band.around(f0, 2.5, why, "Hz"), found=math.isfinite(v)))
    r72 = row_at(lock, 72.0, MAIN)
    if r72 is not None:
        q = Quantity(float(r72["k_max"]), float(r72.get("k_max_lo", math.nan)),
                     float(r72.get("k_max_hi", math.nan)), "", "bootstrap over particles")
        parts.append(Part("k_max at 72 Hz (two complete loops ⇔ 2 ≤ k_max < 3)", q, q.text(".3g"),
                          band=Band(2.0, 3.0 - 1e-9, "two-loop spiral")))
    fs = sorted(p.q.value for p in parts[:4] if p.found)
    extra = f"spacing Δf = {np.mean(np.diff(fs)):.1f} Hz" if len(fs) >= 2 else ""
    return Measured(parts, extra, "Each new loop of the spiral appears as a jump of k_max (the "
                    "0.99 quantile of v_y⁺ in units of g/(2f)) by about one: see the k(f) plot.")


def _ergo_parts(ergo: pd.DataFrame) -> pd.DataFrame:
    """Per frequency: (a) do the families' CIs overlap pairwise, (b) does EB converge."""
    fams = families(ergo)
    rows = []
    for _, r in ergo.iterrows():
        agree = all(r[f"D_{a}_lo"] <= r[f"D_{b}_hi"] and r[f"D_{b}_lo"] <= r[f"D_{a}_hi"]
                    for i, a in enumerate(fams) for b in fams[i + 1:])
        if "eb_ok" in r and not pd.isna(r["eb_ok"]):
            eb_ok = bool(r["eb_ok"])
        else:  # a table from before the decay rule: the level rule alone
            eb = [r.get(f"EB_{m}", math.nan) for m in fams] + [r.get("EB", math.nan)]
            eb_ok = bool(all(x <= r["EB_threshold"] for x in eb if np.isfinite(x)))
        rows.append({"f": r["f"], "agree": bool(agree), "eb_ok": eb_ok,
                     "ergodic": r.get("ergodic")})
    return pd.DataFrame(rows)


def _pct(x: float) -> str:
    return f"{100 * x:.0f} %"


def _rule_text(ergo: pd.DataFrame) -> str:
    """The ergodicity rule the table was reduced with, and its calibrated error rates."""
    if "rule" not in ergo or "cv_max" not in ergo:  # a table from before the calibrated rule
        return "EB converges (Brownian level, or falling like 1/T)"
    r = ergo.iloc[0]
    return (f"rule '{r['rule']}' (docs/statistics.md: per-particle D spread CV ≤ "
            f"{_pct(r['cv_max'])}; calibrated false-positive rate ≤ {_pct(r['rule_fp'])}, "
            f"false-negative ≤ {_pct(r['rule_fn'])} at this ensemble size)")


def _spread_text(sel: pd.DataFrame) -> str:
    """What spread of per-particle D the verdict can exclude at the given frequencies."""
    if "CV_D_upper" not in sel or sel.empty:
        return ""
    up = sel["CV_D_upper"].to_numpy(float)
    none = sel["f"][~np.isfinite(up)].tolist()
    gap = (f"; no bound at {', '.join(f'{x:g}' for x in none)} Hz (the CV² estimate lies "
           "below its model's range there)" if none else "")
    if not np.isfinite(up).any():
        return gap
    worst = sel.iloc[int(np.nanargmax(up))]
    return (f"; the runs exclude a per-particle D spread above CV {_pct(np.nanmin(up))}–"
            f"{_pct(np.nanmax(up))} (95 % upper bound; weakest at {worst['f']:g} Hz); smaller "
            "spreads are not excluded" + gap)


@measure("klages2004.nonergodic_near_55")
def nonergodic_near_55(claim: Claim, ctx) -> Measured:
    """Families' D disagree (CIs do not overlap) in 53–57 Hz and nowhere else: agrees; also
    elsewhere: partly; nowhere: disagrees (the CIs are reduce's bootstrap CIs)."""
    ergo = ctx["tables"].get("ergodicity")
    if ergo is None or len(families(ergo)) < 2:
        return Measured(missing="no table with several families")
    parts = _ergo_parts(ergo)
    near = parts[(parts["f"] >= 53) & (parts["f"] <= 57)]
    bad = near[~near["agree"]]
    meas = ("families' D disagree at f = " + ", ".join(f"{x:g}" for x in bad["f"]) if len(bad)
            else "families' D agree at every f in 53–57")
    negative = near["f"][near["ergodic"].astype("boolean").fillna(True).eq(False)]
    if len(negative):
        meas += f"; reduce verdict non-ergodic at {', '.join(f'{x:g}' for x in negative)}"
    others = [f for f in parts["f"] if not 53 <= f <= 57 and f in set(parts["f"][~parts["agree"]])]
    if others:
        meas += f"; families' D also disagree at {', '.join(f'{x:g}' for x in others)}"
    verdict = "agrees" if len(bad) and not others else "partly" if len(bad) else "disagrees"
    note = (f"The families ({', '.join(families(ergo))}) start in different basins: the "
            "bouncing state and creeping coexist." if len(bad) else "")
    return Measured(text=meas, verdict=verdict, note=note)


@measure("klages2004.ergodic_above_58")
def ergodic_above_58(claim: Claim, ctx) -> Measured:
    """(a) families' D agree and (b) EB converges at every f ≥ 58: agrees; (a) only: partly."""
    ergo = ctx["tables"].get("ergodicity")
    if ergo is None or len(families(ergo)) < 2:
        return Measured(missing="no table with several families")
    parts = _ergo_parts(ergo)
    hi = parts[parts["f"] >= 58]
    if hi.empty:
        return Measured(missing="no f ≥ 58 in the ergodicity table")
    dis = hi[~hi["agree"]]["f"].tolist()
    eb = hi[~hi["eb_ok"]]["f"].tolist()
    meas = (f"f = {', '.join(f'{x:g}' for x in hi['f'])}: families' D "
            + ("agree everywhere" if not dis else f"disagree at {', '.join(f'{x:g}' for x in dis)}")
            + f"; {_rule_text(ergo)} " + (
                "everywhere" if not eb else f"fails at {', '.join(f'{x:g}' for x in eb)}"))
    meas += _spread_text(ergo[ergo["f"] >= 58])
    if not dis and not eb:
        return Measured(text=meas, verdict="agrees")
    if not dis:
        return Measured(text=meas, verdict="partly", note=(
            "Initial conditions do not matter (criterion a), but the per-particle D "
            "spread that the EB statistics estimate is above the rule's limit (b)."))
    return Measured(text=meas, verdict="disagrees")


def spiral_closeness(y: np.ndarray, v: np.ndarray, A: float, f: float, g: float, alpha: float,
                     t_max: float, n: int = 3000, seed: int = 0) -> tuple[float, float]:
    """How close post-collision points above the creeping band lie to the spiral of Eqs. (8)-(9).

    Distances in units of the spiral's loop size (y / A, v / (A 2π f (1 + α))) to the curve
    with t_c ∈ [0, t_max].  Returns (median distance of the points, median distance of as many
    points scattered uniformly over their bounding box): a ratio well below 1 means the points
    crowd along the curve.
    """
    ok = np.isfinite(y) & np.isfinite(v) & (v > creep_speed(A, f))
    y, v = y[ok], v[ok]
    if y.size < 20 or not math.isfinite(t_max):
        return math.nan, math.nan
    rng = np.random.default_rng(seed)
    idx = rng.choice(y.size, min(n, y.size), replace=False)
    cy, cv = spiral(A, f, g, alpha, np.linspace(0.0, t_max, 4000))
    V = A * 2 * math.pi * f * (1 + alpha)

    def med(yy, vv):
        d = np.empty(yy.size)
        for i in range(0, yy.size, 500):
            a, b = yy[i:i + 500, None], vv[i:i + 500, None]
            d[i:i + 500] = np.hypot((a - cy) / A, (b - cv) / V).min(axis=1)
        return float(np.median(d))

    null = (rng.uniform(y.min(), y.max(), idx.size), rng.uniform(v.min(), v.max(), idx.size))
    return med(y[idx], v[idx]), med(*null)


@measure("klages2004.spiral_approx")
def spiral_approx(claim: Claim, ctx) -> Measured:
    """Median distance ratio (points vs uniform scatter) at 66, 72, 78 Hz, each < 0.7; no CI."""
    stores = [s for s in (ctx["stores"].get("figure3"), ctx["stores"].get("locking")) if s]
    if not stores:
        return Measured(missing="no store with collisions")
    parts = []
    for f0 in (66.0, 72.0, 78.0):
        for path in stores:
            st = as_store(path)
            if not np.any(np.abs(np.asarray(st.study.frequencies) - f0) < 1e-3):
                continue
            p = st.study.params(f0)
            names = [m.name for m in st.study.families]
            s = states(st, f0, MAIN if MAIN in names else names[0])
            tm = flight_time_max(flight_times(s["t"], s["y"], s["vy"], p.g))
            d, d0 = spiral_closeness(s["y"].ravel(), s["vy"].ravel(), p.A, f0, p.g, p.alpha, tm)
            if math.isfinite(d):
                parts.append(Part(f"{f0:g} Hz", Quantity(d / d0),
                                  f"{d:.3f} vs {d0:.3f} (ratio {d / d0:.2f}, no CI)"))
            break
    if not parts:
        return Measured(missing="no states at 66, 72, 78 Hz")
    return Measured(parts, "(median distance to the curve, in loop sizes, of the non-creeping "
                    "states vs of uniformly scattered points)")


@measure("klages2004.matyas_integer")
def matyas_integer(claim: Claim, ctx) -> Measured:
    """The 3 largest significant maxima of the matyas2004 D(f): k_peak of the main family
    (bootstrap CI) against the nearest integer ± K_TOL."""
    table, lock = ctx["tables"].get("figure2_matyas2004"), ctx["tables"].get("locking_matyas2004")
    if table is None or lock is None:
        return Measured(missing="no matyas2004 tables")
    ext = sorted((e for e in curve_extrema(table, ("D", "D_lo", "D_hi")) if e.kind == "max"),
                 key=lambda e: -e.D)[:3]
    if not ext:
        return Measured(text="no significant maximum", verdict="disagrees")
    parts = []
    for e in ext:
        r = row_at(lock, e.f, MAIN)
        if r is None or not math.isfinite(r["k_peak"]):
            continue
        q = Quantity(float(r["k_peak"]), float(r.get("k_peak_lo", math.nan)),
                     float(r.get("k_peak_hi", math.nan)), "", "bootstrap over particles")
        n = max(1, round(q.value))
        parts.append(Part(f"max at {e.f:g} Hz (D = {e.D:.3g})", q, f"k_peak = {q.text('.3g')}, "
                          f"k_max = {r['k_max']:.2f}",
                          band=Band.around(n, K_TOL, f"integer k = {n}")))
    if not parts:
        return Measured(text="no k at the maxima", verdict="disagrees")
    hits = [judge(p.q, p.band) for p in parts]
    return Measured(parts, verdict=combine(hits), note=(
        f"The {len(ext)} largest significant maxima, largest first; locking read from the "
        f"dominant v_y⁺ peak of the {MAIN} family. The amplitude (A = 0.1 here) and the "
        "frequency range of the 2004 study are not known from this paper, so the peaks need "
        "not be the same."))


@measure("klages2004.finescale")
def finescale_extrema(claim: Claim, ctx) -> Measured:
    """Significant extrema that the 0.05 Hz resolution shows and the 0.4 Hz grid does not, in
    the refined window (scene finescale; pipeline/studies/klages2004/finescale.py)."""
    from .finescale import extrema_per_hz, located_extrema, new_extrema, table_arrays

    table = ctx["tables"].get("finescale")
    if table is None:
        return Measured(missing="no finescale table")
    f, D, lo, hi = table_arrays(table)
    n, n_lo, n_hi = new_extrema(f, D, lo, hi)
    counts = extrema_per_hz(f, D, lo, hi)
    per = "; ".join(f"{c.h:g} Hz: {c.per_hz[0]:.2f} [{c.per_hz[1]:.2f}, {c.per_hz[2]:.2f}]"
                    f" ({c.n_points} points)" for c in counts)
    where = ", ".join(f"{e.kind} {e.f:g} [{e.f_lo:.3f}, {e.f_hi:.3f}]"
                      for e in located_extrema(f, D, lo, hi))
    return Measured([Part(f"{f.min():g}–{f.max():g} Hz", Quantity(
        float(n), n_lo, n_hi, "extrema", "bootstrap of D(f) within its CIs, paired"),
        f"{n} more significant extrema at 0.05 Hz than at 0.4 Hz [{n_lo:g}, {n_hi:g}]")],
        text=f"significant extrema per Hz by resolution: {per}; located (Hz): {where}",
        note="Refinement adds points only around extrema and significant jumps, so the fine "
             "levels count the structure next to what coarser levels saw: a lower bound on a "
             "uniform fine grid.")
