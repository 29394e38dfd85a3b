"""``figures/REPORT.md``: the paper's claims beside what the stores and tables measure.

Every number in the report is computed here from the reduce tables (D(f) with bootstrap CIs,
ergodicity verdicts), the locking tables (:mod:`pipeline.collisions`) and the stores'
attributes; nothing measured is typed in.  The paper's own numbers (the claims) are the only
constants, in :data:`CLAIMS` order.

Rules used for the verdicts (stated again in the report):

* extrema: :func:`bbb.extrema.find_extrema` on the curve (Bonferroni-corrected significance,
  differences below 1 % of the curve's largest D ignored); a claimed extremum near f0 is
  found if a significant one of that kind lies within 2 Hz (3 Hz for the "washed-out"
  maximum near 80) of f0, measured from its position range [f_lo, f_hi];
* onset of diffusion: the lowest f at which D_lo exceeds 1 % of the curve's largest D;
* k and v_y⁺ peaks: from the locking table at the frequency nearest to the claim's;
  a k agrees if within 0.15 of the paper's, is "close" within 0.3;
* ergodicity: the reduce verdict, split into its two parts -- (a) do the families' D agree
  within their CIs, (b) does the ergodicity-breaking parameter EB converge (Brownian level, or 1/T).

Verdicts: **agrees**, **partly** (some of the claim, or with another initial-condition
family than the main one), **disagrees**, **not measured** (a table is missing).
"""

from __future__ import annotations

import datetime as _dt
import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from bbb.approx import spiral
from bbb.extrema import Extremum, find_extrema, nearest
from bbb.locking import (
    CREEP_MARGIN,
    FLIGHT_TOL,
    MAX_QUANTILE,
    TMAX_QUANTILE,
    creep_speed,
    flight_time_max,
    flight_times,
)

from .collisions import as_store, states

__all__ = ["Row", "CLAIMS", "curve_extrema", "onset", "evaluate", "write_report",
           "spiral_closeness", "period1_limit"]

MAIN = "rest"  # the main initial-condition family (Fig. 2's curve)
ONSET_FRACTION = 0.01  # onset: D_lo above this fraction of the curve's largest D
DEPTH_FRACTION = 0.01  # extrema: differences below this fraction of max D do not count
WINDOW = 2.0  # Hz: how far a claimed extremum may lie from the measured one
K_TOL, K_CLOSE = 0.15, 0.3


@dataclass(frozen=True)
class Row:
    """One claim: what the paper says, what we measured, the verdict and a plain note."""

    claim: str
    measured: str
    verdict: str
    note: str = ""


# -------------------------------------------------------------------------------------------
# measurements
# -------------------------------------------------------------------------------------------
def _cols(table: pd.DataFrame, family: str | None) -> tuple[str, str, str]:
    if family is None:
        return "D", "D_lo", "D_hi"
    return f"D_{family}", f"D_{family}_lo", f"D_{family}_hi"


def _families(table: pd.DataFrame) -> list[str]:
    return [c[2:-3] for c in table.columns
            if c.startswith("D_") and c.endswith("_lo") and c != "D_lo"]


def curves(tables: Mapping[str, pd.DataFrame]) -> dict[str, tuple[pd.DataFrame, tuple[str, str, str]]]:
    """The D(f) curves to look at: the main one (Fig. 2 scene) and every family of the
    ergodicity scene, as {label: (table, (D, lo, hi) columns)}."""
    out = {}
    main = tables.get("figure2")
    if main is not None and "D" in main:
        out[f"{MAIN} (Fig. 2 scene)"] = (main, _cols(main, None))
    ergo = tables.get("ergodicity")
    if ergo is not None:
        for fam in _families(ergo):
            out[f"{fam} (ergodicity scene)"] = (ergo, _cols(ergo, fam))
    return out


def curve_extrema(table: pd.DataFrame, cols: tuple[str, str, str]) -> list[Extremum]:
    """Significant extrema of one D(f) curve (differences below 1 % of its max D ignored)."""
    D = table[cols[0]].to_numpy(float)
    depth = DEPTH_FRACTION * float(np.nanmax(D)) if np.isfinite(D).any() else 0.0
    return find_extrema(table["f"], D, table[cols[1]], table[cols[2]], min_depth=max(depth, 0.0))


def onset(table: pd.DataFrame, cols: tuple[str, str, str]) -> float:
    """Lowest f (Hz) at which D_lo > 1 % of the curve's largest D; NaN if never."""
    t = table.sort_values("f")
    D, lo = t[cols[0]].to_numpy(float), t[cols[1]].to_numpy(float)
    if not np.isfinite(D).any():
        return math.nan
    above = np.flatnonzero(np.nan_to_num(lo, nan=-np.inf) > ONSET_FRACTION * np.nanmax(D))
    return float(t["f"].iloc[above[0]]) if above.size else math.nan


def _row_at(table: pd.DataFrame | None, f0: float, family: str | None = None,
            tol: float = 0.5) -> pd.Series | None:
    if table is None or table.empty:
        return None
    t = table if family is None or "family" not in table else table[table["family"] == family]
    if t.empty:
        return None
    i = int(np.argmin(np.abs(t["f"].to_numpy(float) - f0)))
    row = t.iloc[i]
    return row if abs(float(row["f"]) - f0) <= tol else None


def spiral_closeness(y: np.ndarray, v: np.ndarray, A: float, f: float, g: float, alpha: float,
                     t_max: float, n: int = 3000, seed: int = 0) -> tuple[float, float]:
    """How close post-collision points above the creeping band lie to the spiral of Eqs. (8)-(9).

    Distances are measured in units of the spiral's loop size (y / A, v / (A 2π f (1 + α)))
    to the curve with t_c ∈ [0, t_max].  Returns (median distance of the points, median
    distance of as many points scattered uniformly over the points' bounding box): a ratio
    well below 1 means the points crowd along the curve.
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


# -------------------------------------------------------------------------------------------
# the claims
# -------------------------------------------------------------------------------------------
#: |D| below this (mm²/s) is printed as 0: particles that never move give D ~ 1e-30 from rounding
D_ZERO = 1e-6


def _fmt_d(v: float, digits: int = 4) -> str:
    """A diffusion coefficient (mm²/s) for the report: rounding noise of a still ensemble as 0."""
    return "0" if abs(v) < D_ZERO else f"{v:.{digits}g}"


def _fmt_ext(e: Extremum) -> str:
    rng = f"{e.f_lo:g}–{e.f_hi:g}" if e.f_hi > e.f_lo else f"{e.f:g}"
    return (f"{e.kind} at f = {e.f:g} Hz (range {rng}), D = {_fmt_d(e.D)} "
            f"[{_fmt_d(e.lo)}, {_fmt_d(e.hi)}]")


def _extremum_claim(kind: str, f0: float, window: float, text: str,
                    ctx: Mapping) -> Row:
    found_main, found_other = None, []
    for label in ctx["curves"]:
        e = nearest(ctx["extrema"][label], kind, f0, window)
        if e is None:
            continue
        if label.startswith(MAIN) and found_main is None:
            found_main = (label, e)
        else:
            found_other.append((label, e))
    covering = [lab for lab, (t, _) in ctx["curves"].items()
                if t["f"].min() <= f0 - window and t["f"].max() >= f0 + window]
    if not covering:
        return Row(text, f"no D(f) curve spans {f0 - window:g}–{f0 + window:g} Hz", "not measured")
    parts = []
    if found_main:
        parts.append(f"{found_main[0]}: {_fmt_ext(found_main[1])}")
    parts += [f"{lab}: {_fmt_ext(e)}" for lab, e in found_other]
    if found_main and found_main[0].endswith("(Fig. 2 scene)"):
        return Row(text, "; ".join(parts), "agrees")
    if parts:
        return Row(text, "; ".join(parts), "partly",
                   f"not a significant {kind} of the {MAIN} curve of Fig. 2; seen in another "
                   "curve only")
    return Row(text, f"no significant {kind} within {window:g} Hz of {f0:g} Hz in any curve",
               "disagrees", "What the curves do there: " + _trend(f0, window, ctx))


def period1_limit(alpha: float) -> float:
    """Γ above which the flat-floor period-1 (1/1 locked) orbit is unstable (Luck & Mehta 1993):
    Γ₂ = sqrt((π(1-α)/(1+α))² + (2(1+α²)/(1+α)²)²); 1.1707 for α = 0.7."""
    return math.hypot(math.pi * (1 - alpha) / (1 + alpha), 2 * (1 + alpha**2) / (1 + alpha) ** 2)


def _trend(f0: float, window: float, ctx) -> str:
    """D of every curve at the grid points nearest f0 - window, f0, f0 + window."""
    out = []
    for label, (table, cols) in ctx["curves"].items():
        vals = []
        for fx in (f0 - window, f0, f0 + window):
            r = _row_at(table, fx, tol=0.6)
            if r is not None and math.isfinite(r[cols[0]]):
                vals.append(f"D({r['f']:g}) = {_fmt_d(r[cols[0]], 3)}")
        if vals:
            out.append(f"{label}: " + ", ".join(vals))
    return "; ".join(out) + "."


def _claim_onset(ctx) -> Row:
    text = "Onset of diffusion around f = 50"
    if not ctx["curves"]:
        return Row(text, "no D(f) table", "not measured")
    meas, main_on, others = [], math.nan, []
    for label, (table, cols) in ctx["curves"].items():
        on = onset(table, cols)
        lowest = float(table["f"].min())
        s = "never" if math.isnan(on) else (f"≤ {on:g} Hz (lowest f studied)" if on <= lowest
                                             else f"{on:g} Hz")
        meas.append(f"{label}: {s}")
        if label.endswith("(Fig. 2 scene)"):
            main_on = on
        elif not math.isnan(on):
            others.append(on)
    gamma1 = ctx.get("f_gamma1")
    note = (f"Γ = 1 at f = {gamma1:.1f} Hz: below it a particle at rest never lifts off. "
            if gamma1 else "")
    if not math.isnan(main_on) and abs(main_on - 50) <= 2.5:
        return Row(text, "; ".join(meas), "agrees", note)
    if others and min(others) <= 52.5:
        return Row(text, "; ".join(meas), "partly", note + (
            f"Particles started at rest creep (D ≈ 0) below {main_on:g} Hz; diffusion near 50 Hz "
            "needs particles that are already bouncing (launched, dropped): the paper's ensemble "
            "of 'moving particles' was probably of that kind."))
    return Row(text, "; ".join(meas), "disagrees", note)


def _claim_spot(ctx) -> Row:
    text = "f = 54: 1/1 frequency locking, a spot at v_y⁺ ≈ 100 mm/s (k ≈ 1)"
    lock = ctx["tables"].get("locking")
    if lock is None:
        return Row(text, "no locking table", "not measured")
    meas, ok = [], []
    for fam in lock["family"].unique():
        r = _row_at(lock, 54.0, fam)
        if r is None:
            continue
        if math.isnan(r["v_peak"]):
            meas.append(f"{fam} (f = {r['f']:g}): all states in the creeping band "
                        f"({100 * r['frac_creep']:.0f} %)")
            continue
        meas.append(f"{fam} (f = {r['f']:g}): peak v_y⁺ = {r['v_peak']:.0f} mm/s, k = "
                    f"{r['k_peak']:.2f}; {100 * r['frac_creep']:.0f} % creeping")
        ok.append((fam, abs(r["k_peak"] - 1.0) <= 0.1))
    if not meas:
        return Row(text, "f = 54 not in the locking table", "not measured")
    if any(o for fam, o in ok if fam == MAIN):
        return Row(text, "; ".join(meas), "agrees")
    if any(o for _, o in ok):
        return Row(text, "; ".join(meas), "partly",
                   "The 1/1 spot exists (k = 1 is v_y⁺ = g/(2f) = 90.7 mm/s at 54 Hz) but only for "
                   f"particles that are bouncing to begin with; started at {MAIN}, they creep.")
    return Row(text, "; ".join(meas), "disagrees")


def _claim_vho(ctx) -> Row:
    text = "f = 60: virtual harmonic oscillator mode (VHO) at v_y⁺ ≈ 70 mm/s"
    r = _row_at(ctx["tables"].get("locking"), 60.0, MAIN)
    if r is None or math.isnan(r["v_peak"]):
        return Row(text, "no v_y⁺ peak at 60 Hz in the locking table", "not measured")
    d = abs(r["v_peak"] - 70.0)
    meas = (f"{MAIN}, f = {r['f']:g}: dominant v_y⁺ peak at {r['v_peak']:.0f} mm/s (k = "
            f"{r['k_peak']:.2f}); {100 * r['frac_creep']:.0f} % of states creeping")
    return Row(text, meas, "agrees" if d <= 10 else "partly" if d <= 20 else "disagrees",
               "" if d <= 10 else f"peak {d:.0f} mm/s from the paper's value")


def _claim_loops(ctx) -> Row:
    text = ("Spiral: the VHO 'spirals out' at f = 66, a two-loop spiral at 72, a third loop from "
            "76 (complete near 80), a fourth from 86 (complete near 90), a fifth from 96")
    lock = ctx["tables"].get("locking")
    if lock is None:
        return Row(text, "no locking table", "not measured")
    t = lock[lock["family"] == MAIN].sort_values("f")
    f, k = t["f"].to_numpy(float), t["k_max"].to_numpy(float)
    paper = {2: 66.0, 3: 76.0, 4: 86.0, 5: 96.0}
    starts, meas = {}, []
    for n in paper:
        above = np.nan_to_num(k, nan=-1.0) >= n
        idx = np.flatnonzero(above & (f > 58))
        if idx.size:
            starts[n] = float(f[idx[0]])
    r72 = _row_at(lock, 72.0, MAIN)
    loops72 = float(r72["k_max"]) if r72 is not None else math.nan
    meas.append("f where k_max first reaches " + ", ".join(
        f"{n}: {starts[n]:g} Hz" if n in starts else f"{n}: not reached" for n in paper))
    if len(starts) >= 2:
        fs = sorted(starts.values())
        meas.append(f"spacing Δf = {np.mean(np.diff(fs)):.1f} Hz")
    meas.append(f"k_max at 72 Hz = {loops72:.2f} (two complete loops ⇔ 2 ≤ k_max < 3)")
    good = [n for n in paper if n in starts and abs(starts[n] - paper[n]) <= 2.5]
    verdict = ("agrees" if len(good) == len(paper) and 2 <= loops72 < 3
               else "partly" if good else "disagrees")
    return Row(text, "; ".join(meas), verdict,
               "Each new loop of the spiral appears as a jump of k_max (the 0.99 quantile of "
               "v_y⁺ in units of g/(2f)) by about one: see the k(f) plot.")


def _claim_k(f0: float, k0: float, ctx) -> Row:
    text = f"k ≈ {k0:g} around f = {f0:g} (maximal v_y⁺ of the spiral)"
    r = _row_at(ctx["tables"].get("locking"), f0, MAIN)
    if r is None or math.isnan(r["k_max"]):
        return Row(text, f"no k at {f0:g} Hz", "not measured")
    d = abs(r["k_max"] - k0)
    meas = (f"{MAIN}, f = {r['f']:g}: k_max = {r['k_max']:.2f} (v_y⁺ = {r['v_max']:.0f} mm/s); "
            f"k_peak = {r['k_peak']:.2f}")
    return Row(text, meas, "agrees" if d <= K_TOL else "partly" if d <= K_CLOSE else "disagrees",
               "" if d <= K_TOL else f"|Δk| = {d:.2f}")


def _claim_rise(ctx) -> Row:
    text = "Drastic increase of D(f) on a global scale from f = 66"
    main = ctx["tables"].get("figure2")
    if main is None:
        return Row(text, "no D(f) table", "not measured")
    r66 = _row_at(main, 66.0)
    t = main[(main["f"] >= 66) & (main["f"] <= 86)]
    if r66 is None or t.empty:
        return Row(text, "66–86 Hz not in the D(f) table", "not measured")
    top = t.loc[t["D"].idxmax()]
    ratio = top["D"] / r66["D"] if r66["D"] > 0 else math.inf
    sig = top["D_lo"] > r66["D_hi"]
    meas = (f"D({r66['f']:g}) = {r66['D']:.4g} [{r66['D_lo']:.4g}, {r66['D_hi']:.4g}] → largest D in "
            f"66–86 Hz: D({top['f']:g}) = {top['D']:.4g} [{top['D_lo']:.4g}, {top['D_hi']:.4g}], "
            f"×{ratio:.1f}")
    return Row(text, meas, "agrees" if sig and ratio >= 2 else "partly" if sig else "disagrees")


def _ergo_parts(ergo: pd.DataFrame) -> pd.DataFrame:
    """Per frequency: (a) do the families' CIs overlap pairwise, (b) is every EB below its
    threshold."""
    fams = _families(ergo)
    rows = []
    for _, r in ergo.iterrows():
        # reduce's rule (a): every pair of 95 % intervals overlaps
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


def _claim_nonergodic(ctx) -> Row:
    text = "Non-ergodic (depends on the initial condition) only near the peak around f = 55"
    ergo = ctx["tables"].get("ergodicity")
    if ergo is None or len(_families(ergo)) < 2:
        return Row(text, "no table with several families", "not measured")
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
    fams = ", ".join(_families(ergo))
    verdict = "agrees" if len(bad) and not others else "partly" if len(bad) else "disagrees"
    return Row(text, meas, verdict,
               f"The families ({fams}) start in different basins: the bouncing state and "
               "creeping coexist." if len(bad) else "")


def _claim_ergodic(ctx) -> Row:
    text = "Ergodic for f ≥ 58"
    ergo = ctx["tables"].get("ergodicity")
    if ergo is None or len(_families(ergo)) < 2:
        return Row(text, "no table with several families", "not measured")
    parts = _ergo_parts(ergo)
    hi = parts[parts["f"] >= 58]
    if hi.empty:
        return Row(text, "no f ≥ 58 in the ergodicity table", "not measured")
    dis = hi[~hi["agree"]]["f"].tolist()
    eb = hi[~hi["eb_ok"]]["f"].tolist()
    meas = (f"f = {', '.join(f'{x:g}' for x in hi['f'])}: families' D "
            + ("agree everywhere" if not dis else f"disagree at {', '.join(f'{x:g}' for x in dis)}")
            + "; EB converges (Brownian level, or falling like 1/T) " + (
                "everywhere" if not eb else f"except at {', '.join(f'{x:g}' for x in eb)}"))
    if "EB_decay" in ergo:
        sel = ergo[ergo["f"] >= 58]
        meas += (f"; EB(T/2)/EB(T) = {sel['EB_decay'].min():.2f}–{sel['EB_decay'].max():.2f} "
                 f"(≥ {sel['EB_decay_threshold'].iloc[0]:.2f} passes) while EB is "
                 f"{(sel['EB'] / sel['EB_threshold']).min():.1f}–"
                 f"{(sel['EB'] / sel['EB_threshold']).max():.1f} × the level rule's threshold")
    if not dis and not eb:
        return Row(text, meas, "agrees")
    if not dis:
        return Row(text, meas, "partly",
                   "Initial conditions do not matter (criterion a), but the spread of the "
                   "time-averaged MSD between trajectories neither sits at the Brownian level "
                   "nor falls like 1/T (b).")
    return Row(text, meas, "disagrees")


def _claim_spiral_approx(ctx) -> Row:
    text = ("The flat-floor approximation Eqs. (8)–(9), no fit parameter, reproduces the spiral "
            "from the VHO on (Fig. 3 d–f)")
    stores = [s for s in (ctx["stores"].get("figure3"), ctx["stores"].get("locking")) if s]
    if not stores:
        return Row(text, "no store with collisions", "not measured")
    meas, ratios = [], []
    for f0 in (66.0, 72.0, 78.0):
        for path in stores:
            st = as_store(path)
            if not np.any(np.abs(np.asarray(st.study.frequencies) - f0) < 1e-3):
                continue
            p = st.study.params(f0)
            s = states(st, f0, MAIN if MAIN in [m.name for m in st.study.families]
                       else st.study.families[0].name)
            tm = flight_time_max(flight_times(s["t"], s["y"], s["vy"], p.g))
            d, d0 = spiral_closeness(s["y"].ravel(), s["vy"].ravel(), p.A, f0, p.g, p.alpha, tm)
            if math.isfinite(d):
                meas.append(f"{f0:g} Hz: {d:.3f} vs {d0:.3f} (ratio {d / d0:.2f})")
                ratios.append(d / d0)
            break
    if not ratios:
        return Row(text, "no states at 66, 72, 78 Hz", "not measured")
    verdict = "agrees" if max(ratios) < 0.7 else "partly" if min(ratios) < 0.9 else "disagrees"
    return Row(text, "median distance to the curve, in loop sizes, of the non-creeping states vs "
               "of uniformly scattered points: " + "; ".join(meas), verdict,
               "The outer loops follow the curve; the inner part (short flights) does not, as "
               "the paper says. Points sit lower in y than the curve by up to the arc depth "
               "R − √(R² − S²/4), which the flat-floor approximation leaves out.")


def _claim_matyas(ctx) -> Row:
    text = ("Earlier parameters (R = 25, α = 0.5; Mátyás & Klages 2004): the largest maxima of "
            "D(f) are integer frequency lockings")
    table, lock = ctx["tables"].get("figure2_matyas2004"), ctx["tables"].get("locking_matyas2004")
    if table is None or lock is None:
        return Row(text, "no matyas2004 tables", "not measured")
    ext = [e for e in curve_extrema(table, _cols(table, None)) if e.kind == "max"]
    ext = sorted(ext, key=lambda e: -e.D)[:3]
    if not ext:
        return Row(text, "no significant maximum", "disagrees")
    meas, kinds = [], []
    for e in ext:
        ks = []
        for fam in lock["family"].unique():
            r = _row_at(lock, e.f, fam)
            if r is not None and math.isfinite(r["k_peak"]):
                ks.append((fam, r["k_peak"], r["k_max"]))
        main = next((k for k in ks if k[0] == MAIN), ks[0] if ks else None)
        kind = "no k" if main is None else _locking_kind(main[1])
        kinds.append(kind)
        meas.append(f"max at {e.f:g} Hz (D = {e.D:.3g}): " + (", ".join(
            f"{fam} k_peak = {kp:.2f}, k_max = {km:.2f}" for fam, kp, km in ks) or "no k")
            + f" → {kind}")
    hits = sum(k.startswith("integer") for k in kinds)
    verdict = "agrees" if hits == len(ext) else "partly" if hits else "disagrees"
    return Row(text, "; ".join(meas), verdict,
               f"The {len(ext)} largest significant maxima, largest first; locking read from the "
               f"dominant v_y⁺ peak of the {MAIN} family (within {K_TOL:g} of an integer ≥ 1, or "
               "of a half-integer). The amplitude (A = 0.1 here) and the frequency range of the "
               "2004 study are not known from this paper, so the peaks need not be the same.")


def _locking_kind(k: float) -> str:
    if abs(k - round(k)) <= K_TOL and round(k) >= 1:
        return f"integer locking k ≈ {round(k)}"
    half = math.floor(k) + 0.5
    if abs(k - half) <= K_TOL:
        return f"half-integer k ≈ {half:g}"
    return "no simple locking"


def _with_note(row: Row, extra: str) -> Row:
    if row.verdict in ("agrees", "not measured") or not extra:
        return row
    return Row(row.claim, row.measured, row.verdict, (row.note + " " + extra).strip())


def _falling_curves(ctx, f_to: float = 57.5) -> tuple[list[str], float]:
    """Labels of the curves that move at their lowest f and never rise significantly (next D
    above the previous CI) from there up to ``f_to`` Hz; and that lowest f."""
    out, f_low = [], math.nan
    for label, (table, cols) in ctx["curves"].items():
        t = table.sort_values("f")
        t = t[t["f"] <= f_to]
        D, lo, hi = (t[c].to_numpy(float) for c in cols)
        if len(t) < 2 or not (np.isfinite(lo[0]) and lo[0] > 0):
            continue
        f_low = float(t["f"].iloc[0]) if math.isnan(f_low) else min(f_low, float(t["f"].iloc[0]))
        if np.all(lo[1:] <= hi[:-1]):
            out.append(label)
    return out, f_low


def _note_54(ctx) -> str:
    """Likely reason for a missing maximum near 54: where the 1/1 orbit stops being stable."""
    p = ctx.get("params")
    if p is None:
        return ""
    g2 = period1_limit(p["alpha"])
    f2 = math.sqrt(g2 * p["g"] / p["A"]) / (2 * math.pi)
    falling, f_low = _falling_curves(ctx)
    seen = (f"; the D of {', '.join(falling)} indeed falls from the lowest f studied "
            f"({f_low:g} Hz) to 57 Hz without a significant rise" if falling else "")
    return (f"Likely reason: on a flat floor the 1/1 orbit is stable only up to Γ = {g2:.4f}, "
            f"f = {f2:.1f} Hz (Luck & Mehta); above it bouncing particles decay into creeping "
            f"within our run{seen}. A maximum near 54 needs an ensemble that still bounces "
            "there, e.g. shorter runs or particles counted only while moving.")


#: the paper's claims in its order: (text or kind, evaluator)
CLAIMS: Sequence[Callable[[Mapping], Row]] = (
    _claim_onset,
    lambda c: _with_note(_extremum_claim("max", 54.0, WINDOW,
                                         "Local maximum of D(f) around f = 54", c), _note_54(c)),
    _claim_spot,
    lambda c: _extremum_claim("min", 58.0, WINDOW, "Local minimum around f = 58 (1/1 resonance "
                              "destroyed, creeping dominates)", c),
    lambda c: _extremum_claim("max", 60.0, WINDOW, "Local maximum at f = 60", c),
    _claim_vho,
    lambda c: _extremum_claim("min", 62.0, WINDOW, "Local minimum around f = 62 (VHO unstable)",
                              c),
    _claim_loops,
    _claim_rise,
    lambda c: _extremum_claim("max", 80.0, 3.0, "Washed-out local maximum around f = 80", c),
    lambda c: _claim_k(60.0, 1.47, c),
    lambda c: _claim_k(72.0, 2.5, c),
    lambda c: _claim_k(80.0, 3.43, c),
    lambda c: _claim_k(90.0, 4.5, c),
    _claim_spiral_approx,
    _claim_nonergodic,
    _claim_ergodic,
    _claim_matyas,
)


def evaluate(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str] | None = None,
             f_gamma1: float | None = None, params: Mapping[str, float] | None = None
             ) -> tuple[list[Row], dict[str, list[Extremum]]]:
    """All claim rows, and the significant extrema of every D(f) curve.

    params -- the Fig. 2 scene's parameters (g, A, alpha, ...), for explanatory notes
    """
    cv = curves(tables)
    ctx = {"tables": tables, "stores": dict(stores or {}), "curves": cv,
           "extrema": {label: curve_extrema(t, cols) for label, (t, cols) in cv.items()},
           "f_gamma1": f_gamma1, "params": params}
    return [claim(ctx) for claim in CLAIMS], ctx["extrema"]


# -------------------------------------------------------------------------------------------
# the document
# -------------------------------------------------------------------------------------------
def _md(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _scene_rows(stores: Mapping[str, str], run_log: Mapping | None) -> list[str]:
    lines = ["| scene | workflow | accuracy | particles × t_max | frequencies × families | chunks "
             "done | task time (sum of chunk_seconds) | wall time of the run |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    total = 0.0
    for name, path in stores.items():
        try:
            st = as_store(path)
        except Exception as e:  # a store that cannot be opened is reported, not fatal
            lines.append(f"| {name} | – | – | – | – | – | – | cannot open: {_md(e)} |")
            continue
        g = st.group()
        secs = float(np.nansum(np.asarray(g["chunk_seconds"][...])))
        total += secs
        done = st.done()
        acc = st.study.accuracy
        log = (run_log or {}).get("scenes", {}).get(name, {})
        wall = (f"{log['wall_s']:.0f} s ({log.get('computed', 0)} chunks computed on "
                f"{log.get('workers', '?')} workers)" if "wall_s" in log else "–")
        lines.append(f"| {name} | `{log.get('workflow', st.study.source)}` | {acc.preset} | "
                     f"{acc.n_particles} × {acc.t_max:g} s | {len(st.study.frequencies)} × "
                     f"{len(st.study.families)} | {int(done.sum())}/{done.size} | {secs:.0f} s | "
                     f"{wall} |")
    lines.append(f"\nTotal task time over all scenes: {total:.0f} s ≈ {total / 3600:.2f} core-hours.")
    return lines


def _params_lines(stores: Mapping[str, str]) -> list[str]:
    path = stores.get("figure2") or next(iter(stores.values()), None)
    if path is None:
        return ["(no store)"]
    st = as_store(path)
    attrs = dict(st.group().attrs)
    p = attrs.get("params", {})
    lines = ["| quantity | value |", "| --- | --- |"]
    for k, unit in (("g", "mm/s²"), ("A", "mm"), ("R", "mm"), ("S", "mm"), ("alpha", ""),
                    ("beta", "")):
        if k in p:
            lines.append(f"| {k} | {p[k]:g} {unit} |")
    for k, v in attrs.get("numerics", {}).items():
        lines.append(f"| numerics.{k} | {v:g} |")
    lines.append(f"| accuracy preset (Fig. 2 scene) | {attrs.get('accuracy', {}).get('preset')} |")
    lines.append(f"| bbb version | {attrs.get('bbb_version')} |")
    lines.append(f"| store created | {attrs.get('created')} |")
    A = p.get("A")
    g = p.get("g", 9800.0)
    lines += ["", (
        f"**Amplitude.** The paper prints A = 0.01 (units of 1 mm) with g = 9800 mm/s². With "
        "A = 0.01 the peak floor acceleration Γ = A(2πf)²/g stays below 0.41 for f ≤ 100 Hz and "
        "no particle ever leaves the floor (docs/amplitude.md). The paper's own landmarks — "
        "onset near 50 Hz, the 1/1 spot at v_y⁺ ≈ 100 near 54 Hz, the VHO at ≈ 70 near 60 Hz — "
        f"fit A = 0.1, which we use (A = {A:g} mm here; Γ = 1 at f = "
        f"{math.sqrt(g / A) / (2 * math.pi):.1f} Hz)." if A else "")]
    return lines


CAPTIONS = {
    "fig1_geometry": (
        "Fig. 1 — The bouncing ball billiard drawn from `bbb.surface`: arcs of radius R centred "
        "S apart, the floor at the phase of the collision marked ★ (solid) and at its rest "
        "height (dashed), and four free flights of one particle computed by `bbb.simulate` "
        "(launched at f = 60 Hz, after 1 s). Panel (a) exaggerates the vertical scale by the "
        "factor written in it; panel (b) shows the collision ★ at true scale with the local "
        "frame v_⊥ (outward normal of the arc) and v_∥ (tangent), and the incoming and "
        "outgoing velocity directions."),
    "fig2_diffusion": (
        "Fig. 2 — D(f) for α = 0.7, R = 15, particles started at rest, with the bootstrap 95 % "
        "CI on every point (resampling particles). Letters mark the frequencies of Fig. 3. "
        "Squares: D of other initial-condition families (ergodicity scene) where it lies "
        "outside the rest family's CI. Shading: darker where the reduce verdict (families' D "
        "agree, and EB at the Brownian level or falling like 1/T) is negative; lighter where it "
        "rests on the EB of the one family only. Inset: 50–67 Hz magnified."),
    "fig3_phase_space": (
        "Fig. 3 — Post-collision states (y, v_y⁺) at f = 54, 58, 60, 66, 72, 78 Hz; black: "
        "particles started at rest, blue: launched (Fig. 3 and locking scenes). Dotted: the "
        "upper edge of the creeping band, 1.1 A 2πf. Red (d–f): Eqs. (8)–(9) with "
        "t_0 = 1/(2f) (largest upward floor velocity), t_1 = t_0 + t_c, t_c ∈ [0, t_max(f)], "
        "t_max the 0.99 quantile of the simulated free-flight times; no fit parameter."),
    "fig_locking": (
        "k = 2 v_y⁺ f / g against f. Filled: from the maximal v_y⁺ of the spiral (0.99 "
        "quantile above the creeping band); open: from the dominant peak of the v_y⁺ "
        "distribution. Solid lines: integer k, dashed: half-integer. Stars: the paper's values "
        "1.47, 2.5, 3.43, 4.5 at 60, 72, 80, 90 Hz."),
    "fig2_matyas2004": (
        "Fig. 2 for the earlier parameters R = 25, α = 0.5 (Mátyás & Klages 2004), particles "
        "at rest, 95 % CIs; lower panel: k from the maximal v_y⁺ (filled) and the dominant "
        "v_y⁺ peak (open), integer lines."),
}


def write_report(out_dir: str | os.PathLike, *, stores: Mapping[str, str],
                 tables: Mapping[str, pd.DataFrame], figures: Sequence[str | os.PathLike] = (),
                 run_log: Mapping | None = None) -> Path:
    """Write ``<out_dir>/REPORT.md`` and return its path.

    stores  -- scene name -> store path (figure2, ergodicity, figure3, locking, ...)
    tables  -- "figure2", "ergodicity", "figure2_matyas2004" (reduce diffusion tables) and
               "locking", "locking_matyas2004" (locking tables); any may be missing
    figures -- paths of the figures drawn (listed with captions)
    run_log -- make_figures' log: per-scene wall time of this invocation, FAST flag
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    f_gamma1 = params = None
    if stores.get("figure2"):
        p = as_store(stores["figure2"]).study.params(60.0)
        f_gamma1 = math.sqrt(p.g / p.A) / (2 * math.pi) if p.A > 0 else None
        params = p.as_dict() if p.A > 0 else None
    rows, extrema = evaluate(tables, stores, f_gamma1, params)
    fast = bool((run_log or {}).get("fast"))
    L = ["# Klages, Barna & Mátyás (2004): the claims beside our measurements", ""]
    L.append(f"Written {_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')} by "
             f"`python -m pipeline.make_figures{' --fast' if fast else ''}`"
             + (" — **draft accuracy (FAST): numbers are rough**" if fast else "") + ". "
             "Every measured number below is computed from the stores and tables; regenerate, "
             "do not edit.")
    if run_log and "wall_s" in run_log:
        L.append(f"\nWall time of the runs and reductions behind it: {run_log['wall_s']:.0f} s "
                 f"({run_log['wall_s'] / 60:.1f} min; per scene below).")
    L += ["", "## Claims", "", "| # | the paper says | we measured | verdict | notes |",
          "| --- | --- | --- | --- | --- |"]
    for i, r in enumerate(rows, 1):
        L.append(f"| {i} | {_md(r.claim)} | {_md(r.measured)} | **{r.verdict}** | {_md(r.note)} |")
    by: dict[str, list[str]] = {}
    for i, r in enumerate(rows, 1):
        by.setdefault(r.verdict, []).append(str(i))
    L += ["", "Summary: " + "; ".join(f"**{v}** {len(n)} (#{', #'.join(n)})" for v, n in by.items())
          + "."]
    L += ["", "## Significant extrema of D(f), located by `bbb.extrema`", ""]
    for label, ext in extrema.items():
        L.append(f"- **{label}**: " + ("; ".join(_fmt_ext(e) + f", z = {e.z:.1f}" for e in ext)
                                       if ext else "none"))
    lock = tables.get("locking")
    if lock is not None:
        L += ["", "## Locking at the paper's frequencies", "",
              "| f (Hz) | family | creeping | max v_y⁺ (mm/s) | k_max | peak v_y⁺ (mm/s) | k_peak | "
              "t_max (ms) | f·t_max |", "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for f0 in (54, 58, 60, 66, 72, 76, 78, 80, 86, 90, 96):
            for fam in lock["family"].unique():
                r = _row_at(lock, f0, fam, tol=0.25)
                if r is None:
                    continue
                L.append(f"| {r['f']:g} | {fam} | {100 * r['frac_creep']:.0f} % | {r['v_max']:.0f} | "
                         f"{r['k_max']:.2f} | {r['v_peak']:.0f} | {r['k_peak']:.2f} | "
                         f"{1e3 * r['t_max']:.1f} | {r['loops']:.2f} |")
        L.append("\nThe whole table: `locking.csv` beside this report.")
    L += ["", "## Parameters actually used", ""] + _params_lines(stores)
    L += ["", "## Runs", ""] + _scene_rows(stores, run_log)
    L += ["", "## Definitions", "",
          f"- **Creeping band**: v_y⁺ ≤ (1 + {CREEP_MARGIN:g}) A 2πf, the floor's peak speed plus "
          "a margin; creeping particles leave each collision with about the floor's velocity.",
          f"- **Maximal v_y⁺ of the spiral**: the {MAX_QUANTILE:g} quantile of v_y⁺ over the "
          "states above the creeping band (robust against single outliers); k_max = 2 v f / g.",
          "- **Dominant peak**: the mode of a Gaussian kernel density estimate (Silverman "
          "bandwidth) of v_y⁺ above the creeping band; k_peak = 2 v f / g.",
          f"- **t_max(f)**: the {TMAX_QUANTILE:g} quantile of the free-flight times, i.e. "
          "differences of consecutive collision times of one particle, kept only where the "
          f"parabola from the earlier collision lands within {FLIGHT_TOL:g} mm of the later one "
          "(intervals spent stuck to the floor are not flights).",
          "- **Significant extremum** (`bbb.extrema`): a maximum is a point from which the curve, "
          "on both sides, reaches a significantly lower point before a higher one; 'a "
          "significantly above b' means (D_a − D_b)/√(s_a⁻² + s_b⁺²) > z_crit with s± read off "
          "the 95 % CIs and z_crit Bonferroni-corrected over all pairs of points (4.36 for 124 "
          f"points), and D_a − D_b > {100 * DEPTH_FRACTION:g} % of the curve's largest D. The "
          "position range is the contiguous run of points whose CIs overlap the extremum's.",
          f"- **Onset of diffusion**: the lowest f at which D_lo > {100 * ONSET_FRACTION:g} % "
          "of the curve's largest D.",
          "- **Ergodicity** (reduce): (a) the initial-condition families' D agree within their "
          "CIs and (b) EB = Var(δ²)/⟨δ²⟩² of the time-averaged MSD converges: it is below a "
          "tolerance times its Brownian value, or it falls like 1/T (EB over the first half of "
          "the run / EB over all of it ≥ halfway between 1 and the Brownian ratio ≈ 2; a "
          "population mixing different D keeps the ratio near 1); `ergodic` needs both."]
    if figures:
        L += ["", "## Figures", ""]
        for p in figures:
            p = Path(p)
            if p.suffix != ".png":
                continue
            L.append(f"- [`{p.name}`]({p.name}) (and `.pdf`): {CAPTIONS.get(p.stem, '')}")
    path = out / "REPORT.md"
    path.write_text("\n".join(L) + "\n", encoding="utf-8")
    return path
