"""The floor shapes and the floor's motion, written on their own for the independent checks
(nothing from bbb): each shape's height profile in numpy (the brute-force gap scan reads it)
and its contact pieces as heyoka expressions (the event detector integrates them).

Conventions (docs/physics.md, "Model and units" and "Transport"; lengths mm, times s):
the floor's frame has x along its mean plane and y normal to it; gravity there is
(−g sin φ, −g cos φ) for a tilt φ, and the floor moves rigidly by A (cos ψ, sin ψ)(−sin θ),
θ = 2πf·(floor time), ψ the throw (90°: the paper's vertical vibration).  A point of the floor
at offset u from the floor's origin (u = x − X_f) sits at height h(u) above Y_f.  The paper's
arcs have their tops at h = 0, h(u) = −(R − √(R² − d²)) with d the offset from the nearest
arc centre kS.  Every shape follows the same frame (docs/physics.md, "Floors"): cells
[kS − S/2, kS + S/2], the tops (a sine's crests, a sawtooth's peaks) at height 0, the
valleys below, at the cell edges for the arcs, the sine and the sawtooth.  Each shape is one
small ``height`` function (numpy) and one ``pieces`` function (heyoka), adapted together.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: a contact point off its piece by more than this fraction of the piece's length is not on it
#: (rounding of the event's position: the pieces meet at cusps and kinks)
ON_PIECE = 1e-9


@dataclass(frozen=True)
class Drive:
    """Gravity and the floor's vibration: g (mm/s²), A (mm), f (Hz), tilt φ and throw ψ
    (degrees), exactly as bbb.Params names them."""

    g: float
    A: float
    f: float
    tilt: float = 0.0
    throw: float = 90.0

    @property
    def omega(self) -> float:
        return 2.0 * math.pi * self.f

    @property
    def gravity(self) -> tuple[float, float]:
        """(gₓ, g_y): gravity's magnitudes along −x and −y of the floor's frame, mm/s²."""
        phi = math.radians(self.tilt)
        return self.g * math.sin(phi), self.g * math.cos(phi)

    @property
    def amplitude(self) -> tuple[float, float]:
        """(Aₓ, A_y): the floor's amplitudes along x and y, mm (it moves by (Aₓ, A_y)(−sin θ))."""
        psi = math.radians(self.throw)
        if self.throw == 90.0:  # exactly vertical: no rounding of cos 90° into a sideways motion
            return 0.0, self.A
        return self.A * math.cos(psi), self.A * math.sin(psi)


@dataclass(frozen=True)
class Arc:
    """The paper's floor: arcs of radius R (mm) centred at x = kS, tops at height 0."""

    R: float
    S: float
    name = "arc"

    @property
    def period(self) -> float:
        return self.S

    @property
    def top(self) -> float:
        return 0.0

    @property
    def bottom(self) -> float:
        return float(self.height(np.array(0.5 * self.S)))

    def height(self, u: np.ndarray) -> np.ndarray:
        d = u - np.floor(u / self.S + 0.5) * self.S
        ad = np.abs(d)
        q = np.sqrt(np.maximum((self.R - ad) * (self.R + ad), 0.0))
        return -d * d / (self.R + q)

    def cells(self, u_lo: float, u_hi: float) -> range:
        """The arcs whose cell [kS − S/2, kS + S/2] meets [u_lo, u_hi]."""
        return range(math.floor(u_lo / self.S + 0.5), math.floor(u_hi / self.S + 0.5) + 1)

    def pieces(self, U, V, k):
        """Circle k, (U − kS)² + V (V + 2R): < 0 inside, written without R² − R² cancellation."""
        return [(U - k * self.S) ** 2 + V * (V + 2.0 * self.R)]

    def on_piece(self, j: int, k: float, u: float, v: float) -> bool:
        """Whether an entry into circle k at (u, v) lies on the floor: in its cell, upper half."""
        return abs(u - k * self.S) <= 0.5 * self.S * (1.0 + ON_PIECE) and v + self.R >= 0.0


@dataclass(frozen=True)
class Flat:
    """A flat floor at height 0 (bbb's R = inf)."""

    name = "flat"
    period = math.inf
    top = 0.0
    bottom = 0.0

    def height(self, u: np.ndarray) -> np.ndarray:
        return np.zeros_like(np.asarray(u, float))

    def cells(self, u_lo: float, u_hi: float) -> range:
        return range(0, 1)

    def pieces(self, U, V, k):
        return [V]

    def on_piece(self, j: int, k: float, u: float, v: float) -> bool:
        return True


@dataclass(frozen=True)
class Sine:
    """h(u) = a (cos(2πu/λ) − 1): amplitude a (mm, top to valley 2a), wavelength λ (mm); tops
    at u = kλ at height 0 (like the arcs' tops), valleys at u = (k + ½)λ at height −2a."""

    amplitude: float
    wavelength: float
    name = "sine"

    @property
    def period(self) -> float:
        return self.wavelength

    @property
    def top(self) -> float:
        return 0.0

    @property
    def bottom(self) -> float:
        return -2.0 * abs(self.amplitude)

    def height(self, u: np.ndarray) -> np.ndarray:
        w = 2.0 * math.pi * np.asarray(u, float) / self.wavelength
        return self.amplitude * (np.cos(w) - 1.0)

    def cells(self, u_lo: float, u_hi: float) -> range:
        return range(0, 1)

    def pieces(self, U, V, k):
        import heyoka as hy

        return [V - self.amplitude * (hy.cos((2.0 * math.pi / self.wavelength) * U) - 1.0)]

    def on_piece(self, j: int, k: float, u: float, v: float) -> bool:
        return True


@dataclass(frozen=True)
class Sawtooth:
    """Teeth of period P (mm) and height H (mm) with straight faces: the peaks at height 0 (like
    the arcs' tops), the valleys at height −H at the cell edges u = (k + ½)P, each peak a
    fraction ξ = ``peak`` in (0, 1) of P right of its left valley, at u = (k − ½ + ξ)P
    (½: symmetric teeth, peaks at kP).  Tooth k spans [(k − ½)P, (k + ½)P]."""

    period: float
    peak: float
    height_mm: float
    name = "sawtooth"

    @property
    def top(self) -> float:
        return 0.0

    @property
    def bottom(self) -> float:
        return -self.height_mm

    def height(self, u: np.ndarray) -> np.ndarray:
        r = np.asarray(u, float) / self.period + 0.5
        s = r - np.floor(r)  # position in the tooth from its left valley, [0, 1)
        up = np.where(s <= self.peak, s / self.peak, (1.0 - s) / (1.0 - self.peak))
        return self.height_mm * (up - 1.0)

    def cells(self, u_lo: float, u_hi: float) -> range:
        """The teeth [(k − ½)P, (k + ½)P] that meet [u_lo, u_hi]."""
        return range(math.floor(u_lo / self.period + 0.5), math.floor(u_hi / self.period + 0.5) + 1)

    def pieces(self, U, V, k):
        """Tooth k's two faces as lines (above the line: > 0); each line reaches beyond its
        face, so an event is kept only when it lies on the face (:meth:`on_piece`)."""
        P, xi, H = self.period, self.peak, self.height_mm
        s = U - (k - 0.5) * P  # from the tooth's left valley
        return [V + H - (H / (xi * P)) * s, V + H - (H / ((1.0 - xi) * P)) * (P - s)]

    def on_piece(self, j: int, k: float, u: float, v: float) -> bool:
        s = u / self.period - k + 0.5
        lo, hi = (0.0, self.peak) if j == 0 else (self.peak, 1.0)
        return lo - ON_PIECE <= s <= hi + ON_PIECE


SHAPES = {"arc": Arc, "flat": Flat, "sine": Sine, "sawtooth": Sawtooth}
