"""The flat-floor spiral approximation of the paper, Eqs. (8)–(9), and the locking ratio, Eq. (7).

Klages, Barna & Mátyás repeat the Luck–Mehta argument for a flat floor
y_f(t) = -A sin(2π f t) and no memory between collisions: a particle launched from the
floor at t0, when the floor moves upward fastest, and hitting it again at t1 leaves with

    y1⁺   = -A sin(2π f t1)                                                  (8)
    v_y1⁺ = α g/2 (t1 - t0) - A 2π f (1 + α) cos(2π f t1)                    (9)

with t1 = t0 + t_c and t_c ∈ [0, t_max(f)] taken from the simulated collision times.
The curve (y1⁺, v_y1⁺) traced as t_c grows is the spiral of the paper's Fig. 3.

Units: A in mm, f in Hz, g in mm/s², times in s, velocities in mm/s.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["floor_t0", "spiral", "spiral_of", "locking_ratio"]


class _HasSpiralParams(Protocol):
    A: float
    f: float
    g: float
    alpha: float


def floor_t0(f: float) -> float:
    """Launch time t0, s: when the floor y_f = -A sin(2π f t) moves upward fastest.

    The floor velocity is v_f = -2π f A cos(2π f t), largest (+2π f A) where
    cos(2π f t) = -1, i.e. 2π f t = π: t0 = 1/(2f), the unique such time in [0, 1/f).
    There the floor passes its rest height y_f = 0 going up.
    """
    if not (math.isfinite(f) and f > 0):
        raise ValueError(f"f = {f!r} must be a finite frequency > 0 (Hz)")
    return 0.5 / f


def spiral(
    A: float, f: float, g: float, alpha: float, t_c: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Post-collision height and vertical velocity of the spiral, Eqs. (8)–(9).

    A     -- floor amplitude, mm
    f     -- floor frequency, Hz
    g     -- gravitational acceleration, mm/s²
    alpha -- normal restitution coefficient
    t_c   -- flight times t1 - t0 ≥ 0, s (array or scalar)

    Returns ``(y, v)`` with the shape of ``t_c``: y1⁺ in mm and v_y1⁺ in mm/s, where
    t1 = floor_t0(f) + t_c.
    """
    for name, value in (("A", A), ("g", g), ("alpha", alpha)):
        if not math.isfinite(value):
            raise ValueError(f"{name} = {value!r} must be finite")
    tc = np.asarray(t_c, dtype=np.float64)
    if not np.all(np.isfinite(tc)) or np.any(tc < 0):
        raise ValueError("t_c must be finite and ≥ 0 (flight time after launch, s)")
    t0 = floor_t0(f)
    phase = 2.0 * math.pi * f * (t0 + tc)
    y = -A * np.sin(phase)
    v = alpha * g / 2.0 * tc - A * 2.0 * math.pi * f * (1.0 + alpha) * np.cos(phase)
    return y, v


def spiral_of(
    params: _HasSpiralParams, t_c: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:func:`spiral` with A, f, g, alpha read from any object that has them (e.g. Params)."""
    return spiral(params.A, params.f, params.g, params.alpha, t_c)


def locking_ratio(v_y: ArrayLike, f: ArrayLike, g: float) -> NDArray[np.float64] | float:
    """k = T_p / T_f = 2 v_y f / g, paper Eq. (7) (dimensionless).

    v_y -- post-collision vertical velocity, mm/s; the flight time is T_p = 2 v_y / g
    f   -- floor frequency, Hz (T_f = 1/f)
    g   -- gravitational acceleration, mm/s²

    k = 1 is 1/1 frequency locking; half-integer k marks the spiral resonances.
    Returns a float for scalar input, else an array.
    """
    if not (math.isfinite(g) and g > 0):
        raise ValueError(f"g = {g!r} must be finite and > 0 (mm/s²)")
    k = 2.0 * np.asarray(v_y, dtype=np.float64) * np.asarray(f, dtype=np.float64) / g
    return float(k) if k.ndim == 0 else k
