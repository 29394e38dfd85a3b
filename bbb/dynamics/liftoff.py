"""When a particle held at rest lifts off, one rule for both floors: where the normal load
n·(a_floor + (gx, gy)) turns negative, in a conveyor's cusp only when both arcs' loads do.
On the paper's floor (``frame = None``, pruned at compile time) that is where the floor
accelerates downward faster than g, sin ωs < −1/Γ, in the expressions its bits were made
with."""

from __future__ import annotations

import math

from ..jit import inlined, jitted
from .bounds import cusp_side
from .floors import normal
from .floors.arc import arc_normal


@inlined
def phase_wait(th, th_l, w):
    # time (s) from the phase th to the next phase th_l (rad, both in [0, 2π)); a whole
    # period if th is th_l: the let-go there was just tried
    if th < th_l:
        return (th_l - th) / w
    return (th_l + 2.0 * math.pi - th) / w


@inlined
def normal_load(nx, ny, gx, gy, Ax, Ay, w):
    # the normal force per unit mass that carries a particle with the floor, n·(a_floor +
    # (gx, gy)) = k sin ωs + gn (mm/s²): returns (k, gn)
    return (nx * Ax + ny * Ay) * w * w, nx * gx + ny * gy


@jitted
def letgo_delay(th, k, gn, w):
    """Time (s) from the phase th (rad) until k sin θ + gn next turns negative (a downward
    crossing, 0 if at th); inf if it never is negative, −1 if it is at all but isolated θ."""
    if k == 0.0:
        return -1.0 if gn < 0.0 else math.inf
    c = -gn / abs(k)
    if c <= -1.0:
        return math.inf
    if c >= 1.0:
        return -1.0
    if k < 0.0:
        th += math.pi
    th = th % (2.0 * math.pi)
    th_l = math.pi - math.asin(c)
    if th == th_l:
        return 0.0
    return phase_wait(th, th_l, w)


@inlined
def let_go(s, d, fl, frame):
    # (k, c, th): the floor lets go where k sin ωs < c |k| turns true, i.e. where the normal
    # load k sin ωs + gn turns negative, c = −gn/|k|; th = ωs shifted by π where k < 0.
    # The paper's floor: k = A ω² > 0 and c = −1/Γ on every arc (the load is ∝ n_y), in
    # the expression order its bits were made with (inf: it never lets go, Γ ≤ 1)
    w = fl.w
    if frame is None:
        gam = fl.A * w * w / fl.g
        if gam <= 1.0:
            return 1.0, -math.inf, w * s
        return 1.0, -1.0 / gam, w * s
    nx, ny = normal(fl.R, d)
    k, gn = normal_load(nx, ny, frame.gx, frame.gy, frame.Ax, frame.Ay, w)
    if k == 0.0:
        # pressed (or let go) at every phase
        return 0.0, math.inf if gn < 0.0 else -math.inf, w * s
    th = w * s if k > 0.0 else w * s + math.pi
    if th >= 2.0 * math.pi:
        th -= 2.0 * math.pi
    return k, -gn / abs(k), th


@jitted
def liftoff_wait(s, d, fl, frame, retry):
    """Time (s) until a particle carried by the floor at offset d lifts off: the normal
    contact force per unit mass, n·(a_floor + (gx, gy)) = An ω² sin ωs + gn, turns negative
    (An, gn: the floor amplitude and gravity along the floor's normal n; on the paper's floor
    ``frame = None``: sin ωs < −1/Γ).  inf if never; ``retry``: the let-go at s was just
    tried and failed.  On the conveyor in a cusp (bbb.dynamics.bounds.cusp_side) both
    arcs must let go."""
    w = fl.w
    if frame is not None:
        side = cusp_side(d, fl.R, fl.S)
        if side != 0:
            return liftoff_wait_cusp(s, d, side, fl, frame, retry)
    k, c, th = let_go(s, d, fl, frame)
    if frame is not None and k == 0.0:
        if c == math.inf:
            return 2.0 * math.pi / w if retry else 0.0
        return math.inf
    if c <= -1.0:
        return math.inf
    sn = math.sin(w * s) if k > 0.0 else -math.sin(w * s)
    if not retry and sn < c:
        return 0.0
    if frame is None:
        return phase_wait(th, math.pi + math.asin(-c), w)
    if c >= 1.0:
        return 2.0 * math.pi / w * 0.25  # lifting everywhere but at one phase: move on
    return phase_wait(th, math.pi - math.asin(c), w)


@jitted
def liftoff_wait_cusp(s, d, side, fl, frame, retry):
    """liftoff_wait on the conveyor (``frame``) in a cusp: the first time both arcs' normal
    loads are negative (the particle's free motion relative to the floor then leaves both),
    inf if never.  A vertical cusp (R = S/2: horizontal normals) lets go only of a load with
    no sideways part."""
    gx, gy, Ax, Ay = frame
    w, R, S = fl.w, fl.R, fl.S
    T = 2.0 * math.pi / w
    n1x, n1y = arc_normal(d, R)
    n2x, n2y = arc_normal(d - side * S, R)
    k1, g1 = normal_load(n1x, n1y, gx, gy, Ax, Ay, w)
    k2, g2 = normal_load(n2x, n2y, gx, gy, Ax, Ay, w)
    if n1y == 0.0 or n2y == 0.0:
        if Ax != 0.0 or gx != 0.0:
            return math.inf  # pressed on one wall at all but isolated phases: held for good
        k1, g1 = Ay * w * w, gy
        k2, g2 = k1, g1
    th = w * s
    if not retry and k1 * math.sin(th) + g1 < 0.0 and k2 * math.sin(th) + g2 < 0.0:
        return 0.0
    e1 = letgo_delay(th, k1, g1, w)
    e2 = letgo_delay(th, k2, g2, w)
    if e1 == math.inf or e2 == math.inf:
        return math.inf
    if e1 < 0.0 and e2 < 0.0:
        return T * 0.25  # both let go at all but isolated phases, a try failed: move on
    best = math.inf
    for i in range(2):
        e, kb, gb, eb = (e1, k2, g2, e2) if i == 0 else (e2, k1, g1, e1)
        if e < 0.0:
            continue  # never turns negative: it is; the other's turn is the candidate
        if e == 0.0 and retry:
            e = T
        ok = eb < 0.0
        if not ok:
            # the other arc's load at this turn: negative, or turning at the same phase
            thc = th + w * e
            fb = kb * math.sin(thc) + gb
            tol = 64.0 * 2.220446049250313e-16 * (abs(kb) + abs(gb))
            ok = fb < -tol or (fb <= tol and kb * math.cos(thc) < 0.0)
        if ok:
            best = min(best, e)
    return best
