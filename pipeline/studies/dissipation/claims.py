"""The D(f, α) map's claims as data, judged on the map's own points (:mod:`pipeline.claims.record`).

Rules, fixed before the map was looked at (tests/pipeline/studies/dissipation/test_claims.py
turns each on synthetic maps with known answers):

lines           the judged α lines (:func:`.lines.judged_lines`): the α values the scene lists,
                each a whole D(f) curve; α values refinement added hold a few points and are
                drawn, not judged.
onset           per line, the lowest f whose D_lo exceeds 1 % of the line's largest D, with
                the CI of the paper's claim 1 (:func:`pipeline.claims.measures.onset_ci`).
thresholds      f(Γ) = sqrt(Γ g / A) / 2π of the flat-floor 1/1 orbit's existence Γ₁(α) and
                loss of stability Γ'(α) (:mod:`bbb.analysis.period1`).  A threshold
                *predicts the onset* on a line when judging the onset against f(Γ) ± 2.5 Hz
                (claim 1's tolerance: 'around f = 50' read off the paper's Fig. 2) gives
                'agrees' or 'agrees within the CI'; the claim wants it on ≥ 75 % of the lines
                (a level), and (a contrast) the onset to move with the threshold across α:
                Spearman's ρ(onset, f(Γ)) > 0 with a two-sided permutation p ≤ 0.05
                (:mod:`pipeline.claims.rank`).
first maximum   per line, the first significant maximum of D(f) above the onset (the extrema
                rule of the paper's claims: family-wise α = 0.05, depth ≥ 1 % of the line's
                max D) -- at α = 0.7 the VHO maximum the paper puts at 60 Hz.  It *moves with
                α* when the permutation p of ρ(α, its f) is ≤ 0.05, either sign; at α = 0.7 it
                must sit at 60 ± 2 Hz (claim 5's band).
loops           per line of the locking map (32 particles, 150 s, post-collision states), the
                lowest f where k_max = 2 v_max f / g reaches 2 and 3 (claim 8's rule); each
                *moves with α* when the permutation p of ρ(α, f) is ≤ 0.05.
ergodicity      among the points where D_lo exceeds 1 % of their line's max D (something
                diffuses), those the reduce verdict calls not ergodic (column ``ergodic``:
                the calibrated rule of docs/statistics.md, false-positive rate ≤ 1 % per
                point).  'Only next to the onset' = within ONSET + 4 Hz (the paper: non-ergodic
                at its 1/1 peak near 55 Hz, ergodic from 58; its peak's onset is 54 Hz):
                (a) the share beyond that window, with its Wilson interval, lies in [0, 5 %],
                and (b) the share inside exceeds the share beyond (Newcombe's interval of the
                difference above 0).
cuts            the α = 0.7 line against the committed Fig. 2 curve, and the α = 0.5 line of
                the R = 25 map against Mátyás & Klages' Fig. 2, frequency by frequency where
                they share one (:mod:`.cuts`): agree at ≥ 95 % of the compared frequencies.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from bbb import Params
from bbb.analysis.period1 import frequency_at, gamma_1, gamma_prime
from bbb.analysis.stats.proportion import share_difference, wilson

from ...claims.rank import rank_trend
from ...claims.record import Band, Claim, Measured, Part, Quantity, judge, measure
from .lines import cut, first_max_above, first_reaching, judged_lines, listed_alphas, onset

__all__ = ["MAP", "LOCKING", "R25", "CUTS", "ONSET_TOL", "LEVEL_SHARE", "P_TREND", "NEAR_ONSET",
           "BEYOND_MAX", "CUT_SHARE", "CLAIMS", "threshold_frequency", "cut_line"]

MAP, LOCKING, R25 = "dissipation", "dissipation_locking", "dissipation_r25"
#: (label, the cut's α) of the cuts table's ``cut`` column
CUTS = {"figure2": ("Fig. 2 (α = 0.7, R = 15)", 0.7),
        "figure2_matyas2004": ("Mátyás & Klages' Fig. 2 (α = 0.5, R = 25)", 0.5)}
ONSET_TOL = 2.5  # Hz, claim 1's tolerance
LEVEL_SHARE = 0.75  # of the judged lines
P_TREND = 0.05
NEAR_ONSET = 4.0  # Hz above the onset
BEYOND_MAX = 0.05
CUT_SHARE = 0.95
VHO = (0.7, 60.0, 2.0)  # α, the paper's f, its tolerance (claim 5)
_GOOD = ("agrees", "agrees within the CI")
_THRESHOLDS = {"gamma_prime": ("Γ'", gamma_prime), "gamma_1": ("Γ₁", gamma_1)}


def threshold_frequency(name: str, alpha, preset: str = "klages2004"):
    """f (Hz) at which the preset's floor (A, g) reaches the threshold ``name`` (gamma_prime,
    gamma_1) at restitution ``alpha``."""
    p = Params.preset(preset, f=1.0)
    return frequency_at(_THRESHOLDS[name][1](alpha), p.A, p.g)


def _trend_part(label: str, x, y, sign: int = 0) -> Part:
    """A part judged by the permutation p of ρ(x, y) (≤ P_TREND); ``sign`` +1 demands ρ > 0."""
    rho, p, n = rank_trend(x, y)
    found = math.isfinite(rho) and (sign == 0 or np.sign(rho) == sign)
    return Part(label, Quantity(p), f"ρ = {rho:.2f}, permutation p = {p:.3g} over {n} lines"
                if math.isfinite(rho) else f"fewer than 3 lines located ({n})",
                band=Band(0.0, P_TREND, f"permutation p ≤ {P_TREND:g}"), found=found)


def _lines(ctx, scene: str = MAP) -> dict[float, pd.DataFrame]:
    return judged_lines(ctx["tables"].get(f"{scene}_diffusion"), _listed(ctx))


def _listed(ctx) -> tuple[float, ...]:
    """The α lines judged: ``ctx["listed"]``, else those the shipped scene lists."""
    return ctx.get("listed") or listed_alphas(MAP)


@measure("dissipation.onset_threshold")
def onset_threshold(claim: Claim, ctx) -> Measured:
    name = claim.options["threshold"]
    sym = _THRESHOLDS[name][0]
    lines = _lines(ctx)
    if not lines:
        return Measured(missing="no D(f, α) map reduced")
    alphas, ons, preds, texts, good = [], [], [], [], 0
    for a, line in lines.items():
        q, fp = onset(line), float(threshold_frequency(name, a))
        v = judge(q, Band.around(fp, ONSET_TOL, ""))
        good += v in _GOOD
        alphas.append(a), ons.append(q.value), preds.append(fp)
        texts.append(f"α = {a:g}: {q.text('g') if math.isfinite(q.value) else 'none'} vs "
                     f"{fp:.1f}")
    share = good / len(lines)
    return Measured([
        Part(f"lines whose onset lies within ± {ONSET_TOL:g} Hz of f({sym})",
             Quantity(share), f"{good} of {len(lines)} ({'; '.join(texts)} Hz)",
             band=Band(LEVEL_SHARE, 1.0, f"≥ {100 * LEVEL_SHARE:g} % of the lines")),
        _trend_part(f"the onset moves with f({sym}) across α", preds, ons, sign=+1)])


@measure("dissipation.first_maximum")
def first_maximum(claim: Claim, ctx) -> Measured:
    lines = _lines(ctx)
    if not lines:
        return Measured(missing="no D(f, α) map reduced")
    located = {a: first_max_above(line, onset(line).value) for a, line in lines.items()}
    texts = "; ".join(f"α = {a:g}: {q.text('g') if math.isfinite(q.value) else 'none'}"
                      for a, q in located.items())
    parts = [_trend_part("its position moves with α", list(located),
                         [q.value for q in located.values()])]
    a0, f0, tol = VHO
    q0 = next((q for a, q in located.items() if abs(a - a0) < 1e-9), None)
    if q0 is not None:
        parts.append(Part(f"α = {a0:g} (the VHO maximum)", q0, q0.text("g") + " Hz",
                          band=Band.around(f0, tol, "claim 5: 'local maximum at f = 60'", "Hz"),
                          found=math.isfinite(q0.value)))
    return Measured(parts, text=f"first maximum above the onset: {texts} Hz")


@measure("dissipation.loops")
def loops(claim: Claim, ctx) -> Measured:
    lock = judged_lines(ctx["tables"].get(f"{LOCKING}_locking"), _listed(ctx))
    if not lock:
        return Measured(missing="no locking map reduced")
    parts = []
    for n in (2, 3):
        at = {a: first_reaching(line, "k_max", n) for a, line in lock.items()}
        p = _trend_part(f"k_max reaches {n}: moves with α", list(at),
                        [q.value for q in at.values()])
        located = "; ".join(f"α = {a:g}: {q.value:g}" for a, q in at.items()
                            if math.isfinite(q.value))
        parts.append(Part(p.label, p.q, f"{p.text} ({located or 'never reached'} Hz)",
                          band=p.band, found=p.found))
    return Measured(parts)


def _diffusing(line: pd.DataFrame) -> pd.DataFrame:
    D = line["D"].to_numpy(float)
    top = np.nanmax(D) if np.isfinite(D).any() else math.nan
    keep = np.nan_to_num(line["D_lo"].to_numpy(float), nan=-np.inf) > 0.01 * top
    return line[keep]


@measure("dissipation.ergodicity")
def ergodicity(claim: Claim, ctx) -> Measured:
    lines = _lines(ctx)
    if not lines:
        return Measured(missing="no D(f, α) map reduced")
    near, beyond, where = [0, 0], [0, 0], []
    for a, line in lines.items():
        f_on = onset(line).value
        d = _diffusing(line)
        if not math.isfinite(f_on) or "ergodic" not in d or d.empty:
            continue
        bad = ~d["ergodic"].astype(float).fillna(1.0).astype(bool).to_numpy()
        inside = (d["f"] < f_on + NEAR_ONSET).to_numpy()
        for box, sel in ((near, inside), (beyond, ~inside)):
            box[0] += int(bad[sel].sum())
            box[1] += int(sel.sum())
        where += [f"α = {a:g}: {', '.join(f'{x:g}' for x in d['f'][bad])}"] if bad.any() else []
    if near[1] + beyond[1] == 0:
        return Measured(missing="no diffusing point with an ergodicity verdict")
    pb, lb, hb = wilson(*beyond)
    dd, dl, dh = share_difference(*near, *beyond)
    return Measured([
        Part(f"not ergodic beyond onset + {NEAR_ONSET:g} Hz",
             Quantity(pb, lb, hb, "", "Wilson interval"),
             f"{beyond[0]} of {beyond[1]} points, {100 * pb:.1f} % [{100 * lb:.1f}, "
             f"{100 * hb:.1f}]", band=Band(0.0, BEYOND_MAX, f"≤ {100 * BEYOND_MAX:g} %")),
        Part(f"share inside the window minus beyond ({near[0]} of {near[1]} inside)",
             Quantity(dd, dl, dh, "", "Newcombe's interval"), f"{dd:+.3f} [{dl:+.3f}, {dh:+.3f}]",
             band=Band(1e-12, 1.0, "above 0"))],
        text=("not ergodic at " + "; ".join(where) + " Hz") if where else "every diffusing point ergodic")


@measure("dissipation.cuts")
def cuts(claim: Claim, ctx) -> Measured:
    t = ctx["tables"].get(f"{MAP}_cuts")
    if t is None or t.empty:
        return Measured(missing="no cut compared (the committed Fig. 2 tables or the map lines)")
    parts = []
    for name, (label, _a) in CUTS.items():
        rows = t[t["cut"] == name]
        if rows.empty:
            continue
        ok = rows["agree"].dropna()
        share = float(ok.mean()) if len(ok) else math.nan
        off = rows["f"][rows["agree"] == 0].tolist()
        parts.append(Part(label, Quantity(share),
                          f"{int(ok.sum())} of {len(ok)} shared frequencies agree"
                          + (f" (not: {', '.join(f'{x:g}' for x in off)} Hz)" if off else "")
                          + (f"; {int(rows['agree'].isna().sum())} not compared (an estimator "
                             "failed)" if rows["agree"].isna().any() else ""),
                          band=Band(CUT_SHARE, 1.0, f"≥ {100 * CUT_SHARE:g} % agree")))
    return Measured(parts) if parts else Measured(missing="no cut compared")


CLAIMS = [
    Claim("The flat-floor 1/1 orbit's loss of stability Γ'(α) predicts the onset of diffusion "
          "from rest across dissipation", onset_threshold, MAP,
          Band(-math.inf, math.inf, "rule: the onset within ± 2.5 Hz of f(Γ') on ≥ 75 % of "
               "the α lines, and moving with f(Γ') (Spearman ρ > 0, permutation p ≤ 0.05)"),
          options={"threshold": "gamma_prime"}),
    Claim("The flat-floor 1/1 orbit's existence threshold Γ₁(α) predicts the onset of "
          "diffusion from rest across dissipation", onset_threshold, MAP,
          Band(-math.inf, math.inf, "rule: the onset within ± 2.5 Hz of f(Γ₁) on ≥ 75 % of "
               "the α lines, and moving with f(Γ₁) (Spearman ρ > 0, permutation p ≤ 0.05)"),
          options={"threshold": "gamma_1"}),
    Claim("The first maximum above the onset (the VHO maximum at α = 0.7) moves with "
          "dissipation", first_maximum, MAP,
          Band(-math.inf, math.inf, "rule: permutation p ≤ 0.05 of ρ(α, its f); at α = 0.7 "
               "at 60 ± 2 Hz")),
    Claim("The spiral's loops (k_max = 2, 3) move with dissipation", loops, LOCKING,
          Band(-math.inf, math.inf, "rule: permutation p ≤ 0.05 of ρ(α, f where k_max first "
               "reaches n)")),
    Claim("Ergodicity breaks only next to the onset of diffusion, at every dissipation",
          ergodicity, MAP,
          Band(-math.inf, math.inf, "rule: beyond onset + 4 Hz ≤ 5 % of the diffusing points "
               "not ergodic (Wilson), and more inside the window than beyond (Newcombe)")),
    Claim("Cuts of the maps reproduce the committed Fig. 2 curves (α = 0.7; Mátyás & Klages' "
          "α = 0.5, R = 25)", cuts, MAP,
          Band(-math.inf, math.inf, "rule: D within the combined CIs at ≥ 95 % of the shared "
               "frequencies, resolved zeros at their scene's resolution")),
]


def cut_line(tables, name: str) -> pd.DataFrame | None:
    """The map line a cut compares (Fig. 2's α = 0.7 line of the map, or Mátyás and Klages'
    α = 0.5 line of the R = 25 map), or None."""
    scene = MAP if name == "figure2" else R25
    return cut(tables.get(f"{scene}_diffusion"), "alpha", CUTS[name][1])
