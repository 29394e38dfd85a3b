"""The floor's profile within a cell, for the trajectory checker (tests/bbb/trajectory_check.py),
in its own numpy code (nothing from bbb): one class per shape with the depth c(d) below the
floor's top at offset d (mm) from a cell's centre, its slope and curvature, the outward normal,
how far they move with a rounding of d, and the bounds the checker's level gap certificate
takes over an offset range [da, db] within one cell (the least depth, the least curvature,
the largest pull n_y² c'').  Conventions: docs/physics.md, "Floors"."""

from __future__ import annotations

import math

import numpy as np


class ArcProfile:
    """The paper's arcs of radius R (mm): offset d from an arc's centre lies c(d) = R − √(R² − d²)
    below its top.  A floor shape gives the checker its depth, slope, curvature, normal and how
    far they move with a rounding of d; a new shape is a class like this one plus the parts of
    the checker that still assume arcs (module doc, "Other floor shapes")."""

    def __init__(self, R: float) -> None:
        self.R = R

    def q(self, d):
        # √(R² − d²) as √((R−|d|)(R+|d|)): no cancellation at the cusps of R = S/2
        ad = np.abs(d)
        return np.sqrt(np.maximum((self.R - ad) * (self.R + ad), 0.0))

    def depth(self, d):
        """c(d) = R − √(R² − d²) (mm), written d²/(R + √(R² − d²))."""
        return d * d / (self.R + self.q(d))

    def slope(self, d):
        """c'(d) = d/√(R² − d²); ±inf at a vertical cusp."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.q(d) > 0, d / self.q(d), np.copysign(np.inf, d))

    def curvature(self, d):
        """c''(d) = R²/(R² − d²)^{3/2}, increasing in |d|."""
        with np.errstate(divide="ignore"):
            return self.R**2 / self.q(d) ** 3

    def normal(self, d):
        """Outward unit normal (nₓ, n_y) of the arc at offset d."""
        return d / self.R, self.q(d) / self.R

    def height_error(self, d, dx):
        """Largest change of c when d moves by dx: min(c'·dx, √(2R dx)) (mm)."""
        far = np.minimum(np.abs(d) + dx, self.R)
        with np.errstate(invalid="ignore"):
            lip = np.where(far < self.R, self.slope(far) * dx, np.inf)
        return np.minimum(lip, np.sqrt(2.0 * self.R * dx))

    def normal_error(self, dx, d=None):
        """δn ≤ δd/R + √(2R δd)/R (the √ at a vertical cusp)."""
        return dx / self.R + np.sqrt(2.0 * self.R * dx) / self.R

    @property
    def scale(self):
        """The length (mm) whose rounding the gap carries besides the particle's: R."""
        return self.R

    def depth_min(self, da, db, ca, cb):
        """A lower bound of c over offsets [da, db] in one cell (c grows with |d|)."""
        return np.where(da * db <= 0, 0.0, np.minimum(ca, cb))

    def curvature_min(self, da, db):
        """A lower bound of c'' over [da, db] in one cell: c'' grows with |d|."""
        return self.curvature(np.where(da * db <= 0, 0.0, np.minimum(np.abs(da), np.abs(db))))

    def pull(self, d, dx):
        """The largest n_y² c'' within dx of d (1/mm): (β u∥)² times it is the arc's pull on a
        particle leaving it (the sticking rule's G''): 1/√(R² − d²) at |d| + dx."""
        with np.errstate(divide="ignore"):
            return 1.0 / self.q(np.minimum(np.abs(d) + dx, self.R))


class SineProfile:
    """A sine of amplitude a (mm, top to valley 2a) and wavelength S: c(d) = a (1 − cos kd),
    k = 2π/S, tops at the cell centres, smooth valleys at the cell edges (docs/physics.md,
    "Floors").  Within a cell c grows with |d| and c'' = a k² cos kd falls with |d|."""

    def __init__(self, depth: float, S: float) -> None:
        self.a, self.k = 0.5 * depth, 2.0 * math.pi / S

    def depth(self, d):
        return self.a * (1.0 - np.cos(self.k * d))

    def slope(self, d):
        return self.a * self.k * np.sin(self.k * d)

    def curvature(self, d):
        return self.a * self.k**2 * np.cos(self.k * d)

    def normal(self, d):
        c1 = self.slope(d)
        r = np.sqrt(1.0 + c1 * c1)
        return c1 / r, 1.0 / r

    def height_error(self, d, dx):
        """|c'| ≤ a k: c moves by at most a k dx."""
        return self.a * self.k * np.asarray(dx, float) + 0.0 * d

    def normal_error(self, dx, d=None):
        """The normal is a function of c' with derivative ≤ 1, and |c''| ≤ a k²."""
        return self.a * self.k**2 * dx

    @property
    def scale(self):
        return 2.0 * self.a

    def depth_min(self, da, db, ca, cb):
        return np.where(da * db <= 0, 0.0, np.minimum(ca, cb))

    def curvature_min(self, da, db):
        """c'' falls with |d| up to the valley (|d| = S/2, c'' = −a k²): its least at max |d|."""
        far = np.minimum(self.k * np.maximum(np.abs(da), np.abs(db)), math.pi)
        return self.a * self.k**2 * np.cos(far)

    def pull(self, d, dx):
        """An upper bound of n_y² c'' within dx of d: c'' is largest at the least |d|, where
        (c'' > 0 there, |d| ≤ S/4) n_y² = 1/(1 + c'²) is largest too; where even that c'' is
        < 0, n_y² ≥ 1/(1 + a²k²) bounds the product."""
        near = np.minimum(np.maximum(np.abs(d) - dx, 0.0), math.pi / self.k)
        c2 = self.curvature(near)
        return np.where(c2 > 0, c2 / (1.0 + self.slope(near) ** 2), c2 / (1.0 + (self.a * self.k) ** 2))


class SawtoothProfile:
    """A sawtooth ``depth`` h (mm) deep on a period S: straight flanks from a valley at each
    cell edge up to one peak, a fraction ``peak`` ξ of S from the left valley, i.e. at offset
    dp = (ξ − ½)S from the cell's centre; c(d) = h (dp − d)/(ξS) left of it and
    h (d − dp)/((1 − ξ)S) right of it (docs/physics.md, "Floors").  Curvature 0 on the flanks;
    the peak is a convex kink of the gap (G' only jumps up across it, so the Taylor bounds from
    either end still hold), the valleys are concave kinks at the cell edges, where the flights
    are split.  At the peak itself the slope is taken as 0 (the lower one-sided value, which
    keeps a Taylor bound from a point at the peak a lower bound)."""

    def __init__(self, depth: float, peak: float, S: float) -> None:
        self.h, self.dp = depth, (peak - 0.5) * S
        self.kl, self.kr = depth / (peak * S), depth / ((1.0 - peak) * S)

    def depth(self, d):
        d = np.asarray(d, float)
        return np.where(d < self.dp, self.kl * (self.dp - d), self.kr * (d - self.dp))

    def slope(self, d):
        d = np.asarray(d, float)
        return np.where(d < self.dp, -self.kl, np.where(d > self.dp, self.kr, 0.0))

    def curvature(self, d):
        return np.zeros_like(np.asarray(d, float))

    def normal(self, d):
        c1 = self.slope(d)
        r = np.sqrt(1.0 + c1 * c1)
        return c1 / r, 1.0 / r

    def height_error(self, d, dx):
        return max(self.kl, self.kr) * np.asarray(dx, float) + 0.0 * np.asarray(d, float)

    def normal_error(self, dx, d=None):
        """0 on a flank; within dx of the peak either flank's normal (or the peak's) may be
        the kernel's: a jump of at most 2 (no d given: that bound everywhere)."""
        if d is None:
            return 2.0 + 0.0 * dx
        return np.where(np.abs(np.asarray(d, float) - self.dp) <= dx, 2.0, 0.0)

    @property
    def scale(self):
        return self.h

    def depth_min(self, da, db, ca, cb):
        return np.where((da - self.dp) * (db - self.dp) <= 0, 0.0, np.minimum(ca, cb))

    def curvature_min(self, da, db):
        return np.zeros_like(np.asarray(da, float))

    def pull(self, d, dx):
        """The peak's kink within dx of d: an unbounded pull (inf), else the flank's 0."""
        return np.where(np.abs(np.asarray(d, float) - self.dp) <= dx, np.inf, 0.0)


class FlatProfile:
    """A flat floor (R = inf): no depth, the normal straight up."""

    def q(self, d):
        return np.full_like(np.asarray(d, float), np.inf)

    def depth(self, d):
        return np.zeros_like(d)

    slope = curvature = depth

    def normal(self, d):
        return np.zeros_like(d), np.ones_like(d)

    def height_error(self, d, dx):
        return np.zeros_like(d)

    def normal_error(self, dx, d=None):
        return 0.0 * dx

    scale = 0.0

    def depth_min(self, da, db, ca, cb):
        return np.zeros_like(np.asarray(da, float))

    def curvature_min(self, da, db):
        return np.zeros_like(np.asarray(da, float))

    def pull(self, d, dx):
        return np.zeros_like(np.asarray(d, float))
