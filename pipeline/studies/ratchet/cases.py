"""Synthetic ratchet maps with known answers, and each ratchet claim's synthetic cases
(:class:`~pipeline.claims.claim.Case`), named by the claim records of :mod:`.claims`.

A map's diffusion table holds the lines (α, p) for α = 0.7 and p = 0.3, 0.5, 0.7 over
40–100 Hz in steps of 2 Hz; v(p, f) = c(p) g(f) is set directly with a standard error of
0.1 mm/s (95 % CI ± 0.196 mm/s), every drift steady: c(p) = 10 (0.5 − p) mm/s is odd about
the centre (v(1 − p) = −v(p), v = 0 at p = 0.5) unless a case breaks it."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...claims.claim import Case

__all__ = ["F", "map_table", "current_cases", "centred_cases", "mirror_cases",
           "reversal_cases"]

F = np.arange(40.0, 100.5, 2.0)
_SE, _Z = 0.1, 1.959963984540054
_PEAKS = (0.3, 0.5, 0.7)


def _odd(p: float) -> float:
    return 10.0 * (0.5 - p)


def map_table(g=lambda f: np.ones_like(f), c=_odd, peaks=_PEAKS, alphas=(0.7,),
              se: float = _SE, steady=True) -> pd.DataFrame:
    """The map's diffusion table: v(p, f) = c(p) g(f) (mm/s) on every line (α, p), its 95 % CI
    ± 1.96 ``se``; ``steady``: True, or a callable f -> bool array."""
    rows = []
    for a in alphas:
        for p in peaks:
            v = c(p) * np.asarray(g(F), dtype=float)
            ok = np.ones(F.size, bool) if steady is True else np.asarray(steady(F), bool)
            rows.append(pd.DataFrame({"f": F, "peak": p, "alpha": a, "v": v,
                                      "v_lo": v - _Z * se, "v_hi": v + _Z * se, "steady": ok}))
    return pd.concat(rows, ignore_index=True)


def _ctx(t: pd.DataFrame | None) -> dict:
    return {"tables": {"ratchet_diffusion": t}}


def _reversing(f):
    """A sign change at 70 Hz, |v| ≥ 0.6 c at the neighbouring frequencies."""
    return np.tanh((70.0 - f) / 3.0)


def current_cases() -> list[Case]:
    """R1's rule: a significant v somewhere on every off-centre line."""
    base = "odd current on every off-centre line"
    return [
        Case(base, _ctx(map_table()), "agrees"),
        Case("no current anywhere", _ctx(map_table(c=lambda p: 0.0)), "disagrees", perturbs=base),
        Case("a current on p = 0.3 only", _ctx(map_table(c=lambda p: 2.0 if p < 0.5 else 0.0)),
             "partly", perturbs=base),
        # 3 SE at one frequency: below the Bonferroni threshold over 31 points (z = 3.2)
        Case("a 3-SE blip at one f", _ctx(map_table(g=lambda f: np.where(f == 70.0, 1.0, 0.0),
                                                    c=lambda p: 3 * _SE * np.sign(0.5 - p))),
             "disagrees", perturbs=base),
        Case("no table", _ctx(None), "not measured", perturbs=base),
    ]


def centred_cases() -> list[Case]:
    """R2's rule: no significant v on the centred lines, Bonferroni over all their points."""
    base = "no current at p = 0.5"
    return [
        Case(base, _ctx(map_table()), "agrees"),
        Case("a current at p = 0.5", _ctx(map_table(c=lambda p: 10.0 * (0.6 - p))), "disagrees",
             perturbs=base),
        Case("a 3-SE blip at p = 0.5, one f", _ctx(map_table(
            g=lambda f: np.where(f == 70.0, 1.0, 0.0), c=lambda p: 3 * _SE if p == 0.5 else 0.0)),
             "agrees", perturbs=""),
        Case("a 5-SE blip at p = 0.5, one f", _ctx(map_table(
            g=lambda f: np.where(f == 70.0, 1.0, 0.0), c=lambda p: 5 * _SE if p == 0.5 else 0.0)),
             "disagrees", perturbs=base),
        Case("no centred line", _ctx(map_table(peaks=(0.3, 0.7))), "not measured", perturbs=base),
    ]


def mirror_cases() -> list[Case]:
    """R3's rule: v(1 − p) = −v(p) within the CIs, Bonferroni over all sums."""
    base = "odd in p − 0.5"
    two = (0.2, 0.3, 0.5, 0.7, 0.8)
    return [
        Case(base, _ctx(map_table(peaks=two)), "agrees"),
        Case("even: v(1 − p) = v(p)", _ctx(map_table(c=lambda p: abs(10.0 * (0.5 - p)),
                                                     peaks=two)), "disagrees", perturbs=base),
        Case("the 0.3/0.7 pair off by 1 mm/s", _ctx(map_table(
            c=lambda p: _odd(p) + (1.0 if p == 0.7 else 0.0), peaks=two)), "partly",
             perturbs=base),
        # each side 0.25 mm/s off the mirror: the sum 0.25 over SE 0.14 is 1.8 SE, not significant
        Case("a sum of 1.8 SE", _ctx(map_table(c=lambda p: _odd(p) + 0.25 * (p == 0.7),
                                               peaks=two)), "agrees", perturbs=""),
        Case("the partner of p = 0.2 missing", _ctx(map_table(peaks=(0.2, 0.3, 0.5, 0.7))),
             "not measured", perturbs=base),
    ]


def reversal_cases() -> list[Case]:
    """R4's rule: a sign change of v along f on an off-centre line, located to ± one step."""
    base = "v reverses at 70 Hz"
    slow = "v reverses slowly: located to ± 8 Hz"
    return [
        Case(base, _ctx(map_table(g=_reversing)), "agrees"),
        Case("v one-signed", _ctx(map_table()), "disagrees", perturbs=base),
        # v = ± 0.023 (70 − f) mm/s: below 3.2 SE (not significant) over 64–76 Hz, so the
        # sign change is known between 62 and 78 Hz only (± 8 Hz)
        Case(slow, _ctx(map_table(g=lambda f: (70.0 - f) * 0.0115)), "disagrees",
             perturbs=base),
        Case("a step of 0.5 Hz asked", _ctx(map_table(g=_reversing)), "disagrees",
             perturbs=base, options={"f_step": 0.5}),
        # the reversal's neighbourhood unsteady: its points left out, the interval widens
        Case("66–74 Hz unsteady", _ctx(map_table(g=_reversing,
                                                 steady=lambda f: (f < 66) | (f > 74))),
             "disagrees", perturbs=base),
        Case("no table", _ctx(None), "not measured", perturbs=base),
    ]
