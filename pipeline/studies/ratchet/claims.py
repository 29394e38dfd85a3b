"""The ratchet claims as data, judged by :mod:`pipeline.claims.claim` from the map scene's
diffusion table (drift v with its bootstrap CI per (α, peak p, f); bbb.analysis.transport),
one line per (α, p).

Rules, fixed before the data (calibrated on synthetic maps with known answers in
:mod:`.cases`; the sign rules are :mod:`pipeline.claims.signs`):

significant v   v ≠ 0 at a point when |v| exceeds z_n standard errors (read off its CI side
                towards 0), z_n = Φ⁻¹(1 − α / (2 n)) Bonferroni over the n points of the curve,
                α = 0.05, and |v| > V_MIN = 1e-6 mm/s.
steady only     every rule uses the points whose drift is steady (the table's ``steady``
                column): an accelerating ensemble has a window mean, not a drift.
R1 current      on every line with off-centre teeth (p ≠ 0.5) at least one frequency with a
                significant v (Bonferroni over the line): the teeth break the mirror symmetry.
R2 centred      on the lines with centred teeth (p = 0.5, particles independent, so v is
                measured) no frequency with a significant v, Bonferroni over all their points
                together (family-wise false alarm ≤ 5 %).
R3 mirror       x → −x takes the floor p to the floor 1 − p, so v(1 − p) = −v(p): at every
                (α, p < 0.5, f) with both lines steady the sum v(p) + v(1 − p), its interval
                from the two CIs in quadrature (:func:`pipeline.claims.signs.sum_interval`:
                the lines' particles start from the same draws but run apart; treated as
                independent), is not significant, Bonferroni over all the sums of the claim.
                A line whose mirror partner is missing is a part not measured.
R4 reversals    along f on the off-centre lines, a sign change between consecutive significant
                points (those between not significant) is a current reversal, located as the
                interval from the last significant f of one sign to the first of the other
                (:func:`pipeline.claims.signs.reversal_intervals`); at least one exists and
                each is located within ± one frequency step (its half-width ≤ F_STEP): the
                sign changes between neighbouring grid frequencies or with one unresolved
                frequency between.  None anywhere: 'disagrees'.
"""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np
import pandas as pd

from ...claims.claim import Band, Claim, Measured, Part, Quantity, measure
from ...claims.signs import (
    reversal_intervals,
    significant_signs,
    steady_rows,
    sum_interval,
)
from .cases import centred_cases, current_cases, mirror_cases, reversal_cases

__all__ = ["SCENE", "TABLE", "CENTRE", "F_STEP", "PEAKS", "ALPHAS", "line_label", "map_lines",
           "line_reversals", "mirror_sums", "CLAIMS", "context"]

SCENE = "ratchet"
#: the key of the map's diffusion table
TABLE = f"{SCENE}_diffusion"
#: the peak position of the symmetric teeth (fraction of S from the left valley)
CENTRE = 0.5
#: Hz: the scene's frequency step, the resolution of a reversal's location
F_STEP = 2.0
#: the scene's grid (scenes/ratchet.toml; tests/pipeline/studies/ratchet checks it)
PEAKS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8)
ALPHAS = (0.5, 0.7, 0.9)
_Z95 = NormalDist().inv_cdf(0.975)


def line_label(alpha: float, peak: float) -> str:
    return f"α = {alpha:g}, p = {peak:g}"


def _centred(p: float) -> bool:
    return math.isclose(p, CENTRE, abs_tol=1e-9)


def map_lines(t: pd.DataFrame | None) -> dict[tuple[float, float], pd.DataFrame]:
    """{(α, p): the line's steady rows, sorted by f} of the map's diffusion table (attrs
    ["unsteady"]: the f left out); {} without the transport columns."""
    if t is None or "v" not in t or not {"alpha", "peak"} <= set(t.columns):
        return {}
    out = {}
    for (a, p), g in t.groupby(["alpha", "peak"], sort=True):
        rows = steady_rows(g)
        if rows is not None:
            out[(float(a), float(p))] = rows
    return out


def _left_out(t: pd.DataFrame) -> str:
    u = t.attrs.get("unsteady", [])
    return f"; {len(u)} f left out, drift not steady ({', '.join(f'{x:g}' for x in u)} Hz)" if u else ""


def line_reversals(t: pd.DataFrame) -> tuple[list[tuple[float, float, int]], np.ndarray]:
    """(the sign changes along f as (f_a, f_b, sign after), the significant signs) of one
    line's steady rows (Bonferroni over the line)."""
    s = significant_signs(t["v"], t["v_lo"], t["v_hi"])
    return reversal_intervals(t["f"].to_numpy(float), s), s


def mirror_sums(lines: dict[tuple[float, float], pd.DataFrame]
                ) -> dict[tuple[float, float], pd.DataFrame | None]:
    """{(α, p < 0.5): rows (f, v_p, v_q, sum, sum_lo, sum_hi) at the f where both p and
    q = 1 − p are steady, None when the partner line is missing} for every off-centre line
    with p < 0.5 (and every p > 0.5 whose partner is missing, keyed by its own p)."""
    out: dict[tuple[float, float], pd.DataFrame | None] = {}
    for (a, p), t in lines.items():
        if _centred(p):
            continue
        q = round(1.0 - p, 9)
        partner = next((lines[k] for k in lines if k[0] == a and math.isclose(k[1], q,
                                                                               abs_tol=1e-9)), None)
        if p > CENTRE and partner is not None:
            continue  # counted from its partner p < 0.5
        if partner is None:
            out[(a, p)] = None
            continue
        m = t.merge(partner, on="f", suffixes=("_p", "_q"))
        s, lo, hi = sum_interval(m["v_p"], m["v_lo_p"], m["v_hi_p"], m["v_q"], m["v_lo_q"],
                                 m["v_hi_q"])
        out[(a, p)] = pd.DataFrame({"f": m["f"], "v_p": m["v_p"], "v_q": m["v_q"], "sum": s,
                                    "sum_lo": lo, "sum_hi": hi})
    return out


def _lines(ctx) -> dict[tuple[float, float], pd.DataFrame]:
    return map_lines(ctx["tables"].get(TABLE))


@measure("ratchet.current")
def current(claim: Claim, ctx) -> Measured:
    """One part per off-centre line: its number of frequencies with a significant v."""
    parts = []
    for (a, p), t in _lines(ctx).items():
        if _centred(p):
            continue
        s = significant_signs(t["v"], t["v_lo"], t["v_hi"])
        parts.append(Part(line_label(a, p), Quantity(float((s != 0).sum())),
                          f"{int((s > 0).sum())} f with v > 0, {int((s < 0).sum())} with v < 0 "
                          f"of {len(t)}; v from {t['v'].min():.3g} to {t['v'].max():.3g} mm/s"
                          + _left_out(t)))
    return Measured(parts) if parts else Measured(missing=f"no off-centre line in {TABLE}")


@measure("ratchet.centred")
def centred(claim: Claim, ctx) -> Measured:
    """One part per centred line: its number of frequencies with a significant v, Bonferroni
    over the points of every centred line together."""
    lines = {k: t for k, t in _lines(ctx).items() if _centred(k[1])}
    if not lines:
        return Measured(missing=f"no centred line (p = {CENTRE:g}) in {TABLE}")
    pooled = pd.concat(lines.values(), ignore_index=True)
    s = significant_signs(pooled["v"], pooled["v_lo"], pooled["v_hi"])
    parts, i = [], 0
    for (a, p), t in lines.items():
        si, i = s[i:i + len(t)], i + len(t)
        where = t["f"][si != 0].tolist()
        se = float(np.median((t["v_hi"] - t["v_lo"]) / (2 * _Z95)))
        parts.append(Part(line_label(a, p), Quantity(float(len(where))),
                          f"{len(where)} of {len(t)} f with a significant v "
                          f"({', '.join(f'{x:g}' for x in where) or 'none'}); max |v| = "
                          f"{float(np.abs(t['v']).max()):.3g} mm/s, median SE {se:.3g} mm/s"
                          + _left_out(t)))
    return Measured(parts, note=f"Bonferroni over all {len(pooled)} points of the centred lines.")


@measure("ratchet.mirror")
def mirror(claim: Claim, ctx) -> Measured:
    """One part per mirror pair (α, p, 1 − p): its number of f with a significant sum
    v(p) + v(1 − p), Bonferroni over every sum of the claim."""
    sums = mirror_sums(_lines(ctx))
    if not sums:
        return Measured(missing=f"no off-centre line in {TABLE}")
    have = [t for t in sums.values() if t is not None and len(t)]
    n = sum(len(t) for t in have)
    parts = []
    for (a, p), t in sums.items():
        label = f"α = {a:g}, p = {p:g} / {round(1 - p, 9):g}"
        if t is None or not len(t):
            parts.append(Part(label, Quantity(math.nan), "its mirror partner (p = "
                              f"{round(1 - p, 9):g}) has no steady point in the table"))
            continue
        s = significant_signs(t["sum"], t["sum_lo"], t["sum_hi"], alpha=0.05 * len(t) / n)
        where = t["f"][s != 0].tolist()
        k = int(np.argmax(np.abs(t["sum"])))
        parts.append(Part(label, Quantity(float(len(where))),
                          f"{len(where)} of {len(t)} f with a significant v(p) + v(1 − p) "
                          f"({', '.join(f'{x:g}' for x in where) or 'none'}); largest |sum| "
                          f"{abs(t['sum'].iloc[k]):.3g} mm/s at {t['f'].iloc[k]:g} Hz "
                          f"[{t['sum_lo'].iloc[k]:.3g}, {t['sum_hi'].iloc[k]:.3g}]"))
    return Measured(parts, note=f"Bonferroni over all {n} sums.")


@measure("ratchet.reversals")
def reversals(claim: Claim, ctx) -> Measured:
    """One part per current reversal along f on an off-centre line: the half-width of its
    interval (Hz); a single part 'not found' when no line has one."""
    lines = {k: t for k, t in _lines(ctx).items() if not _centred(k[1])}
    if not lines:
        return Measured(missing=f"no off-centre line in {TABLE}")
    parts, quiet = [], []
    for (a, p), t in lines.items():
        found, _ = line_reversals(t)
        if not found:
            quiet.append(line_label(a, p))
        for fa, fb, k in found:
            parts.append(Part(f"{line_label(a, p)}, {fa:g}–{fb:g} Hz",
                              Quantity(0.5 * (fb - fa), unit="Hz"),
                              f"v {'−' if k > 0 else '+'} → {'+' if k > 0 else '−'} between "
                              f"{fa:g} and {fb:g} Hz: at {0.5 * (fa + fb):g} ± "
                              f"{0.5 * (fb - fa):g} Hz"))
    note = (f"No significant sign change along f on {len(quiet)} lines "
            f"({'; '.join(quiet)}).") if quiet else ""
    if not parts:
        return Measured([Part("off-centre lines", Quantity(math.nan),
                              "no current reversal along f on any off-centre line", found=False)],
                        note=note)
    step = float(claim.options.get("f_step", F_STEP))
    band = Band(0.0, step, f"located within ± one frequency step ({step:g} Hz)", "Hz")
    return Measured([Part(x.label, x.q, x.text, band=band) for x in parts], note=note)


_REG = "2026-11-28 aa6f513"
_SCOPE = {"scenes": [SCENE], "families": ["rest"], "alpha": list(ALPHAS), "peak": list(PEAKS),
          "frequencies": "the scene's 40–100 Hz in steps of 2 Hz, steady points only"}
CLAIMS = [
    Claim("Off-centre sawtooth teeth break the mirror symmetry: a level floor vibrated "
          "vertically carries a current", current, SCENE,
          Band(1.0, math.inf, "rule: at least one frequency with a significant v (Bonferroni "
               "over the line, α = 0.05) on every line with the peak off centre"),
          id="R1", registered=_REG, scope=_SCOPE, all_parts=True, cases=current_cases),
    Claim("Centred teeth carry no current (control)", centred, SCENE,
          Band(0.0, 0.0, "rule: no frequency with a significant v on the p = 0.5 lines "
               "(independent particles; Bonferroni over all their points, α = 0.05)"),
          id="R2", registered=_REG, scope=_SCOPE, all_parts=True, cases=centred_cases),
    Claim("Mirror pairs carry opposite currents: v(1 − p) = −v(p) (x → −x takes the teeth p to "
          "1 − p)", mirror, SCENE,
          Band(0.0, 0.0, "rule: no (α, p, f) with a significant v(p) + v(1 − p) (CIs in "
               "quadrature; Bonferroni over all sums, α = 0.05); pairs 0.2/0.8, 0.3/0.7, "
               "0.4/0.6"),
          id="R3", registered=_REG, scope=_SCOPE, all_parts=True, cases=mirror_cases),
    Claim("The ratchet current reverses with the driving frequency, each reversal located "
          "within ± one frequency step", reversals, SCENE,
          Band(0.0, F_STEP, f"rule: at least one sign change of v along f between "
               f"significant points on an off-centre line, each located (last significant f "
               f"of one sign to the first of the other) to a half-width ≤ {F_STEP:g} Hz", "Hz"),
          options={"f_step": F_STEP}, id="R4", registered=_REG, scope=_SCOPE,
          cases=reversal_cases),
]


def context(tables, stores=None) -> dict:
    """The context the claims are judged in: the map's diffusion table."""
    return {"tables": {TABLE: tables.get(TABLE)}}
