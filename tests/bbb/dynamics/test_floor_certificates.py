"""What each floor shape's module provides (bbb.dynamics.floors) holds against the shape written
here from its definition: depth and slope are the profile and its derivative, and the
certificates the collision search proves with bound the profile over intervals inside one cell
(curvature_max above c'', depth_min below c, concavity below −c'').  The kernel computes some
of them from others (the sine's slope from the depth's half angle, its curvature bound from
the depths at the interval's ends); this checks them against finite differences of the
profile, which shares none of that code."""

import numpy as np
import pytest
from numba import njit

from bbb import Params
from bbb.dynamics.floors import concavity, curvature_max, depth, depth_min, slope
from bbb.surface import shape_of

from .test_floors import profile

SHAPES = {
    "arc": {"R": 15.0},
    "arc R = S/2": {"R": 1.0},
    "sine": {"floor": "sine", "depth": 0.3},
    "deep sine": {"floor": "sine", "depth": 1.5},
    "sawtooth": {"floor": "sawtooth", "depth": 0.3, "peak": 0.3},
}
#: finite-difference step (mm) and the relative slack of a bound against sampled values
H = 1e-4
SLACK = 1e-6


@njit
def certificates(sh, da, db):
    # (curvature_max, depth_min) over [da, db] from the ends' depths, as the search calls them
    ca, cb = depth(sh, da), depth(sh, db)
    return curvature_max(sh, da, db, ca, cb), depth_min(sh, da, db, ca, cb)


@njit
def depth_slope(sh, d):
    return depth(sh, d), slope(sh, d)


@njit
def concavity_of(sh):
    return concavity(sh)


def _case(name):
    p = Params.preset("klages2004", f=60.0, **SHAPES[name])
    return p, shape_of(p)


def _intervals(p, n=400, seed=5):
    # random [da, db] inside one cell, short and long, some holding the cell's top
    rng = np.random.default_rng(seed)
    half = 0.5 * p.S * (1.0 - 1e-3)   # off the cusp, where an arc R = S/2 is vertical
    a = rng.uniform(-half, half, n)
    w = 10.0 ** rng.uniform(-3.0, np.log10(2 * half), n)
    b = np.clip(a + w * rng.choice([-1.0, 1.0], n), -half, half)
    return np.minimum(a, b), np.maximum(a, b)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_depth_and_slope_are_the_profile_and_its_derivative(name):
    p, sh = _case(name)
    d = np.linspace(-0.49 * p.S, 0.49 * p.S, 197)
    if p.floor == "sawtooth":
        top = (p.peak - 0.5) * p.S
        d = d[np.abs(d - top) > 2 * H]   # the peak's kink has no derivative
    got = np.array([depth_slope(sh, x) for x in d])
    # fourth-order central difference: a steep arc near its cusp has a large c'''
    fd = (8 * (profile(p, d + H) - profile(p, d - H))
          - (profile(p, d + 2 * H) - profile(p, d - 2 * H))) / (12 * H)
    # the profile here is R − √(R² − d²), with its cancellation near the top: 1e-13 mm
    assert np.allclose(got[:, 0], profile(p, d), rtol=1e-12, atol=1e-13)
    assert np.allclose(got[:, 1], fd, rtol=1e-7, atol=1e-8)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_the_certificates_bound_the_profile_over_every_interval(name):
    p, sh = _case(name)
    kappa = concavity_of(sh)
    for da, db in zip(*_intervals(p), strict=True):
        cmax, cmin = certificates(sh, da, db)
        x = np.linspace(da, db, 41)
        c = profile(p, x)
        assert cmin <= c.min() + SLACK * (1.0 + abs(c.min())), (da, db)
        inner = x[(x - H > da) & (x + H < db)]
        if inner.size == 0:
            continue
        c2 = (profile(p, inner + H) - 2 * profile(p, inner) + profile(p, inner - H)) / H**2
        tol = 1e-4 * (1.0 + np.abs(c2).max())
        assert cmax >= c2.max() - tol, (da, db, cmax, c2.max())
        assert c2.min() >= -kappa - tol, (da, db)
