"""The mechanisms claims as data (judged by :mod:`pipeline.claims` from the mechanisms table).

Rules, fixed before the data (their thresholds are definitions, not fits):

memory share   s = (D_∞ − D_0) / D_∞ at f0.  "Made by memory" means most of D is memory:
               s ≥ 0.5.  CI: conservative, from the ends of the two CIs
               (1 − D_0_hi / D_inf_lo, 1 − D_0_lo / D_inf_hi), not a bootstrap.  A D_∞ whose CI
               reaches 0 (nothing diffuses) is "not measured".  The row also says whether D_0
               itself has the extremum at f0 (D_0(f0) beyond the CIs of both grid neighbours,
               same side): then the extremum is already in the jump statistics.
λ ratio        r = mean λ over the scene's f ≥ 66 Hz (the spiral regime) / λ(60 Hz) (the VHO).
               Larger means r > 1 with its CI (ends: mean of the lows / λ_hi(60), mean of the
               highs / λ_lo(60)).
"""

from __future__ import annotations

import math

import pandas as pd

from ...claim_measures import row_at
from ...claims import Band, Claim, Measured, Part, Quantity, evaluate, markdown_table, measure

__all__ = ["CLAIMS", "EXTREMA", "report_lines"]

#: the paper's extrema of D(f) (Fig. 2) and their kind
EXTREMA = ((54.0, "min"), (58.0, "min"), (60.0, "max"), (62.0, "min"), (80.0, "max"))
SPIRAL_FROM = 66.0  # Hz: the spiral regime (klages2004 claims)
VHO = 60.0


def _d0_extremum(t: pd.DataFrame, f0: float) -> str:
    """Whether D_0 has a local extremum at f0 on the scene's grid, beyond the CIs."""
    t = t.sort_values("f").reset_index(drop=True)
    i = t.index[(t["f"] - f0).abs() < 1e-6]
    if not len(i) or i[0] == 0 or i[0] == len(t) - 1:
        return "D_0 extremum: no neighbours"
    r, a, b = (t.loc[j] for j in (i[0], i[0] - 1, i[0] + 1))
    if r["D_0_lo"] > max(a["D_0_hi"], b["D_0_hi"]):
        kind = "max"
    elif r["D_0_hi"] < min(a["D_0_lo"], b["D_0_lo"]):
        kind = "min"
    else:
        kind = "none"
    return (f"D_0 = {a['D_0']:.3g}, {r['D_0']:.3g}, {b['D_0']:.3g} mm²/s at "
            f"{a['f']:g}, {r['f']:g}, {b['f']:g} Hz: D_0 {'has a ' + kind if kind != 'none' else 'has no'}"
            " local extremum there")


@measure("memory_share")
def memory_share(claim: Claim, ctx) -> Measured:
    t = ctx["tables"].get(claim.scene)
    if t is None or "D_inf" not in t:
        return Measured(missing="no mechanisms table with jumps")
    r = row_at(t, claim.f0)
    if r is None:
        return Measured(missing=f"f = {claim.f0:g} not in the mechanisms table")
    d0, lo0, hi0 = r["D_0"], r["D_0_lo"], r["D_0_hi"]
    di, loi, hii = r["D_inf"], r["D_inf_lo"], r["D_inf_hi"]
    conv = "" if r["converged"] else "; the expansion did not converge (D_∞ = D_max_lag)"
    if not loi > 0:
        return Measured(missing=f"D_∞ = {di:.3g} [{loi:.3g}, {hii:.3g}] mm²/s reaches 0: nothing "
                        f"diffuses; {_d0_extremum(t, claim.f0)}{conv}")
    q = Quantity(1 - d0 / di, 1 - hi0 / loi, 1 - lo0 / hii, "", "ends of the D_0 and D_∞ CIs")
    txt = (f"(D_∞ − D_0)/D_∞ = {q.text('.3f')}; D_0 = {d0:.3g}, D_∞ = {di:.4g} mm²/s, "
           f"memory over K = {int(r['lag'])} periods; {_d0_extremum(t, claim.f0)}{conv}")
    return Measured([Part(f"f = {r['f']:g}", q, txt)])


@measure("lyapunov_ratio")
def lyapunov_ratio(claim: Claim, ctx) -> Measured:
    t = ctx["tables"].get(claim.scene)
    if t is None or "lam" not in t:
        return Measured(missing="no mechanisms table with lyapunov")
    vho = row_at(t, VHO)
    sp = t[t["f"] >= SPIRAL_FROM].dropna(subset=["lam"])
    if vho is None or sp.empty or not vho["lam_lo"] > 0:
        return Measured(missing=f"λ at {VHO:g} Hz or at f ≥ {SPIRAL_FROM:g} Hz not measured")
    q = Quantity(sp["lam"].mean() / vho["lam"], sp["lam_lo"].mean() / vho["lam_hi"],
                 sp["lam_hi"].mean() / vho["lam_lo"], "", "ends of the λ CIs")
    txt = (f"mean λ(f ≥ {SPIRAL_FROM:g}, {len(sp)} f) = {sp['lam'].mean():.3g} 1/s, λ({VHO:g}) = "
           f"{vho['lam']:.3g} [{vho['lam_lo']:.3g}, {vho['lam_hi']:.3g}] 1/s; ratio {q.text('.3f')}")
    return Measured([Part("λ ratio", q, txt)])


_SHARE = Band(0.5, math.inf, "rule: made by memory when D_∞ − D_0 is at least half of D_∞ "
              "(module docstring of pipeline.studies.mechanisms.claims)")
CLAIMS = [
    Claim(f"The {kind}imum of D at {f0:g} Hz is made by memory (D_∞ − D_0), not by the "
          "random-walk term D_0", "memory_share", "mechanisms", _SHARE, f0=f0)
    for f0, kind in EXTREMA
] + [
    Claim(f"λ is larger in the spiral regime (f ≥ {SPIRAL_FROM:g} Hz) than at the VHO "
          f"({VHO:g} Hz)", "lyapunov_ratio", "mechanisms",
          Band(1.0, math.inf, "rule: ratio of the mean λ over f ≥ 66 Hz to λ(60 Hz) above 1"),
          f0=VHO),
]


def report_lines(tables) -> list[str]:
    """The REPORT.md section: the claim rows judged from ``tables["mechanisms"]``."""
    rows = evaluate(CLAIMS, {"tables": {"mechanisms": tables.get("mechanisms")}})
    L = ["", "## Mechanisms: memory and chaos at the extrema (scene mechanisms)", "",
         "Verdicts computed from the mechanisms store (Green–Kubo expansion per floor period, "
         "Lyapunov exponent from two trajectories; pipeline/studies/mechanisms/claims.py "
         "states the rules).", ""]
    return L + markdown_table(rows, prefix="M")
