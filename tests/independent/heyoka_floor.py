"""An independent event detector: the next contact of a free flight with the moving floor,
found by heyoka's Taylor integrator and its event detection (nothing from bbb).

The flight is integrated in the floor's frame (x along the mean plane, y normal to it;
``floors`` module doc): x'' = −gₓ, y'' = −g_y, with the floor phase θ = θ₀ + ωτ in the event
functions (τ the time since the flight's start, θ₀ a runtime parameter, so one compiled
integrator serves every flight).  Relative to the moving floor the particle sits at
U = x + Aₓ sin θ, V = y + A_y sin θ; each piece of the floor is an event function of (U, V)
that turns negative when the particle passes below it (the shape's ``pieces``): per reachable
cell a whole circle for an arc — its upper envelope is the floor, so the first entry into any
circle is the first contact, and no square root can turn NaN — the plane V = 0 for a flat
floor, V − h(U) for a sine, and the two face lines of every reachable tooth of a sawtooth;
and for every shape the floor's lowest level V = bottom.
Events are terminal and fire only when their function goes from positive to negative; an
event off its piece (a face line beyond the face) is passed over and the flight continues.

heyoka's integrator runs at its default tolerance (machine ε, relative), and its event
detection isolates the roots of each event function's Taylor polynomial over the whole step
(heyoka's documentation, "Event detection"), rather than sampling signs, so a dip below the
floor inside a step is found however short.  One exception, measured with 7.13.2: a step whose
event function starts at exactly 0 (below, PRE_STEP).  The detector's agreement with a
brute-force scan is what tests/independent/test_heyoka_floor.py asserts (TOL_TAU there).

The cells a flight can reach: the flight must meet the floor before it falls below the
floor's lowest point, y < bottom − |A_y| (a bound on its duration, τ_max), and until then U
lies within the range of the parabola x(τ) widened by |Aₓ|.  The flight is cut into time
windows of at most ``SLOTS`` cells each.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import heyoka as hy
import numpy as np

from tests.independent.floors import Drive

#: cells (arcs, teeth) per compiled integrator: a flight that can reach more is cut into windows
SLOTS = 16
#: leaving the floor.  A flight that starts on the floor (after a collision, at a lift-off)
#: starts with an event function of exactly 0, and heyoka 7.13.2 then misses a root later in
#: that same step (a hop within one arc's cell then ends at the lowest level instead:
#: test_a_hop_that_starts_on_an_arc_lands_in_the_same_cell), or, at a lift-off (gap ∝ τ³),
#: finds one at τ = 0.  So the detector first
#: flies the particle off the floor — steps from PRE_STEP s on, doubled, events passed over —
#: until its gap exceeds GAP_OFF mm (≫ the gap's rounding, ~1e-16 mm), and searches from there.
#: A flight that ends before it rises that far is not resolved: an error, never a wrong
#: contact.  The shortest model flights are bounces between the walls of a steep cusp
#: (R = 1.2 mm, S = 2 mm: 1e-10 s, rising 3e-11 mm) and creeping hops.
PRE_STEP = 1e-14
GAP_OFF = 1e-13
#: a flight still within GAP_OFF of the floor after this long (s) does not leave it
MAX_OFF = 1e-4


@dataclass(frozen=True)
class Contact:
    """The next contact: τ (s after the flight's start), the point (x, y) in the floor's frame
    (mm, lab x along the plane), the incoming velocity (mm/s), the floor's phase θ (rad, not
    reduced), the piece hit (cell index k and which of the cell's pieces; k = nan and piece
    −1: the floor's lowest level, at a cusp)."""

    tau: float
    x: float
    y: float
    vx: float
    vy: float
    theta: float
    cell: float
    piece: int


def flight_duration_bound(shape, drive: Drive, y0: float, vy: float) -> float:
    """τ_max (s): the time at which the flight is below the floor's lowest point."""
    _, gy = drive.gravity
    _, ay = drive.amplitude
    drop = y0 - (shape.bottom - abs(ay))
    if drop < 0.0:
        raise ValueError(f"the flight starts below the floor's lowest point ({drop:.3e} mm)")
    return (vy + math.sqrt(vy * vy + 2.0 * gy * drop)) / gy * (1.0 + 1e-12) + 1e-15


@functools.lru_cache(maxsize=32)
def integrator(shape, drive: Drive, slots: int):
    """The compiled integrator for (shape, drive) with ``slots`` cells of events, and the
    number of pieces per cell.  pars[0] = θ₀, pars[1 + j] = the cell index k of slot j (for
    shapes with cells; heyoka sizes ``pars`` to the parameters the expressions use)."""
    gx, gy = drive.gravity
    ax, ay = drive.amplitude
    x, y, vx, vy = hy.make_vars("x", "y", "vx", "vy")
    sin_th = hy.sin(drive.omega * hy.time + hy.par[0])
    U = x + ax * sin_th if ax != 0.0 else x
    V = y + ay * sin_th if ay != 0.0 else y
    events = []
    per_cell = len(shape.pieces(U, V, hy.par[1]))
    for j in range(slots):
        for ex in shape.pieces(U, V, hy.par[1 + j]):
            events.append(hy.t_event(ex, direction=hy.event_direction.negative))
    # the floor's lowest level: a particle can reach it only where the floor is there (at a
    # cusp), so crossing it is a contact; it catches the drop straight into a vertical cusp
    # (R = S/2), where the two circles touch and neither changes sign
    events.append(hy.t_event(V - shape.bottom, direction=hy.event_direction.negative))
    zero = 0.0 * x  # a constant right-hand side as an expression
    ta = hy.taylor_adaptive([(x, vx), (y, vy), (vx, zero - gx), (vy, zero - gy)], [0.0] * 4,
                            t_events=events, compact_mode=True)
    return ta, per_cell


def _x_range(x0: float, vx: float, gx: float, a: float, b: float) -> tuple[float, float]:
    """Exact range of x0 + vx τ − gx τ²/2 over [a, b]."""
    ts = [a, b]
    if gx != 0.0 and a < vx / gx < b:
        ts.append(vx / gx)
    xs = [x0 + vx * t - 0.5 * gx * t * t for t in ts]
    return min(xs), max(xs)


def _windows(shape, drive: Drive, x0: float, vx: float, a: float, b: float, slots: int) -> list:
    """[(a, b, cells)] covering [a, b], each with at most ``slots`` reachable cells."""
    gx, _ = drive.gravity
    ax, _ = drive.amplitude
    lo, hi = _x_range(x0, vx, gx, a, b)
    margin = abs(ax) + 1e-9 * (abs(lo) + abs(hi) + 1.0)
    cells = shape.cells(lo - margin, hi + margin)
    if len(cells) <= slots:
        return [(a, b, cells)]
    mid = 0.5 * (a + b)
    return _windows(shape, drive, x0, vx, a, mid, slots) + _windows(shape, drive, x0, vx, mid, b, slots)


def next_contact(shape, drive: Drive, x0: float, y0: float, vx0: float, vy0: float,
                 theta0: float, slots: int = SLOTS) -> Contact:
    """The first contact of the flight from (x0, y0) with velocity (vx0, vy0) (floor's frame,
    mm, mm/s) at floor phase θ₀ (rad) — a state on or above the floor, e.g. just after a
    collision — with the moving floor ``shape`` driven by ``drive``.

    A periodic floor is the same floor shifted by whole periods P, so the flight is flown from
    x0 − nP (n the nearest whole number of periods; the subtraction is exact in float64) and
    the contact shifted back: the integrator then works with offsets of the order of P, whose
    rounding is that of the floor's own scale, not of a particle's distance from the origin
    (at x ≈ 24 mm an ulp of x moves a sine's height by ~1e-15 mm, ~1e-12 s on a grazing hop)."""
    period = shape.period
    n = round(x0 / period) if math.isfinite(period) and period > 0.0 else 0
    if n:
        c = next_contact(shape, drive, x0 - n * period, y0, vx0, vy0, theta0, slots)
        return Contact(c.tau, c.x + n * period, c.y, c.vx, c.vy, c.theta, c.cell + n, c.piece)
    ta, per_cell = integrator(shape, drive, slots)
    ax, ay = drive.amplitude
    tau_max = flight_duration_bound(shape, drive, y0, vy0)
    ta.time = 0.0
    ta.state[:] = [x0, y0, vx0, vy0]
    if len(ta.pars):  # a still floor (A = 0) has no phase
        ta.pars[0] = theta0
    ta.reset_cooldowns()
    windows = _windows(shape, drive, x0, vx0, 0.0, tau_max, slots)
    _set_cells(ta, windows[0][2], slots)
    tau_off = PRE_STEP
    while (rise := _gap(shape, drive, ta, theta0)) <= GAP_OFF:
        if tau_off > MAX_OFF or (rise < -GAP_OFF and ta.time > 0.0):
            raise AssertionError(f"the flight does not rise {GAP_OFF} mm off the floor (gap "
                                 f"{rise:.2e} mm at {ta.time:.2e} s): too short to resolve")
        while ta.time < tau_off:  # events on the way are the start's own
            ta.propagate_until(tau_off)
        tau_off *= 2.0
    ta.reset_cooldowns()  # a terminal event's cooldown (auto: ~ a step) would mask the contact
    for _, b, cells in windows:
        if ta.time >= b:
            continue
        ks = _set_cells(ta, cells, slots)
        while True:
            outcome = ta.propagate_until(b)[0]
            if outcome == hy.taylor_outcome.time_limit:  # no event: on to the next window
                break
            code = int(outcome.value)  # a terminal event i ends the step with code −1 − i
            if not -len(ta.t_events) <= code < 0:
                raise AssertionError(f"heyoka stopped with {outcome!r} at τ = {ta.time} s")
            x, y, vx, vy = ta.state
            theta = theta0 + drive.omega * ta.time
            if code == -len(ta.t_events):  # the lowest level
                return Contact(ta.time, x, y, vx, vy, theta, math.nan, -1)
            slot, piece = divmod(-1 - code, per_cell)
            u, v = x + ax * math.sin(theta), y + ay * math.sin(theta)
            if shape.on_piece(piece, ks[slot], u, v):
                return Contact(ta.time, x, y, vx, vy, theta, ks[slot], piece)
    raise AssertionError(f"no contact before τ_max = {tau_max} s: the duration bound is wrong")


def _set_cells(ta, cells: range, slots: int) -> np.ndarray:
    """Put the cell indices into the integrator's parameters (unused slots repeat the first)."""
    ks = np.full(slots, float(cells[0]))
    ks[: len(cells)] = cells
    if len(ta.pars) > 1:  # the shape has cells (a flat or sine floor has one piece)
        ta.pars[1:] = ks
    return ks


def _gap(shape, drive: Drive, ta, theta0: float) -> float:
    """The particle's height above the floor now (mm), from the shape's height profile."""
    ax, ay = drive.amplitude
    x, y = ta.state[0], ta.state[1]
    sin_th = math.sin(theta0 + drive.omega * ta.time)
    return y + ay * sin_th - float(shape.height(np.array(x + ax * sin_th)))
