"""The collision rule, Eqs. (5)-(6), one per floor: restitution in the arc's normal and
tangential frame relative to the floor's velocity, with the kick that ends a grazing
cascade where the arc falls away faster than the particle; and, on the conveyor, which
wall of a cusp a collision meets."""

from __future__ import annotations

import math

from numba import njit

from ..surface import floor_a, floor_v
from .bounds_conveyor import cusp_side, times_or_zero
from .floors import curvature, normal
from .floors.arc import arc_curvature, arc_normal, arc_slope


@njit(cache=True, inline="always")
def restitute(ux, uy, nx, ny, alpha, beta):
    # Eqs. (5)-(6): outgoing normal and tangential speeds of the velocity (ux, uy) relative to
    # the floor at the normal (nx, ny); |un|: a grazing contact rounded to un ≥ 0 still
    # reflects outward
    un = ux * nx + uy * ny
    ut = ux * ny - uy * nx
    return alpha * abs(un), beta * ut


@njit(cache=True)
def collide(vx, vy, d, s, g, A, w, R, alpha, beta, v_stick, allow_kick):
    """Eqs. (5)-(6): restitution in the floor's normal/tangential frame at offset d, relative
    to the floor velocity, on the floor shape R (bbb.dynamics.floors).  Returns (vx⁺, vy⁺,
    outgoing relative normal speed, kicked); a speed below ``v_stick`` means the particle
    sticks."""
    nx, ny = normal(R, d)
    vf = floor_v(s, A, w)
    un_out, ut_out = restitute(vx, vy - vf, nx, ny, alpha, beta)
    if un_out < v_stick:
        # A cascade of ever smaller bounces (which ends in sticking) needs the surface to
        # press on the particle: G'' ≤ 0 at G = G' = 0.  Where the arc falls away faster
        # than gravity and floor pull the particle down (vx² c'' > g + a_f, a fast
        # tangential touch), the particle flies off instead: leave with v_stick.
        # Never twice in a row: in a cusp (R = S/2) the neighbouring wall sends the particle
        # straight back, and repeated kicks would be an endless Zeno sequence.
        g2 = -g - floor_a(s, A, w) + (ut_out * ny) ** 2 * curvature(R, d)
        if allow_kick and g2 > 0.0 and abs(ut_out) >= v_stick:
            return v_stick * nx + ut_out * ny, vf + v_stick * ny - ut_out * nx, v_stick, True
    return un_out * nx + ut_out * ny, vf + un_out * ny - ut_out * nx, un_out, False


@njit(cache=True)
def collide_c(vx, vy, d, s, gx, gy, Ax, Ay, w, R, alpha, beta, v_stick, allow_kick):
    """Eqs. (5)-(6) relative to the floor's velocity (Vx, Vy) = −(Ax, Ay) ω cos ωs; returns
    (vx⁺, vy⁺, outgoing relative normal speed, kicked) as :func:`collide`."""
    nx, ny = arc_normal(d, R)
    cw = w * math.cos(w * s)
    vfx = -Ax * cw
    vfy = -Ay * cw
    un_out, ut_out = restitute(vx - vfx, vy - vfy, nx, ny, alpha, beta)
    if un_out < v_stick:
        # collide's kick, with the gap's G'' at G = G' = 0 under the tilted forces:
        # −gy − ÿ_f + c'' d'² + c' (−gx − ẍ_f), d' = ut ny the relative tangential motion
        sw = w * w * math.sin(w * s)
        g2 = -gy - Ay * sw + (ut_out * ny) ** 2 * arc_curvature(d, R)
        g2 += times_or_zero(arc_slope(d, R), -gx - Ax * sw)
        if allow_kick and g2 > 0.0 and abs(ut_out) >= v_stick:
            return (vfx + v_stick * nx + ut_out * ny, vfy + v_stick * ny - ut_out * nx,
                    v_stick, True)
    return vfx + un_out * nx + ut_out * ny, vfy + un_out * ny - ut_out * nx, un_out, False


@njit(cache=True, inline="always")
def collision(vx, vy, d, s, g, A, w, R, alpha, beta, v_stick, allow_kick, frame):
    # Eqs. (5)-(6) on the floor ``frame`` selects (None: the paper's)
    if frame is None:
        return collide(vx, vy, d, s, g, A, w, R, alpha, beta, v_stick, allow_kick)
    return collide_c(vx, vy, d, s, frame.gx, frame.gy, frame.Ax, frame.Ay, w, R, alpha, beta,
                     v_stick, allow_kick)


@njit(cache=True, inline="always")
def wall_met(cell, d, vx, vy, s, Ax, Ay, w, R, S):
    """(cell, d, met) of the wall a collision at offset d meets: at a cusp (within CUSP_REACH)
    the one the particle approaches, relative normal speed < 0 — the nearest arc by rounding
    may be the one it leaves (a rattle down a steep cusp: Eq. (5) took |u⊥| on the wrong
    wall); met is False where it leaves both walls there: the root found was the gap's
    rounding at the cusp point (a bounce 4e-16 mm short of it 'hit' the neighbour 2e-16 s later,
    again and again), not a collision."""
    side = cusp_side(d, R, S)
    if side == 0:
        return cell, d, True
    cw = w * math.cos(w * s)
    ux = vx + Ax * cw
    uy = vy + Ay * cw
    nx, ny = arc_normal(d, R)
    mx, my = arc_normal(d - side * S, R)
    own = ux * nx + uy * ny
    other = ux * mx + uy * my
    if own >= 0.0 and other < 0.0:
        return cell + side, d - side * S, True
    return cell, d, own < 0.0 or other < 0.0
