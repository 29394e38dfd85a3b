"""Where hopping can begin: the lowest vibration frequency at which a particle at rest
somewhere on the floor feels the floor let go.

A particle carried at rest on an arc at angle θ from its top (normal n = (sin θ, cos θ)) is
pressed on by n·(G + a ω² sin ωs) per unit mass, with gravity G = g (sin φ, cos φ) in the
floor's coordinates (tilt φ) and the floor's acceleration amplitude a = A (−sin δ, cos δ),
δ = ψ − 90° (throw ψ; the conventions of :mod:`bbb.dynamics.bounds`).  So the load is
g cos(θ − φ) + A ω² cos(θ + δ) sin ωs, and it turns negative at some phase once
ω² > g cos(θ − φ) / (A |cos(θ + δ)|).  Its θ-derivative has the fixed sign of sin(δ + φ), so
over the arc's angles [−θc, θc] (sin θc = S / 2R) the lowest threshold sits at an edge: at a
cusp.  Below the frequency returned no particle at rest anywhere on the floor lifts off --
under ``contact = "stick"`` it never moves again, and only sliding (``slide``, ``coulomb``)
can transport it.  Units: mm, s, Hz.
"""

from __future__ import annotations

import math

from ..params import Params

__all__ = ["liftoff_frequency"]


def liftoff_frequency(p: Params) -> float:
    """The lowest f (Hz) at which a particle at rest somewhere on p's floor can lift off (at
    p's g, A, R, S, tilt, throw; p.f is ignored); inf if none ever can (A = 0)."""
    phi = math.radians(p.tilt)
    dev = math.radians(p.throw - 90.0)
    th_c = 0.0 if math.isinf(p.R) else math.asin(min(1.0, p.S / (2.0 * p.R)))
    best = math.inf
    for th in (-th_c, th_c):
        press = p.g * math.cos(th - phi)  # gravity's share along the normal (mm/s²)
        swing = p.A * abs(math.cos(th + dev))  # the floor's, per ω² (mm)
        if swing > 0.0:
            best = min(best, math.sqrt(press / swing) / (2.0 * math.pi))
    return best
