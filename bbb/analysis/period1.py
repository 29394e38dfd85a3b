"""The flat-floor period-1 orbit (1/1 locking) of the bouncing ball: where it exists and where it
stops being stable, as thresholds on Γ = A (2π f)² / g and as frequencies.

For a ball on a flat floor vibrated sinusoidally with restitution α and no memory between
collisions (Luck & Mehta 1993, Phys. Rev. E 48, 3988), the orbit that hits the floor once per
period with flight time 1/f exists from

    Γ₁ = π (1 − α) / (1 + α)                                  (the 1/1 orbit appears)

and is linearly stable up to

    Γ' = sqrt(Γ₁² + (2 (1 + α²) / (1 + α)²)²)                 (it loses stability)

e.g. Γ₁ = 0.5544, Γ' = 1.1707 at α = 0.7: 37.1 Hz and 53.9 Hz at A = 0.1 mm, g = 9800 mm/s².
Neither knows the arcs: they are the thresholds of the floor the billiard's arcs bend.
Units: A in mm, g in mm/s², f in Hz; Γ and α dimensionless.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["gamma_1", "gamma_prime", "frequency_at", "gamma_at"]


def _alpha(alpha: ArrayLike) -> NDArray[np.float64]:
    a = np.asarray(alpha, dtype=np.float64)
    if not np.all((a > 0.0) & (a <= 1.0)):
        raise ValueError(f"alpha = {alpha!r} must lie in (0, 1]")
    return a


def gamma_1(alpha: ArrayLike) -> NDArray[np.float64] | float:
    """Γ₁(α) = π (1 − α) / (1 + α): the Γ from which the flat-floor 1/1 orbit exists."""
    a = _alpha(alpha)
    out = math.pi * (1.0 - a) / (1.0 + a)
    return float(out) if out.ndim == 0 else out


def gamma_prime(alpha: ArrayLike) -> NDArray[np.float64] | float:
    """Γ'(α) = sqrt(Γ₁² + (2 (1 + α²) / (1 + α)²)²): the Γ above which the flat-floor 1/1
    orbit is unstable."""
    a = _alpha(alpha)
    out = np.hypot(math.pi * (1.0 - a) / (1.0 + a), 2.0 * (1.0 + a**2) / (1.0 + a) ** 2)
    return float(out) if out.ndim == 0 else out


def frequency_at(gamma: ArrayLike, A: float, g: float) -> NDArray[np.float64] | float:
    """The frequency (Hz) at which a floor of amplitude A (mm) reaches Γ = A (2π f)² / g (g in
    mm/s²)."""
    if not (A > 0.0 and g > 0.0):
        raise ValueError(f"A = {A!r} mm and g = {g!r} mm/s² must be > 0")
    out = np.sqrt(np.asarray(gamma, dtype=np.float64) * g / A) / (2.0 * math.pi)
    return float(out) if out.ndim == 0 else out


def gamma_at(f: ArrayLike, A: float, g: float) -> NDArray[np.float64] | float:
    """Γ = A (2π f)² / g at frequency f (Hz), amplitude A (mm), gravity g (mm/s²)."""
    out = A * (2.0 * math.pi * np.asarray(f, dtype=np.float64)) ** 2 / g
    return float(out) if out.ndim == 0 else out
