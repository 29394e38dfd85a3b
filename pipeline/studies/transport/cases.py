"""Synthetic conveyor tables with known answers, and each transport claim's synthetic cases
(:class:`~pipeline.claims.claim.Case`), named by the claim records of :mod:`.claims`.

A line's diffusion table has v(f) with a standard error of 0.1 mm/s (95 % CI ± 0.196), a
steady, diffusive drift and D about the drift; the contact and counters tables of the
transport_reversal lines put the known boundary (airborne share, lift-offs per period) at the
first grid frequency above Γ_v = 1."""

from __future__ import annotations

import numpy as np
import pandas as pd

from bbb.analysis.transport import SYMMETRY

from ...claims.claim import Case
from .lines import CONVEYORS, GEOMETRIES, HOPPING, SLIDING

__all__ = ["F", "vtable"]

F = np.arange(40.0, 100.5, 2.0)
_Z = 1.96


def vtable(v, D=None, se: float = 0.1, mirror: bool = False) -> pd.DataFrame:
    """A line's diffusion table over F: v(f) (callable or array, mm/s), D about the drift
    (default 10 + f/10 mm²/s, monotonic)."""
    v = np.asarray(v(F) if callable(v) else v, dtype=float)
    D = np.asarray(D(F) if callable(D) else (10.0 + F / 10.0 if D is None else D), dtype=float)
    return pd.DataFrame({"f": F, "v": v, "v_lo": v - _Z * se, "v_hi": v + _Z * se,
                         "D_drift": D, "D_drift_lo": 0.97 * D, "D_drift_hi": 1.03 * D,
                         "steady": True, "diffusive": True,
                         "v_by": SYMMETRY if mirror else "particles"})


def _lines(**tables) -> dict:
    return {"tables": tables}


def _conveyors(v, D=None) -> dict:
    return _lines(**{sc: vtable(v, D) for sc in CONVEYORS})


def _bump(f):
    return 5.0 + 4.0 * np.exp(-0.5 * ((f - 70.0) / 3.0) ** 2)


def _rising(f):
    return 0.1 * f


def no_current_cases() -> list[Case]:
    """T1's rule (mirror pairs read as 'agrees': the flaw T1b mends)."""
    sc = HOPPING[0]
    return [Case("mirror pairs", _lines(**{sc: vtable(np.zeros(F.size), mirror=True)}), "agrees"),
            Case("independent particles, no current", _lines(**{sc: vtable(np.zeros(F.size))}),
                 "agrees"),
            Case("independent particles, a current", _lines(**{sc: vtable(_rising)}), "disagrees",
                 perturbs="independent particles, no current")]


def no_current_construction_cases() -> list[Case]:
    """T1b's rule."""
    sc = HOPPING[0]
    return [Case("mirror pairs", _lines(**{sc: vtable(np.zeros(F.size), mirror=True)}),
                 "by construction"),
            Case("independent particles, no current", _lines(**{sc: vtable(np.zeros(F.size))}),
                 "agrees", perturbs="mirror pairs"),
            Case("independent particles, a current", _lines(**{sc: vtable(_rising)}), "disagrees",
                 perturbs="mirror pairs")]


def v_extrema_cases() -> list[Case]:
    """T2's rule: an extremum of v(f) on every conveyor floor."""
    return [Case("a maximum of v on every floor", _conveyors(_bump), "agrees"),
            Case("v rising on every floor", _conveyors(_rising), "disagrees",
                 perturbs="a maximum of v on every floor")]


def _reversing(f):
    return np.where(f < 70.0, 2.0, -2.0)


def reversal_f_cases() -> list[Case]:
    """T3's rule as registered: along f on the four conveyor floors of scene transport."""
    return [Case("v changes sign at 70 Hz", _conveyors(_reversing), "agrees"),
            Case("v positive everywhere", _conveyors(lambda f: 2.0 + 0 * f), "disagrees",
                 perturbs="v changes sign at 70 Hz"),
            Case("a sign change along ψ only", _psi_only(), "disagrees",
                 perturbs="v changes sign at 70 Hz")]


def _psi_only() -> dict:
    """Every conveyor line positive along f but the tilted lines at ψ = 90° negative: sign
    changes along ψ only (T3b's scope, not T3's)."""
    return _lines(**{sc: vtable(lambda f, s=(-2.0 if g["tilt"] and g["throw"] == 90 else 2.0):
                                s + 0 * f) for sc, g in GEOMETRIES.items()})


def reversal_cases() -> list[Case]:
    """T3b's rule: along f or ψ on every conveyor floor."""
    every = {sc: vtable(_reversing) for sc in GEOMETRIES}
    none = {sc: vtable(lambda f: 2.0 + 0 * f) for sc in GEOMETRIES}
    return [Case("v changes sign along f", _lines(**every), "agrees"),
            Case("v positive everywhere", _lines(**none), "disagrees",
                 perturbs="v changes sign along f"),
            Case("a sign change along ψ only", _psi_only(), "agrees",
                 perturbs="v positive everywhere")]


def d_extrema_cases() -> list[Case]:
    """T4's rule: a maximum and a minimum of D about the drift on every conveyor floor."""
    def wavy(f):
        return 20.0 + 8.0 * np.sin((f - 40.0) / 60.0 * 3 * np.pi)
    return [Case("D with a maximum and a minimum", _conveyors(_bump, wavy), "agrees"),
            Case("D rising", _conveyors(_bump), "disagrees",
                 perturbs="D with a maximum and a minimum")]


def sliding_cases() -> list[Case]:
    """T5's rule: below lift-off no current under stick, one under Coulomb friction."""
    (stick, _, _), (coul, _, _) = SLIDING
    ok = _lines(**{stick: vtable(np.zeros(F.size)), coul: vtable(lambda f: 0.05 * f)})
    both = _lines(**{stick: vtable(lambda f: 0.05 * f), coul: vtable(np.zeros(F.size))})
    return [Case("stick still, Coulomb carries", ok, "agrees"),
            Case("stick carries, Coulomb still", both, "disagrees",
                 perturbs="stick still, Coulomb carries")]


def _reversal(per_period=None, air=None, drop: str = "") -> dict:
    """Contact and counters tables of every transport_reversal line: airborne share and
    lift-offs per period switched on at the first f above Γ_v = 1 (or as given)."""
    from .reversal import REVERSAL_LINES, throw_number_frequency

    contact, counters = {}, {}
    for sc, g in REVERSAL_LINES.items():
        if sc == drop:
            continue
        on = F > throw_number_frequency(g["tilt"], g["throw"])
        a = air(F, on) if air else np.where(on, 0.4, 0.0)
        held = 1.0 - a
        contact[sc] = pd.DataFrame({"f": F, "held_frac": held, "held_frac_lo": held - 0.01,
                                    "held_frac_hi": held + 0.01, "slide_frac": 0.0,
                                    "slide_frac_lo": 0.0, "slide_frac_hi": 0.0})
        per = per_period(F, on) if per_period else np.where(on, 1.0, 0.0)
        counters[sc] = pd.DataFrame({"f": F, "liftoffs_per_s": per * F,
                                     "collisions_per_s": 1300.0})
    return {"tables": {}, "contact": contact, "counters": counters}


def _chatter(f, on):
    return np.full(f.shape, 0.15)  # in the air 15 % of the run at every f: micro-bounces


def hopping_cases() -> list[Case]:
    """T6's rule: the boundary by the airborne share (chatter read as hopping: the flaw T6b
    mends)."""
    return [Case("flight from Γ_v = 1 on", _reversal(), "agrees"),
            Case("chatter at every f", _reversal(air=_chatter), "disagrees",
                 perturbs="flight from Γ_v = 1 on")]


def liftoff_cases() -> list[Case]:
    """T6b's rule: the boundary by lift-offs per period."""
    base = "one lift-off per period from Γ_v = 1 on"
    return [Case(base, _reversal(), "agrees"),
            Case("chatter: no lift-off, in the air at every f",
                 _reversal(per_period=lambda f, on: 0 * f, air=_chatter), "disagrees",
                 perturbs=base),
            Case("lift-offs 10 Hz late", _reversal(
                per_period=lambda f, on: np.where(np.roll(on, 5) & on, 1.0, 0.0)), "disagrees",
                 perturbs=base),
            Case("threshold 5 lift-offs per period", _reversal(), "disagrees", perturbs=base,
                 options={"threshold": 5.0}),
            Case("a line without counters", _reversal(drop="transport_reversal_p60_stick"),
                 "not measured", perturbs=base)]
