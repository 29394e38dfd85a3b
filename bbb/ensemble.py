"""Initial-condition families, drawn deterministically from a ``numpy.random.SeedSequence``.

- ``rest``:     on the surface at uniform random x and floor phase, at rest relative to
                the floor (stuck): it leaves only if the floor accelerates down faster
                than g, i.e. never below Γ = 1.
- ``dropped``:  released with zero velocity from a uniform random height (mm) in
                ``drop_height`` above the surface, at uniform random x and phase.
- ``launched``: leaving the surface vertically at uniform random x and phase, with an
                upward speed relative to the floor uniform in ``launch_speed`` (mm/s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .params import Params
from .surface import depth

__all__ = ["FAMILIES", "InitialState", "initial_state"]

FAMILIES = ("rest", "dropped", "launched")


@dataclass(frozen=True)
class InitialState:
    """Arrays (n_particles,) of initial states: x = cell·S + d (mm), y (mm), v (mm/s),
    floor time s (s) within [0, 1/f), and flags.  On a thrown floor (Params.throw ≠ 90) d is
    the offset relative to the floor, whose sideways displacement X_f(s) adds to x."""

    cell: np.ndarray
    d: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    s: np.ndarray
    stuck: np.ndarray
    from_surface: np.ndarray


def _range(name: str, value: tuple[float, float], lo_ok: float) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (low, high), got {value!r}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and lo_ok <= lo <= hi):
        raise ValueError(f"{name} = {value!r} is out of range; allowed: {lo_ok:g} ≤ low ≤ high, finite")
    return lo, hi


def initial_state(
    p: Params,
    n: int,
    seed: np.random.SeedSequence,
    family: str,
    *,
    drop_height: tuple[float, float] = (0.0, 2.0),
    launch_speed: tuple[float, float] = (0.0, 200.0),
) -> InitialState:
    """Draw ``n`` initial states of ``family`` from ``seed``."""
    if family not in FAMILIES:
        raise ValueError(f"unknown initial family {family!r}; allowed: {', '.join(FAMILIES)}")
    rng = np.random.Generator(np.random.PCG64(seed))
    period = 1.0 / p.f
    d = rng.uniform(-0.5 * p.S, 0.5 * p.S, n)
    s = rng.uniform(0.0, period, n)
    surface = -p.A * np.sin(p.omega * s) - depth(d, p.R)
    floor_v = -p.A * p.omega * np.cos(p.omega * s)
    cell = np.zeros(n, dtype=np.int64)
    vx = np.zeros(n)
    if p.transport:
        # a thrown floor (bbb.conveyor): d is the offset relative to the floor, which moves
        # (Ax, Ay)(−sin 2πft); 'rest' and 'launched' start with its along-plane velocity
        _gx, _gy, ax, ay = p.floor_frame()
        surface = -ay * np.sin(p.omega * s) - depth(d, p.R)
        floor_v = -ay * p.omega * np.cos(p.omega * s)
        if family != "dropped":
            vx = -ax * p.omega * np.cos(p.omega * s)
    if family == "rest":
        return InitialState(cell, d, surface, vx, floor_v.copy(), s,
                            np.ones(n, bool), np.ones(n, bool))
    if family == "dropped":
        lo, hi = _range("drop_height", drop_height, 0.0)
        h = rng.uniform(lo, hi, n)
        return InitialState(cell, d, surface + h, vx, np.zeros(n), s,
                            np.zeros(n, bool), h == 0.0)
    lo, hi = _range("launch_speed", launch_speed, 0.0)
    # (0, hi]: a launch speed of exactly 0 would be a particle at rest, not launched
    u = hi - rng.uniform(0.0, hi - lo, n)
    return InitialState(cell, d, surface, vx, floor_v + u, s, np.zeros(n, bool), np.ones(n, bool))
