"""Why motion starts: two no-fit predictions of the onset of motion from rest, and the linear
maps behind them (docs/physics.md, "Why motion starts").

(b) *Vertical.*  A particle held at rest lifts off where the floor lets go (sin ωt = −1/Γ,
falling edge), flies, lands and bounces ever lower until its relative normal speed drops
below ``v_stick`` and it sticks again: the chattering cycle, which forgets everything at the
stick.  It is the motion reached from rest as long as that cascade ends before the next
lift-off window opens, one period after the lift-off; :func:`chatter_cycle` flies it in the
model's exact flat-floor map (the floor's motion kept in every flight time) and
:func:`chatter_limit` finds the Γ at which it stops ending in time.

(a) *Horizontal.*  A vertical motion at the floor's lowest point is perturbed by an offset ξ
and a horizontal speed u.  At a smooth minimum of curvature κ (the sine's valleys, c'' = −κ)
a collision at ξ with incoming relative normal speed U turns the normal by κξ, so to first
order u⁺ = β u − (α + β) κ U ξ, and a flight of τ moves ξ by u τ: one bounce is the matrix
:func:`bounce_matrix`, det = β.  The period-1 bounce, its period-2 successor and the
chattering cycle (whose stick zeroes u) each give a product of such matrices; the rest point
is horizontally stable when every eigenvalue lies inside the unit circle.  At the arcs' cusp
the floor is a wedge of two arcs: the kick −(α + β) U sin θc cos θc sgn ξ (sin θc = S/2R) does
not vanish as ξ → 0, so no linearisation exists and any vertical motion with a flight is
horizontally unstable there (:func:`wedge_kick`): it rattles, confined by kicks that point
into the cusp from every point below the arc tops.

Units: mm, s, Hz, mm/s; Γ, α, β dimensionless.  numpy only.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["liftoff_phase", "chatter_cycle", "chatter_ends_in_time", "chatter_limit",
           "period1", "period2", "bounce_matrix", "cycle_matrix", "chatter_lambda",
           "stable", "sine_curvature", "wedge_kick", "wedge_rattle"]

#: the kernel's default v_stick (mm/s): below it a cascade ends in sticking
V_STICK = 1e-3
#: samples per period of the landing search's bracketing grid (a flight shorter than the
#: grid is bracketed on its own scale, 2u/g)
_GRID = 4000


def liftoff_phase(gamma: float) -> float:
    """ωt (rad, in (π, 3π/2]) at which a particle held at rest lifts off a floor at −A sin ωt:
    the falling edge of sin ωt < −1/Γ (Γ > 1)."""
    if not gamma > 1.0:
        raise ValueError(f"gamma = {gamma!r}: a particle at rest lifts off only for Γ > 1")
    return math.pi + math.asin(1.0 / gamma)


def _gap(tau, t0, u, A, w, g):
    # the gap between a particle that leaves the floor at t0 with relative normal speed u
    # and the flat floor −A sin ωt, τ later, written without cancelling A·ω·τ terms (mm)
    # A [sin(a + x) − sin a − x cos a] = A [−2 sin a sin²(x/2) + cos a (sin x − x)]
    a, x = w * t0, w * tau
    sx = x - math.sin(x) if x > 1e-2 else x**3 / 6 - x**5 / 120 + x**7 / 5040
    lift = A * (-2.0 * math.sin(a) * math.sin(0.5 * x) ** 2 - math.cos(a) * sx)
    return u * tau + lift - 0.5 * g * tau * tau


def _landing(t0, u, A, w, g):
    """The first τ > 0 at which the flight leaving the floor at t0 with relative speed u
    (≥ 0) meets it again (s), by a bracketing grid and bisection; inf if none within 3
    periods."""
    T = 2.0 * math.pi / w
    geff = g + A * w * w * math.sin(w * t0)
    scale = 2.0 * u / geff if (u > 0 and geff > 0) else T
    h = min(T / _GRID, scale / 50.0) if scale > 0 else T / _GRID
    a = 0.0
    b = h
    while b < 3.0 * T:
        if _gap(b, t0, u, A, w, g) <= 0.0:
            break
        a, h = b, min(2.0 * h, T / _GRID) if b > 2 * scale else h
        b = a + h
    else:
        return math.inf
    for _ in range(200):
        m = 0.5 * (a + b)
        if m <= a or m >= b:
            break
        if _gap(m, t0, u, A, w, g) > 0.0:
            a = m
        else:
            b = m
    return b


def chatter_cycle(gamma: float, f: float, alpha: float, g: float = 9800.0,
                  v_stick: float = V_STICK, max_bounces: int = 2000):
    """The cascade that follows a lift-off from rest on the flat floor (Γ > 1, frequency f):
    a dict with ``t0`` (s, the lift-off, ωt0 = :func:`liftoff_phase`), arrays ``t`` (s, each
    collision), ``U`` (mm/s, incoming relative normal speed), ``tau`` (s, the flight before
    it) and ``t_end`` (s, the collision that ended it: sticking, or inf when it had not
    ended after ``max_bounces`` collisions or 3 periods of one flight)."""
    w = 2.0 * math.pi * f
    A = gamma * g / (w * w)
    t0 = liftoff_phase(gamma) / w
    t, u = t0, 0.0
    ts, Us, taus = [], [], []
    t_end = math.inf
    for _ in range(max_bounces):
        tau = _landing(t, u, A, w, g)
        if not math.isfinite(tau):
            break
        t1 = t + tau
        vf0 = -A * w * math.cos(w * t)
        v_in = u + vf0 - g * tau  # absolute velocity at the landing
        U = -(v_in - (-A * w * math.cos(w * t1)))
        ts.append(t1), Us.append(U), taus.append(tau)
        u = alpha * U
        t = t1
        if u < v_stick:
            pressed = g + A * w * w * math.sin(w * t1) > 0.0
            if pressed:
                t_end = t1
                break
            u = v_stick  # the kernel's kick: the floor falls away faster than gravity
    return {"t0": t0, "t": np.array(ts), "U": np.array(Us), "tau": np.array(taus),
            "t_end": t_end, "A": A, "w": w}


def chatter_ends_in_time(gamma: float, f: float, alpha: float, g: float = 9800.0,
                         v_stick: float = V_STICK) -> bool:
    """Whether the cascade after a lift-off from rest sticks before the next lift-off
    window opens (t_end < t0 + 1/f): the chattering cycle repeats, one stick per period."""
    c = chatter_cycle(gamma, f, alpha, g, v_stick)
    return c["t_end"] < c["t0"] + 1.0 / f


def chatter_limit(alpha: float, A: float = 0.1, g: float = 9800.0, v_stick: float = V_STICK,
                  f_lo: float = None, f_hi: float = 200.0, tol: float = 1e-3) -> float:
    """The frequency (Hz) at floor amplitude A (mm) above which the chattering cycle from
    rest no longer ends within its period (flat floor, restitution α): the lowest f at
    which :func:`chatter_ends_in_time` turns false, by bisection from the lift-off
    frequency (Γ = 1) to ``f_hi``; tol in Hz.  The cascade's length grows with f here, so
    the first change is the one bisection finds (checked against a scan in the tests)."""
    f1 = math.sqrt(g / A) / (2.0 * math.pi)
    lo = f1 * (1.0 + 1e-6) if f_lo is None else f_lo

    def ok(f):
        return chatter_ends_in_time(A * (2 * math.pi * f) ** 2 / g, f, alpha, g, v_stick)

    if not ok(lo):
        return lo
    hi = f_hi
    if ok(hi):
        return math.inf
    while hi - lo > tol:
        m = 0.5 * (lo + hi)
        if ok(m):
            lo = m
        else:
            hi = m
    return hi


def period1(f: float, alpha: float, g: float = 9800.0) -> tuple[float, float]:
    """(U, τ) of the flat-floor period-1 bounce (1/1 orbit) at frequency f: flight τ = 1/f,
    incoming relative normal speed U = g τ / (1 + α) (mm/s, s) -- exact in the moving-floor
    map (the floor is back at the same height and speed after a period)."""
    tau = 1.0 / f
    return g * tau / (1.0 + alpha), tau


def _vertical_step(phase, u, A, w, g):
    # one flight of the exact flat-floor map: (impact phase ωt mod 2π, outgoing relative
    # speed u) -> (next impact phase, incoming relative speed U, flight τ)
    t = phase / w
    tau = _landing(t, u, A, w, g) if u >= 0.0 else math.inf
    if not math.isfinite(tau):
        return math.nan, math.nan, math.inf
    t1 = t + tau
    v_in = u - A * w * math.cos(w * t) - g * tau
    U = -A * w * math.cos(w * t1) - v_in
    return (w * t1) % (2 * math.pi), U, tau


def period2(gamma: float, f: float, alpha: float, g: float = 9800.0,
            guess: tuple[float, float] | None = None):
    """The flat-floor period-2 orbit (two bounces in two periods) at Γ beyond Γ', by Newton on
    the exact two-bounce map: {"phase": ωt of a collision (rad), "u": the relative normal
    speed leaving it (mm/s), "legs": ((U1, τ1), (U2, τ2)) -- each flight τ (s) followed by a
    collision of incoming relative speed U (mm/s)} -- or None when Newton does not converge."""
    w = 2.0 * math.pi * f
    A = gamma * g / (w * w)
    U0, T = period1(f, alpha, g)
    # the 1/1 orbit's impact phase: the floor's velocity there is gT(1 − α)/(2(1 + α)),
    # taken on the side where the floor decelerates (the branch the period doubling leaves)
    vf = g * T * (1 - alpha) / (2 * (1 + alpha))
    ph1 = 2 * math.pi - math.acos(max(-1.0, min(1.0, -vf / (A * w))))
    if guess is None:
        # the period-2 orbit is the attractor just beyond Γ': iterate onto it from the 1/1 orbit
        p, u = ph1 + 1e-3, alpha * U0
        for _ in range(400):
            p, U, _ = _vertical_step(p, u, A, w, g)
            if not math.isfinite(p):
                return None
            u = alpha * U
        guess = (p, u)
    x = np.array(guess, dtype=float)

    def F(z):
        p, u = z
        p1, U1, _ = _vertical_step(p % (2 * math.pi), u, A, w, g)
        p2, U2, _ = _vertical_step(p1, alpha * U1, A, w, g)
        dp = (p2 - p + math.pi) % (2 * math.pi) - math.pi
        return np.array([dp, alpha * U2 - u])

    for _ in range(60):
        r = F(x)
        if not np.all(np.isfinite(r)):
            return None
        if np.max(np.abs(r / np.array([1.0, max(1.0, x[1])]))) < 1e-11:
            break
        J = np.empty((2, 2))
        for k, h in enumerate((1e-7, 1e-7 * max(1.0, x[1]))):
            e = np.zeros(2)
            e[k] = h
            J[:, k] = (F(x + e) - F(x - e)) / (2 * h)
        try:
            x = x - np.linalg.solve(J, r)
        except np.linalg.LinAlgError:
            return None
    else:
        return None
    p, u = x
    p1, U1, t1 = _vertical_step(p % (2 * math.pi), u, A, w, g)
    _, U2, t2 = _vertical_step(p1, alpha * U1, A, w, g)
    if abs(t1 - t2) < 1e-9 / f:  # Newton fell back onto the 1/1 orbit
        return None
    return {"phase": float(p % (2 * math.pi)), "u": float(u),
            "legs": ((float(U1), float(t1)), (float(U2), float(t2)))}


def bounce_matrix(kappa: float, U: float, tau: float, alpha: float, beta: float) -> np.ndarray:
    """One flight of τ (s) then one collision at a smooth minimum of curvature κ (1/mm) with
    incoming relative normal speed U (mm/s), on (ξ, u) just after a collision (mm, mm/s):
    ξ' = ξ + u τ, u' = β u − (α + β) κ U ξ'.  Its determinant is β."""
    c = (alpha + beta) * kappa * U
    return np.array([[1.0, tau], [-c, beta - c * tau]])


def cycle_matrix(kappa: float, legs, alpha: float, beta: float) -> np.ndarray:
    """The product of :func:`bounce_matrix` over ``legs`` = [(U, τ), ...] in time order."""
    M = np.eye(2)
    for U, tau in legs:
        M = bounce_matrix(kappa, U, tau, alpha, beta) @ M
    return M


def chatter_lambda(kappa: float, cycle: dict, alpha: float, beta: float) -> float:
    """ξ after / ξ before one chattering cycle at a smooth minimum of curvature κ (1/mm): the
    particle lifts off with u = 0, lands where it left (the first flight carries no u), and
    every collision of the cascade turns (ξ, u) by :func:`bounce_matrix`; the stick zeroes u
    and freezes ξ.  |λ| < 1: the rest point is horizontally stable under chattering."""
    U, tau = cycle["U"], cycle["tau"]
    if not U.size:
        return math.nan
    c0 = (alpha + beta) * kappa * U[0]
    z = np.array([1.0, -c0])  # (ξ, u) after the first collision, for ξ = 1 at the lift-off
    for k in range(1, U.size):
        z = bounce_matrix(kappa, U[k], tau[k], alpha, beta) @ z
    return float(z[0])


def stable(M: np.ndarray) -> bool:
    """Whether every eigenvalue of the 2×2 map M lies strictly inside the unit circle."""
    return bool(np.max(np.abs(np.linalg.eigvals(M))) < 1.0)


def sine_curvature(depth: float, S: float) -> float:
    """κ (1/mm) of the sine floor at its valleys: (depth/2)(2π/S)² (depth top to valley)."""
    return 0.5 * depth * (2.0 * math.pi / S) ** 2


def wedge_kick(U: float, alpha: float, beta: float, R: float, S: float) -> float:
    """The horizontal speed (mm/s) toward the cusp that a vertical impact of relative speed U
    (mm/s) on either wall of the arcs' cusp leaves with: (α + β) U sin θc cos θc, sin θc =
    S/2R -- the same at any offset from the cusp, however small (a wedge: no linearisation)."""
    s = S / (2.0 * R)
    return (alpha + beta) * U * s * math.sqrt(1.0 - s * s)


def wedge_rattle(U: float, tau: float, alpha: float, beta: float, R: float, S: float) -> float:
    """Half-width (mm) of the symmetric horizontal 2-cycle of a vertical motion (impact speed
    U, flight τ) in the cusp's wedge with straight walls: the kick K = :func:`wedge_kick`
    sends it across with speed K/(1 + β), so it lands K τ / (2(1 + β)) either side."""
    return wedge_kick(U, alpha, beta, R, S) * tau / (2.0 * (1.0 + beta))
