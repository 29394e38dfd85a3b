"""Shared helpers for the physics tests: how far off the surface a recorded collision may
lie, and a brute-force check of recorded flights."""

from __future__ import annotations

import math

import numpy as np

from bbb import Params
from bbb.surface import cell_of, floor_depth

ON_SURFACE_MM = 1e-9
#: At the vertical cusps of R = S/2 the height is only defined to sqrt(2 R δx) for a rounding
#: δx ~ 1e-14 mm of x (the cusp sits at x = cell·S + S/2): ~1.5e-7 mm.  The 1e9-collision soak
#: found collisions recorded there up to ~4e-9 mm off, at (within 1.1e-14 mm of) a cusp.
ON_CUSP_MM = 1e-7


def on_surface_tolerance(p: Params) -> float:
    """How far off the surface a collision may be recorded, mm (rounding of x, not physics)."""
    return ON_CUSP_MM if p.R == p.S / 2 else ON_SURFACE_MM


def gap_along_flights(p: Params, rows: np.ndarray, n_grid: int = 400,
                      per_period: int = 200) -> tuple[float, int]:
    """Brute force: the smallest gap (mm) between particle and surface on a fine time grid
    inside every recorded flight (consecutive rows of one particle), and the number of
    flights checked.  The grid has at least ``per_period`` points per floor period.  With
    lift-offs recorded (7 columns, ``event`` = 1) a flight starts at a collision or a lift-off
    and ends at a collision; the stretch from a stuck collision to its lift-off is carried, not
    flown.  Without them, flights that start stuck (velocity = floor velocity, vx = 0) are
    skipped: their lift-off time is not recorded.  A tilted or thrown floor (``tilt`` φ,
    ``throw`` ψ): gravity (−g sin φ, −g cos φ), arcs displaced by A(cos ψ, sin ψ)(−sin ωt)."""
    worst = math.inf
    checked = 0
    w = p.omega
    phi, psi = math.radians(p.tilt), math.radians(p.throw)
    conveyor = p.transport
    gx, gy = (p.g * math.sin(phi), p.g * math.cos(phi)) if conveyor else (0.0, p.g)
    ax, ay = (p.A * math.cos(psi), p.A * math.sin(psi)) if conveyor else (0.0, p.A)
    events = rows.shape[1] > 6
    for k in range(rows.shape[0] - 1):
        t0, x0, y0, vx, vy, ph = rows[k, :6]
        duration = rows[k + 1, 0] - t0
        vf = -ay * w * math.cos(2 * math.pi * ph)
        vfx = -ax * w * math.cos(2 * math.pi * ph)
        # a flight ends at a collision (0, or 4: one starting sliding contact) and never
        # starts at a contact start or stop (those begin sliding, checked by trajectory_check)
        if events and (rows[k + 1, 6] not in (0.0, 4.0) or rows[k, 6] in (4.0, 6.0)):
            continue
        if not events and abs(vx - vfx) < 1e-9 and abs(vy - vf) < 1e-9:
            continue
        n = max(n_grid, int(per_period * duration * p.f))
        tau = np.linspace(0.0, duration, n + 2)[1:-1]
        s = ph / p.f + tau
        _, dd = cell_of(x0 + vx * tau - 0.5 * gx * tau * tau + ax * np.sin(w * s), p.S)
        surface = -ay * np.sin(w * s) - floor_depth(p, dd)
        yp = y0 + vy * tau - 0.5 * gy * tau * tau
        if tau.size:
            worst = min(worst, float(np.min(yp - surface)))
        checked += 1
    return worst, checked
