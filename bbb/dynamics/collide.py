"""The collision rule, Eqs. (5)-(6), once for both floors: restitution in the floor's normal
and tangential frame relative to the floor's velocity, with the kick that ends a grazing
cascade where the floor falls away faster than the particle; and, on the conveyor, which
wall of a cusp a collision meets.  The paper's floor (``frame = None``) is the variant numba
prunes at compile time: each floor's expressions keep the order its bits were made with."""

from __future__ import annotations

import math

from ..jit import inlined
from ..surface import floor_a, floor_v
from .bounds import cusp_side, times_or_zero
from .floors import curvature, normal, slope


@inlined
def restitute(ux, uy, nx, ny, alpha, beta):
    # Eqs. (5)-(6): outgoing normal and tangential speeds of the velocity (ux, uy) relative to
    # the floor at the normal (nx, ny); |un|: a grazing contact rounded to un ≥ 0 still
    # reflects outward
    un = ux * nx + uy * ny
    ut = ux * ny - uy * nx
    return alpha * abs(un), beta * ut


@inlined
def floor_velocity_at(s, w, fl, frame):
    # the floor's velocity (vfx, vfy) (mm/s), each floor in the expression order its bits
    # were made with: −(A ω) cos ωs on the paper's floor, −Ay (ω cos ωs) on the conveyor
    if frame is None:
        return 0.0, floor_v(s, fl.A, w)
    cw = w * math.cos(w * s)
    return -frame.Ax * cw, -frame.Ay * cw


@inlined
def plus_floor(vf, v, frame):
    # vf + v, but v on the paper's floor, which does not move along x (vf = 0 there, and
    # 0 + v would turn a −0 into +0)
    if frame is None:
        return v
    return vf + v


@inlined
def pressing(d, s, w, fl, frame):
    # the gap's G'' at G = G' = 0 but for the tangential motion's c'' d'² term (mm/s²), as
    # (normal part, tilt part): −g − ÿ_f on the paper's floor; −gy − ÿ_f and c' (−gx − ẍ_f)
    # under the conveyor's tilted forces
    if frame is None:
        return -fl.g - floor_a(s, fl.A, w), 0.0
    sw = w * w * math.sin(w * s)
    return -frame.gy - frame.Ay * sw, times_or_zero(slope(fl.R, d), -frame.gx - frame.Ax * sw)


@inlined
def collide(vx, vy, d, s, fl, frame, v_stick, allow_kick):
    """Eqs. (5)-(6): restitution in the floor's normal/tangential frame at offset d, relative
    to the floor's velocity, on the floor shape fl.R (bbb.dynamics.floors) of the floor
    ``frame`` selects (None: the paper's; else the conveyor's Frame, arcs only).  Returns
    (vx⁺, vy⁺, outgoing relative normal speed, kicked); a speed below ``v_stick`` means the
    particle sticks."""
    R = fl.R
    nx, ny = normal(R, d)
    vfx, vfy = floor_velocity_at(s, fl.w, fl, frame)
    un_out, ut_out = restitute(vx - vfx, vy - vfy, nx, ny, fl.alpha, fl.beta)
    if un_out < v_stick:
        # A cascade of ever smaller bounces (which ends in sticking) needs the surface to
        # press on the particle: G'' ≤ 0 at G = G' = 0.  Where the arc falls away faster
        # than gravity and floor pull the particle down (vx² c'' > g + a_f, a fast
        # tangential touch), the particle flies off instead: leave with v_stick.
        # Never twice in a row: in a cusp (R = S/2) the neighbouring wall sends the particle
        # straight back, and repeated kicks would be an endless Zeno sequence.
        gn, gt = pressing(d, s, fl.w, fl, frame)
        g2 = gn + (ut_out * ny) ** 2 * curvature(R, d)
        g2 += gt  # only its sign matters: + 0.0 on the paper's floor changes none
        if allow_kick and g2 > 0.0 and abs(ut_out) >= v_stick:
            return (plus_floor(vfx, v_stick * nx, frame) + ut_out * ny,
                    vfy + v_stick * ny - ut_out * nx, v_stick, True)
    return (plus_floor(vfx, un_out * nx, frame) + ut_out * ny, vfy + un_out * ny - ut_out * nx,
            un_out, False)


@inlined
def wall_met(cell, d, vx, vy, s, fl, frame):
    """(cell, d, met) of the wall a collision at offset d meets: at a cusp (within CUSP_REACH)
    the one the particle approaches, relative normal speed < 0 — the nearest arc by rounding
    may be the one it leaves (a rattle down a steep cusp: Eq. (5) took |u⊥| on the wrong
    wall); met is False where it leaves both walls there: the root found was the gap's
    rounding at the cusp point (a bounce 4e-16 mm short of it 'hit' the neighbour 2e-16 s later,
    again and again), not a collision.  ``fl``, ``frame``: the conveyor's records."""
    Ax, Ay = frame.Ax, frame.Ay
    w, R, S = fl.w, fl.R, fl.S
    side = cusp_side(d, R, S)
    if side == 0:
        return cell, d, True
    cw = w * math.cos(w * s)
    ux = vx + Ax * cw
    uy = vy + Ay * cw
    nx, ny = normal(R, d)
    mx, my = normal(R, d - side * S)
    own = ux * nx + uy * ny
    other = ux * mx + uy * my
    if own >= 0.0 and other < 0.0:
        return cell + side, d - side * S, True
    return cell, d, own < 0.0 or other < 0.0
