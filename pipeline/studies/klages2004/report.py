"""The paper's section of ``figures/REPORT.md`` beyond its claims table, and its figures'
captions: the extrema, stationarity, ergodicity, locking and definitions.

Every number in it is computed from the reduce tables (D(f) with bootstrap CIs,
stationarity and ergodicity columns), the locking tables (:mod:`pipeline.tables.collisions`, with
bootstrap CIs of k) and the stores' attributes; nothing measured is typed in.  The claims are
data (:data:`pipeline.studies.klages2004.claims.CLAIMS`), judged by :mod:`pipeline.claims.claim` with the
CI of each measured number against the tolerance the claim declares (rule in that module,
restated in the report).  Significant extrema: :func:`bbb.analysis.extrema.find_extrema`
(Bonferroni-corrected, differences below 1 % of the curve's largest D ignored).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from bbb.analysis.extrema import Extremum, critical_z
from bbb.analysis.locking import CREEP_MARGIN, FLIGHT_TOL, MAX_QUANTILE, TMAX_QUANTILE
from bbb.analysis.stationarity import TOLERANCE as STATIONARITY_TOL
from bbb.analysis.stats.ergodicity import cv2_ci_coverage

from ...claims.curves import DEPTH_FRACTION
from ...claims.measures import ONSET_FRACTION, fmt_d, row_at, stationarity_mark
from .claims import context
from .measures import curves

__all__ = ["CAPTIONS", "further_lines"]

_fmt_d = fmt_d
_row_at = row_at


def _fmt_ext(e: Extremum) -> str:
    rng = f"{e.f_lo:g}–{e.f_hi:g}" if e.f_hi > e.f_lo else f"{e.f:g}"
    return (f"{e.kind} at f = {e.f:g} Hz (range {rng}), D = {_fmt_d(e.D)} "
            f"[{_fmt_d(e.lo)}, {_fmt_d(e.hi)}]")


def _stationarity_lines(tables: Mapping[str, pd.DataFrame]) -> list[str]:
    """Per D(f) table: the frequencies where D depends on the run length."""
    out = []
    for name, t in tables.items():
        if t is None or "stationary" not in t:
            continue
        flag = t["stationary"].astype("boolean").eq(False).fillna(False).to_numpy(bool)
        checked = int(t["stationary"].notna().sum())
        if not flag.any():
            out.append(f"- **{name}**: stationary at all {checked} frequencies checked.")
            continue
        pts = [f"{r['f']:g} Hz (D₂/D₁ = {r['D_half2'] / r['D_half1']:.2f})"
               if r["D_half1"] > 0 else f"{r['f']:g} Hz" for _, r in t[flag].iterrows()]
        out.append(f"- **{name}**: D depends on the run length at {flag.sum()} of {checked} "
                   f"frequencies: {', '.join(pts)} (hollow markers in the figures).")
    return out


def _pct(x: float) -> str:
    return f"{100 * x:.0f} %"


def _cv2_text(r: pd.Series) -> str:
    """The signed CV² with its CI (tables from before CV² was reported: the clipped CV)."""
    if "CV2_D" not in r:
        return f"CV {_pct(r['CV_D'])}"
    return f"{r['CV2_D']:.3g} [{r['CV2_D_lo']:.3g}, {r['CV2_D_hi']:.3g}]"


def _bound_text(up: float) -> str:
    """The spread bound in CV, or why there is none (its CV² bound is ≤ 0)."""
    return _pct(up) if math.isfinite(up) else "none (CV² bound ≤ 0)"


def _ergodicity_rule_line(ergo: pd.DataFrame) -> str:
    """The rule behind the ergodicity verdicts and what it can and cannot exclude."""
    r = ergo.iloc[0]
    return (f"Rule `{r['rule']}` (`bbb.analysis.stats.ergodic_verdict`, calibrated on synthetic "
            "populations of known per-particle D spread before it was applied here: "
            "docs/statistics.md): ergodic iff the families' D agree within their CIs and the "
            "estimated squared spread CV²(D_i) = 2 EB(T) − EB(T/2) is at most "
            f"({_pct(r['cv_max'])})² = {r['cv_max'] ** 2:.3g}; CV² is shown signed, with its "
            "95 % bootstrap CI (its noise reaches below 0 where the spread is small; the CI "
            f"covered the true CV² in {_pct(cv2_ci_coverage()[0])}–{_pct(cv2_ci_coverage()[1])} "
            "of synthetic samples). "
            f"Measured worst error rates at this ensemble size: false positive "
            f"{_pct(r['rule_fp'])}, false negative {_pct(r['rule_fn'])}. A verdict excludes only "
            "spreads above the 'excluded above' column; smaller spreads cannot be excluded.")


# -------------------------------------------------------------------------------------------
# the document
# -------------------------------------------------------------------------------------------
def _ci(r: pd.Series, col: str) -> str:
    lo, hi = r.get(f"{col}_lo", math.nan), r.get(f"{col}_hi", math.nan)
    return f"{r[col]:.2f}" + (f" [{lo:.2f}, {hi:.2f}]" if np.isfinite([lo, hi]).all() else "")


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
        "rests on the EB of the one family only. Hollow circles: D depends on the run length "
        "(first vs second half of the run, `bbb.analysis.stationarity`). Inset: 50–67 Hz magnified."),
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
    "fig_finescale": (
        "Fine scales (scene finescale, 58–64 Hz from rest, refined to 0.05 Hz around extrema "
        "and jumps): (a) significant extrema per Hz at the resolutions 0.4, 0.2, 0.1, 0.05 Hz "
        "(sub-samples of the refined grid), 95 % bootstrap intervals of D(f) within its CIs; "
        "(b) the refined D(f), 95 % CIs (grey), the 0.4 Hz grid (black), refined points "
        "(blue), the extrema with the interval each lies in (▲ max, ▼ min)."),
}


def further_lines(tables: Mapping[str, pd.DataFrame], verdicts=None) -> list[str]:
    """The lines of the paper's section after its claims table: the significant extrema of
    every D(f) curve, stationarity, the ergodicity verdicts, locking at the paper's
    frequencies and the definitions, all from ``tables``."""
    extrema = context(tables)["extrema"]
    L = ["", "## Significant extrema of D(f), located by `bbb.analysis.extrema`", ""]
    for label, ext in extrema.items():
        tbl = curves(tables)[label][0]
        L.append(f"- **{label}**: " + ("; ".join(_fmt_ext(e) + f", z = {e.z:.1f}"
                                                 + stationarity_mark(tbl, e.f) for e in ext)
                                       if ext else "none"))
    stat = _stationarity_lines({k: tables.get(k) for k in ("figure2", "ergodicity",
                                                           "figure2_matyas2004")})
    if stat:
        L += ["", "## Stationarity: does D depend on the run length?", "",
              "D of the first and the second half of the analysed run (same fit fractions), "
              "with a paired bootstrap CI over particles of the difference; flagged where that "
              f"CI lies beyond ±{100 * STATIONARITY_TOL:g} % of D (`bbb.analysis.stationarity`; the rule "
              "was calibrated on synthetic walks before it was applied here: its false-flag rate "
              "and its power on a diffusivity that doubles over the run are tabulated in that "
              "module and re-measured by tests/bbb/analysis/test_stationarity.py).", ""] + stat
    ergo = tables.get("ergodicity")
    if ergo is not None and "CV_D_upper" in ergo:
        L += ["", "## Ergodicity verdicts, frequency by frequency", "",
              _ergodicity_rule_line(ergo), "",
              "| f (Hz) | families' D agree | CV² of per-particle D [95 % CI] | spread excluded "
              "above (95 %) | verdict |", "| --- | --- | --- | --- | --- |"]
        for _, r in ergo.sort_values("f").iterrows():
            L.append(f"| {r['f']:g} | {'yes' if r['families_agree'] else 'no'} | "
                     f"{_cv2_text(r)} | {_bound_text(r['CV_D_upper'])} | "
                     f"{'ergodic' if r['ergodic'] else 'not ergodic'} |")
    lock = tables.get("locking")
    if lock is not None:
        L += ["", "## Locking at the paper's frequencies", "",
              "| f (Hz) | family | creeping | max v_y⁺ (mm/s) | k_max [95 % CI] | peak v_y⁺ (mm/s) "
              "| k_peak [95 % CI] | t_max (ms) | f·t_max |",
              "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for f0 in (54, 58, 60, 66, 72, 76, 78, 80, 86, 90, 96):
            for fam in lock["family"].unique():
                r = _row_at(lock, f0, fam, tol=0.25)
                if r is None:
                    continue
                L.append(f"| {r['f']:g} | {fam} | {100 * r['frac_creep']:.0f} % | {r['v_max']:.0f} | "
                         f"{_ci(r, 'k_max')} | {r['v_peak']:.0f} | {_ci(r, 'k_peak')} | "
                         f"{1e3 * r['t_max']:.1f} | {r['loops']:.2f} |")
        L += ["", "The whole table: `locking.csv` beside this report."]
    n_main = len(tables["figure2"]) if tables.get("figure2") is not None else 0
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
          "- **Significant extremum** (`bbb.analysis.extrema`): a maximum is a point from which the curve, "
          "on both sides, reaches a significantly lower point before a higher one; 'a "
          "significantly above b' means (D_a − D_b)/√(s_a⁻² + s_b⁺²) > z_crit with s± read off "
          "the 95 % CIs and z_crit Bonferroni-corrected over all pairs of points"
          + (f" ({critical_z(n_main):.2f} for the {n_main} points of Fig. 2)" if n_main > 1 else "")
          + f", and D_a − D_b > {100 * DEPTH_FRACTION:g} % of the curve's largest D. The "
          "position range is the contiguous run of points whose CIs overlap the extremum's.",
          f"- **Onset of diffusion**: the lowest f at which D_lo > {100 * ONSET_FRACTION:g} % "
          "of the curve's largest D.",
          "- **Ergodicity** (reduce): (a) the initial-condition families' D agree within their "
          "CIs and (b) EB = Var(δ²)/⟨δ²⟩² of the time-averaged MSD converges: it is below a "
          "tolerance times its Brownian value, or it falls like 1/T (EB over the first half of "
          "the run / EB over all of it ≥ halfway between 1 and the Brownian ratio ≈ 2; a "
          "population mixing different D keeps the ratio near 1); `ergodic` needs both."]
    return L
