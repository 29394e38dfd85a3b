"""Claim 2 re-judged from the basins: B1, registered before any D_mix was computed.

The rule (B1, supersedes 2 -- claim 2's verdict stays as it was judged):

  For each stated ensemble -- the scene's grids of initial conditions, ``dropped`` (floor phase
  × drop height 0–2 mm) and ``launched`` (floor phase × launch speed 0–200 mm/s), both at 0.5
  mm from an arc's centre -- and each run length T = 5, 10, 20 s, a part: the frequency f_max
  at which D_mix(f, T) = Σ_c share_c(T) · D_c is largest along the scene's 17 frequencies
  46–62 Hz, with the percentile interval of that location over bootstrap resamples (the
  particles of each frequency resampled independently; :mod:`.tables`).  Band: 54 ± 2 Hz, the
  paper's 'around f = 54' and the width claim 2 was judged with.  A part whose D_mix is not
  measured at some frequency is 'not measured' (its status says where) and left out of the
  combination, named in the note (the rule asks whether some ensemble and T gives a maximum);
  a maximum at the scene's edge (46 or 62 Hz) is no maximum near 54 and lies outside the band.

  Combined by the generic rule: every part agrees -- agrees; some agree -- partly (the parts
  that agree name an ensemble and run length whose D_mix has a maximum within 54 ± 2 Hz:
  what the issue asks for); none -- disagrees (no mixture of these attractors, weighted by
  the shares any of these ensembles reaches at any of these T, gives one: the tested
  statement).

D_c is measured, not assumed: the mean dx²/(2Δt) over the run's second half of the particles
holding class c (stuck, locked 1/1, locked period-k, irregular) through it.
"""

from __future__ import annotations

import math

import pandas as pd

from ...claims.claim import Band, Case, Claim, Measured, Part, Quantity, measure

__all__ = ["SCENE", "CLAIMS", "context", "peak_cases", "peak_table"]

SCENE = "basins"
F0, HALF = 54.0, 2.0
_CI = "bootstrap over particles, location of the maximum"


@measure("basins.dmix_peak")
def dmix_peak(claim: Claim, ctx) -> Measured:
    """One part per (family, T) of the peak table: where D_mix is largest along f."""
    t = ctx["tables"].get("peak")
    if t is None or t.empty:
        return Measured(missing="no basins peak table (D_mix along f at T = 5, 10, 20 s)")
    parts, blank = [], []
    for _, r in t.sort_values(["family", "T"], kind="stable").iterrows():
        label = f"{r['family']}, T = {r['T']:g} s"
        v, lo, hi = (float(r.get(c, math.nan)) for c in ("f_max", "f_max_lo", "f_max_hi"))
        if math.isnan(v):
            blank.append(f"{label}: {r.get('peak_status') or 'blank'}")
            parts.append(Part(label, Quantity(math.nan), "not measured"))
            continue
        q = Quantity(v, lo, hi, "Hz", _CI) if hi > lo else Quantity(v, unit="Hz")
        edge = " (at the scene's edge)" if bool(r.get("at_edge", False)) else ""
        parts.append(Part(label, q, f"max of D_mix at {v:g} Hz{edge} [{lo:g}, {hi:g}], "
                                     f"D_mix = {float(r['D_max']):.3g} mm²/s"))
    note = ("Not measured: " + "; ".join(blank) + ".") if blank else ""
    return Measured(parts, note=note)


_REG = "2026-11-28 d5e357d"
CLAIMS = [
    Claim("Local maximum of D(f) around f = 54, re-judged as a mixture of the attractors: "
          "some stated ensemble and run length T whose D_mix(f, T) = Σ share(T)·D of its "
          "states is largest within 54 ± 2 Hz", dmix_peak, SCENE,
          Band(F0 - HALF, F0 + HALF, "'around f = 54' as claim 2 was judged: ± 2 Hz, the "
               "spacing of the landmarks the paper names (58, 60, 62 Hz)"),
          f0=F0, id="B1", registered=_REG, supersedes="2",
          scope={"scenes": [SCENE], "families": ["dropped", "launched"],
                 "frequencies": "46-62 Hz, 17 frequencies", "T": [5.0, 10.0, 20.0]},
          cases=lambda: peak_cases()),
]


def context(tables, stores=None) -> dict:
    return {"tables": {"peak": tables.get("peak")}}


def peak_table(at: dict[tuple[str, float], float | None], width: float = 1.0) -> pd.DataFrame:
    """A synthetic peak table: {(family, T): f_max (None: not measured)}, intervals ± width."""
    rows = []
    for (fam, T), f in at.items():
        blank = f is None
        rows.append({"family": fam, "T": T, "f_max": math.nan if blank else f,
                     "f_max_lo": math.nan if blank else f - width,
                     "f_max_hi": math.nan if blank else f + width,
                     "D_max": math.nan if blank else 100.0, "at_edge": f in (46.0, 62.0),
                     "peak_status": "D_mix not measured at 50 Hz" if blank else ""})
    return pd.DataFrame(rows)


def _ctx(t) -> dict:
    return {"tables": {"peak": t}}


def peak_cases() -> list[Case]:
    keys = [(fam, T) for fam in ("dropped", "launched") for T in (5.0, 10.0, 20.0)]
    base = "every ensemble peaks at 54 Hz"
    return [
        Case(base, _ctx(peak_table({k: 54.0 for k in keys})), "agrees"),
        Case("every ensemble peaks at the scene's edge, 46 Hz",
             _ctx(peak_table({k: 46.0 for k in keys})), "disagrees", perturbs=base),
        Case("one ensemble (dropped, 5 s) peaks at 54 Hz, the others at 46 Hz",
             _ctx(peak_table({k: 54.0 if k == ("dropped", 5.0) else 46.0 for k in keys})),
             "partly", perturbs=base),
        Case("the peak at 55.5 Hz, its interval beyond 56",
             _ctx(peak_table({k: 55.5 for k in keys})), "agrees within the CI", perturbs=base),
        # the rule asks for some ensemble and T: a part not measured is named, not counted
        Case("launched, 20 s not measured, the others at 54 Hz",
             _ctx(peak_table({k: None if k == ("launched", 20.0) else 54.0 for k in keys})),
             "agrees"),
        Case("launched, 20 s not measured, the others at 46 Hz",
             _ctx(peak_table({k: None if k == ("launched", 20.0) else 46.0 for k in keys})),
             "disagrees", perturbs="launched, 20 s not measured, the others at 54 Hz"),
        Case("no table", _ctx(None), "not measured", perturbs=base),
    ]
