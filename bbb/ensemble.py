"""Initial-condition families, drawn deterministically from a ``numpy.random.SeedSequence``.

- ``rest``:     on the surface at uniform random x and floor phase, at rest relative to
                the floor (stuck): it leaves only if the floor accelerates down faster
                than g, i.e. never below Γ = 1.
- ``dropped``:  released with zero velocity from a uniform random height (mm) in
                ``drop_height`` above the surface, at uniform random x and phase.
- ``launched``: leaving the surface vertically at uniform random x and phase, with an
                upward speed relative to the floor uniform in ``launch_speed`` (mm/s).

Mirror images and pairs: the image of a state is its reflection x → −x (d → −d, vx → −vx,
cell → −cell; :func:`mirrored`).  On a mirror-symmetric floor (no tilt, vertical throw) the
image's trajectory is the reflection of the particle's, bit for bit, so an estimator can count
images without simulating them.  Elsewhere :func:`mirror_pairs` draws half an ensemble and
appends each state's partner -- the same draw at −d, a member of the same family -- for
antithetic estimates of odd quantities such as the drift (:func:`mirror_pair_units` labels the
pairs of a store's chunk layout).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .params import Params
from .surface import depth

__all__ = ["FAMILIES", "InitialState", "initial_state", "mirrored", "mirror_pairs",
           "mirror_pair_units"]

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
        # a thrown floor (bbb.dynamics, the conveyor): d is the offset relative to the floor, which moves
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


def mirrored(state: InitialState) -> InitialState:
    """The mirror image x → −x of every state: d → −d, vx → −vx, cell → −cell (y, vy, s and
    the flags unchanged).  On the paper's floor (level, vertical throw; any contact model)
    bbb.simulate of the images gives the negated positions, collision x and vx, and the same
    counters and contact times, bit for bit (tests/bbb/test_ensemble.py)."""
    return replace(state, cell=-state.cell, d=-state.d, vx=-state.vx)


def mirror_pairs(p: Params, n: int, seed: np.random.SeedSequence, family: str,
                 **kw) -> InitialState:
    """``n`` (even) states: ``n/2`` drawn from ``seed`` as :func:`initial_state` draws them,
    followed by their partners in the same order.  A partner is the same draw at −d (cell
    −cell, everything else equal): a member of the same family.  Where every family starts
    with vx = 0 (a floor vibrated normal to its plane) it is the mirror image
    (:func:`mirrored`); on an obliquely thrown floor 'rest' and 'launched' start with the
    floor's sideways velocity, which the partner keeps (the reflected −vx would start a
    particle sliding against the floor: another ensemble, so a biased pair mean)."""
    if n % 2 or n < 2:
        raise ValueError(f"mirror pairs need an even number of particles ≥ 2, got {n}")
    half = initial_state(p, n // 2, seed, family, **kw)
    partner = replace(half, cell=-half.cell, d=-half.d)
    return InitialState(**{k: np.concatenate([getattr(half, k), getattr(partner, k)])
                           for k in half.__dataclass_fields__})


def mirror_pair_units(n: int, chunk_size: int) -> np.ndarray:
    """Pair labels (int64, shape (n,)) of ``n`` particles stored in chunks of ``chunk_size``
    made by :func:`mirror_pairs`: particle k and k + chunk_size/2 of a chunk share a label."""
    if chunk_size % 2 or n % chunk_size:
        raise ValueError(f"{n} particles in chunks of {chunk_size}: need an even chunk size "
                         "that divides the number of particles")
    k = np.arange(n)
    half = chunk_size // 2
    return (k // chunk_size) * half + k % half
