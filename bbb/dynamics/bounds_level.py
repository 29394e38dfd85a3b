"""The paper floor's gap and its certificates (Eqs. 2-4), for the collision search of
:mod:`bbb.dynamics.search`: the first time τ (s) at which a particle in flight meets the
vibrating arcs, never missing one.

The gap G(τ) = y_particle − y_surface along a flight is only declared positive on an
interval when a rigorous lower bound (chord minus curvature bound, Taylor bound, or
monotone-depth bound) is positive there; a root is refined by bisection to ``tol_t``.
``R`` is the floor's shape (bbb.dynamics.floors: the arc's radius, or a shape's record),
whose certificates the bounds are built from.
The conveyor's are :mod:`bbb.dynamics.bounds_conveyor`'s: different certificates.
"""

from __future__ import annotations

import math

from numba import njit

from ..surface import floor_a
from .floors import concavity, curvature_max, depth, depth_min, slope


@njit(cache=True, inline="always")
def gap(tau, y, vy, s, dj, vx, g, A, w, R, half_s):
    # Eq. (2) against the floor of Sec. 2: G and dG/dτ at flight time τ in the cell dj refers to
    dd = min(max(dj + vx * tau, -half_s), half_s)
    ph = w * (s + tau)
    G = y + vy * tau - 0.5 * g * tau * tau + A * math.sin(ph) + depth(R, dd)
    G1 = vy - g * tau + A * w * math.cos(ph)
    if vx != 0.0:
        G1 += slope(R, dd) * vx
    return G, G1


@njit(cache=True, inline="always")
def curvature_bound(da, db, vx, g, A, w, R):
    # upper bound of G'' = -g + Aw² sin + vx² c''(d) on a sub-interval of one cell
    m = -g + A * w * w
    if vx != 0.0:
        m += vx * vx * curvature_max(R, da, db)
    return m


@njit(cache=True, inline="always")
def pull_bound(vx, g, A, w, R):
    # K with G'' ≥ −K in a cell: g + Aw² on a floor never concave (c'' ≥ 0), more where
    # the shape curves the other way (c'' ≥ −κ)
    k = g + A * w * w
    kappa = concavity(R)
    if kappa != 0.0:
        k += vx * vx * kappa
    return k


@njit(cache=True)
def lower_bound(h, Ga, G1a, Gb, da, db, vx, g, A, w, R):
    """Rigorous lower bound of G on [a, a+h] inside one cell (no cusp crossed)."""
    # chord minus curvature: G ≥ min(Ga, Gb) - M⁺h²/8
    M = curvature_bound(da, db, vx, g, A, w, R)
    lb = min(Ga, Gb) - max(M, 0.0) * h * h * 0.125
    # Taylor from a with G'' ≥ −K: a concave quadratic, minimal at the ends
    q = Ga + G1a * h - 0.5 * pull_bound(vx, g, A, w, R) * h * h
    lb = max(lb, min(Ga, q))
    # depth bounded below by its minimum over [da, db]; the rest has bounded curvature.
    # Handles the vertical cusps of R = S/2 and a sawtooth's peak, where the curvature bound
    # is infinite.
    if vx != 0.0:
        ca = depth(R, da)
        cb = depth(R, db)
        cmin = depth_min(R, da, db, ca, cb)
        mf = max(-g + A * w * w, 0.0)
        lb = max(lb, min(Ga - ca, Gb - cb) - mf * h * h * 0.125 + cmin)
    return lb


@njit(cache=True)
def start_step(h_max, G1, vx, s, g, A, w, R, lifting):
    """A flight step σ > 0 on which G > 0, for a flight that starts on the surface (G(0) = 0).

    Returns 0 when no positive step is certified (the particle does not separate)."""
    sigma = 0.0
    if G1 > 0.0:
        # G ≥ G1 σ - K σ²/2 > 0 for σ < 2 G1/K (pull_bound); take half of that
        sigma = G1 / pull_bound(vx, g, A, w, R)
    if vx == 0.0 and G1 >= 0.0:
        # vertical flight over a fixed point: Taylor to 4th order with |y_f''''| ≤ Aw⁴
        G2 = -g - floor_a(s, A, w)
        if lifting:
            # lift-off is timed where G'' ≥ 0; drop rounding below it (sinks ≤ ε T²/2 with ε
            # the rounding of G'', ≲ 1e-14 mm: docs/physics.md, "Why the lift-off step may clamp")
            G2 = max(G2, 0.0)
        if G2 >= 0.0:
            sigma = quartic_step(sigma, G2, -A * w * w * w * math.cos(w * s), A * w * w * w * w,
                                 h_max)
    return min(sigma, h_max)


@njit(cache=True, inline="always")
def quartic_step(sigma, G2, G3, K, h_max):
    # a flight from G = G' = 0 with G'' = G2 >= 0, G''' = G3, |G''''| <= K: G > 0 on (0, t] where
    # G2/2 + G3 t/6 - K t^2/24 > 0 (Taylor to 4th order); the longest h_max/2^k so, if > sigma
    tr = h_max
    for _ in range(80):
        if 0.5 * G2 + G3 * tr / 6.0 - K * tr * tr / 24.0 > 0.0:
            return max(sigma, tr)
        tr *= 0.5
    return sigma
