"""Where a particle is between events, on either floor: the lab position of a state, the
floor's velocity, a flight's end (Eqs. 1-4) and the position samples written along the way.

``R`` is the floor's shape (bbb.dynamics.floors).  ``frame`` is None on the paper's floor
(numba prunes the conveyor branches at compile time) or the conveyor's
:class:`bbb.dynamics.options.Frame`, whose offsets d are relative to the moving floor
(lab x = cell·S + d + X_f, X_f = −Ax sin ωs).
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..surface import floor_v, floor_y
from .bounds import round_half_away
from .floors import depth, is_flat


@inlined
def lab_x(cell, d, s, S, w, frame):
    # x (mm) of the state (cell, d) at floor time s
    if frame is None:
        return cell * S + d
    return cell * S + d - frame.Ax * math.sin(w * s)


@inlined
def surface_y(s, d, A, w, R, frame):
    # Sec. 2: the surface's height under offset d, y_f − c(d)
    if frame is None:
        return floor_y(s, A, w) - depth(R, d)
    return -frame.Ay * math.sin(w * s) - depth(R, d)


@inlined
def floor_velocity(s, A, w, frame):
    # the floor's velocity (mm/s): what a particle held at rest moves with
    if frame is None:
        return 0.0, floor_v(s, A, w)
    return -frame.Ax * w * math.cos(w * s), -frame.Ay * w * math.cos(w * s)


@inlined
def on_arc_velocity(vt, nx, ny, vfx, vfy, frame):
    # sliding with tangential speed vt relative to the floor on the arc of normal (nx, ny)
    if frame is None:
        return vt * ny, vfy - vt * nx
    return vfx + vt * ny, vfy - vt * nx


@inlined
def fill_flight(samples, isamp, t_end, x0, vx, t_now, frame):
    # x at the sample times before t_end of a flight from x0 at t_now (Eq. 1); samples =
    # (sample_times, pos)
    sample_times, pos = samples
    ns = sample_times.shape[0]
    while isamp < ns and sample_times[isamp] < t_end:
        dt = sample_times[isamp] - t_now
        if frame is None:
            pos[isamp] = x0 + vx * dt
        else:
            pos[isamp] = x0 + vx * dt - 0.5 * frame.gx * dt * dt
        isamp += 1
    return isamp


@inlined
def fill_carried(samples, isamp, t_end, base, s, t_now, w, frame):
    # x at the sample times before t_end of a particle held at rest at base = cell·S + d;
    # samples = (sample_times, pos)
    sample_times, pos = samples
    ns = sample_times.shape[0]
    while isamp < ns and sample_times[isamp] < t_end:
        if frame is None:
            pos[isamp] = base
        else:
            pos[isamp] = base - frame.Ax * math.sin(w * (s + (sample_times[isamp] - t_now)))
        isamp += 1
    return isamp


@inlined
def fly(st, tau, j, fl, frame):
    # Eqs. (1)-(4): the end (cell, d, vx, vy) of the flight from st = (cell, d, vx, vy, s), τ
    # later over the arc j cells on (conveyor: the nearest arc of the offset relative to the
    # floor, bbb.dynamics.bounds's module doc)
    cell, d, vx, vy, s = st
    w, R, S = fl.w, fl.R, fl.S
    if frame is None:
        d = d + vx * tau - j * S
        cell += j
        if is_flat(R):
            k = math.floor(d / S + 0.5)
            d -= k * S
            cell += int(k)
        else:
            d = min(max(d, -0.5 * S), 0.5 * S)
        return cell, d, vx, vy - fl.g * tau
    d = d + vx * tau - 0.5 * frame.gx * tau * tau + frame.Ax * (math.sin(w * (s + tau))
                                                                - math.sin(w * s))
    k = round_half_away(d / S)
    d -= k * S
    cell += int(k)
    d = min(max(d, -0.5 * S), 0.5 * S)
    return cell, d, vx - frame.gx * tau, vy - frame.gy * tau
