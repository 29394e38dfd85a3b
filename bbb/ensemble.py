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

import math
from dataclasses import dataclass, fields, replace

import numpy as np

from .params import Params, real
from .surface import floor_depth

__all__ = ["CELL_MAX", "FAMILIES", "InitialState", "SPEED_CAP_FACTOR", "initial_state",
           "lattice_state", "mirrored", "mirror_pairs", "mirror_pair_units", "speed_cap"]

FAMILIES = ("rest", "dropped", "launched")

#: the speed cap of an initial state is this multiple of the floor's own speed scales
#: (:func:`speed_cap`): far above any start the project uses (launches ≤ 400 mm/s, drops ≤
#: 10 mm on the paper's floor), low enough that a flight's length in cells and periods stays
#: bounded by the floor's parameters (benchmarks/calibrations/guards.py runs starts at the caps)
SPEED_CAP_FACTOR = 100.0
#: the largest |cell| of an initial state: x = cell·S + d keeps d's precision (2⁴⁰ ≈ 1.1e12)
CELL_MAX = 2**40
#: a state counts as on or above the surface down to this depth below it, relative to the
#: floor's size (1 + A + S mm): the rounding of a surface height computed another way
ON_SURFACE_TOL = 1e-9
_FLOATS = ("d", "y", "vx", "vy", "s")
_FLAGS = ("stuck", "from_surface")


def speed_cap(p: Params) -> float:
    """The largest speed (mm/s) an initial state may have: SPEED_CAP_FACTOR × (A·2πf + √(g·S)),
    a multiple of the floor's peak velocity and of the speed of a fall through one cell
    width.  A state's height above the surface is capped likewise at speed_cap²/(2g), the
    height a particle at the cap would rise to."""
    return SPEED_CAP_FACTOR * (p.A * p.omega + math.sqrt(p.g * p.S))


@dataclass(frozen=True)
class InitialState:
    """Arrays (n_particles,) of initial states: x = cell·S + d (mm), y (mm), v (mm/s),
    floor time s (s) within [0, 1/f), and flags.  On a thrown floor (Params.throw ≠ 90) d is
    the offset relative to the floor, whose sideways displacement X_f(s) adds to x.

    On construction each field becomes a 1-d numpy array of one length (cell int64 with
    |cell| ≤ CELL_MAX, flags bool, the rest float64) and every value must be finite: else a
    ValueError naming the field and the first bad particle.  :meth:`check` holds the states
    to a floor (bbb.simulate calls it): |d| ≤ S/2, 0 ≤ s < 1/f, on or above the surface, speed
    at most :func:`speed_cap` and height above the surface at most speed_cap²/(2g)."""

    cell: np.ndarray
    d: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    s: np.ndarray
    stuck: np.ndarray
    from_surface: np.ndarray

    def __post_init__(self) -> None:
        n = None
        for fl in fields(self):
            value = getattr(self, fl.name)
            arr = np.asarray(value) if isinstance(value, (np.ndarray, list, tuple)) else None
            kinds = "iu" if fl.name == "cell" else "b" if fl.name in _FLAGS else "iuf"
            if arr is None or arr.ndim != 1 or arr.dtype.kind not in kinds:
                what = ("integers" if fl.name == "cell" else "bools" if fl.name in _FLAGS
                        else "real numbers")
                got = (f"{arr.ndim}-d {arr.dtype}" if arr is not None
                       else type(value).__name__)
                raise ValueError(f"InitialState.{fl.name} must be a 1-d array of {what}, "
                                 f"got {got}")
            if n is not None and arr.shape[0] != n:
                raise ValueError(f"InitialState.{fl.name} holds {arr.shape[0]} particles, "
                                 f"InitialState.cell {n}; allowed: one length for every field")
            n = arr.shape[0]
            dtype = np.int64 if fl.name == "cell" else bool if fl.name in _FLAGS else np.float64
            if fl.name == "cell" and arr.size and np.any(np.abs(arr.astype(np.float64)) > CELL_MAX):
                _refuse("cell", arr, np.abs(arr.astype(np.float64)) > CELL_MAX,
                        f"|cell| ≤ {CELL_MAX} (2**40)")
            arr = arr.astype(dtype, copy=False)
            if fl.name in _FLOATS and not np.all(np.isfinite(arr)):
                _refuse(fl.name, arr, ~np.isfinite(arr), "finite")
            object.__setattr__(self, fl.name, arr)

    @property
    def n(self) -> int:
        """The number of particles."""
        return int(self.cell.shape[0])

    def check(self, p: Params) -> None:
        """Refuse (ValueError naming the field, the first bad particle, its value and what
        is allowed) a state outside its cell (|d| ≤ S/2), outside the floor period
        (0 ≤ s < 1/f), below the surface, faster than :func:`speed_cap` or higher above the
        surface than speed_cap²/(2g) (g along the floor's normal on a tilted floor)."""
        _refuse_where("d", self.d, np.abs(self.d) > 0.5 * p.S, f"|d| ≤ S/2 = {0.5 * p.S:g} (mm)")
        period = 1.0 / p.f
        _refuse_where("s", self.s, (self.s < 0.0) | (self.s >= period),
                      f"0 ≤ s < 1/f = {period:.17g} (s)")
        gx, gy, _ax, ay = p.floor_frame() if p.transport else (0.0, p.g, 0.0, p.A)
        surface = -ay * np.sin(p.omega * self.s) - floor_depth(p, self.d)
        height = self.y - surface
        tol = ON_SURFACE_TOL * (1.0 + p.A + p.S)
        _refuse_where("y", self.y, height < -tol, "on or above the surface, -A sin(2πfs) - "
                      f"c(d) (mm, to {tol:.3g} mm)")
        cap = speed_cap(p)
        _refuse_where("y", self.y, height > cap**2 / (2.0 * gy),
                      f"at most speed_cap²/(2g) = {cap**2 / (2.0 * gy):.6g} mm above the surface")
        speed = np.hypot(self.vx, self.vy)
        _refuse_where("vx, vy", speed, speed > cap,
                      f"speed √(vx² + vy²) ≤ speed_cap = {cap:.6g} mm/s "
                      f"({SPEED_CAP_FACTOR:g} × (A·2πf + √(g·S)))", "speed")


def _refuse_where(name: str, values: np.ndarray, bad: np.ndarray, allowed: str,
                  what: str = "") -> None:
    if np.any(bad):
        _refuse(name, values, bad, allowed, what)


def _refuse(name: str, values: np.ndarray, bad: np.ndarray, allowed: str, what: str = "") -> None:
    # one line: the field, the first bad particle, its value, how many, what is allowed
    i = int(np.argmax(bad))
    v = values[i].item()
    raise ValueError(f"InitialState.{name} of particle {i}: {what + ' ' if what else ''}{v!r} is out "
                     f"of range ({int(np.count_nonzero(bad))} of {values.shape[0]} particles); "
                     f"allowed: {allowed}")


def _range(name: str, value: tuple[float, float], hi_max: float, unit: str,
           cap: str) -> tuple[float, float]:
    # a family's (low, high): two real numbers, 0 ≤ low ≤ high ≤ hi_max
    try:
        lo, hi = (real("simulate", name, v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (low, high) of real numbers, got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo <= hi <= hi_max):
        raise ValueError(f"{name} = {value!r} is out of range; allowed: 0 ≤ low ≤ high ≤ "
                         f"{hi_max:.6g} ({unit}; {cap})")
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
    """Draw ``n`` initial states of ``family`` from ``seed``.  ``drop_height`` (mm) and
    ``launch_speed`` (mm/s, relative to the floor) lie within 0 and the caps of
    :meth:`InitialState.check`: speed_cap²/(2g) and speed_cap − A·2πf."""
    if family not in FAMILIES:
        raise ValueError(f"unknown initial family {family!r}; allowed: {', '.join(FAMILIES)}")
    rng = np.random.Generator(np.random.PCG64(seed))
    period = 1.0 / p.f
    d = rng.uniform(-0.5 * p.S, 0.5 * p.S, n)
    s = rng.uniform(0.0, period, n)
    surface = -p.A * np.sin(p.omega * s) - floor_depth(p, d)
    floor_v = -p.A * p.omega * np.cos(p.omega * s)
    cell = np.zeros(n, dtype=np.int64)
    vx = np.zeros(n)
    if p.transport:
        # a thrown floor (bbb.dynamics, the conveyor): d is the offset relative to the floor, which moves
        # (Ax, Ay)(−sin 2πft); 'rest' and 'launched' start with its along-plane velocity
        _gx, _gy, ax, ay = p.floor_frame()
        surface = -ay * np.sin(p.omega * s) - floor_depth(p, d)
        floor_v = -ay * p.omega * np.cos(p.omega * s)
        if family != "dropped":
            vx = -ax * p.omega * np.cos(p.omega * s)
    if family == "rest":
        return InitialState(cell, d, surface, vx, floor_v.copy(), s,
                            np.ones(n, bool), np.ones(n, bool))
    if family == "dropped":
        cap = speed_cap(p)
        lo, hi = _range("drop_height", drop_height, cap**2 / (2.0 * p.floor_frame()[1]), "mm",
                        "the height a particle at speed_cap rises to")
        h = rng.uniform(lo, hi, n)
        return InitialState(cell, d, surface + h, vx, np.zeros(n), s,
                            np.zeros(n, bool), h == 0.0)
    lo, hi = _range("launch_speed", launch_speed, speed_cap(p) - p.A * p.omega, "mm/s",
                    "speed_cap less the floor's peak speed")
    # (0, hi]: a launch speed of exactly 0 would be a particle at rest, not launched
    u = hi - rng.uniform(0.0, hi - lo, n)
    return InitialState(cell, d, surface, vx, floor_v + u, s, np.zeros(n, bool), np.ones(n, bool))


def lattice_state(p: Params, family: str, index: np.ndarray, shape: tuple[int, int],
                  offset: float, *, drop_height: tuple[float, float] = (0.0, 2.0),
                  launch_speed: tuple[float, float] = (0.0, 200.0)) -> InitialState:
    """The states of a grid of initial conditions (no randomness): particle ``index`` (int,
    0 ≤ index < n_phase·n_value, ``shape`` = (n_phase, n_value)) sits at row i = index //
    n_value, column j = index % n_value: floor time s = (i + ½)/n_phase of a period and, for
    ``dropped``, a release height lo + (j + ½)(hi − lo)/n_value (mm) in ``drop_height``, for
    ``launched`` an upward launch speed in ``launch_speed`` likewise (mm/s, relative to the
    floor), all at the offset ``offset`` (mm, |offset| ≤ S/2) in cell 0.  The level floor
    vibrated vertically only (a grid of a basin of attraction: every cell's centre)."""
    if family not in ("dropped", "launched"):
        raise ValueError(f"a lattice of initial states is 'dropped' or 'launched', got {family!r}")
    if p.transport:
        raise ValueError("a lattice of initial states needs a level floor vibrated vertically "
                         "(tilt = 0, throw = 90)")
    n_phase, n_value = (int(v) for v in shape)
    index = np.asarray(index, dtype=np.int64)
    if n_phase < 1 or n_value < 1 or np.any((index < 0) | (index >= n_phase * n_value)):
        raise ValueError(f"lattice index out of range: shape {shape}, allowed 0 ≤ index < "
                         f"{n_phase * n_value}")
    if not abs(offset) <= 0.5 * p.S:
        raise ValueError(f"lattice offset = {offset!r} mm is out of range; allowed: |offset| ≤ "
                         f"S/2 = {0.5 * p.S:g} mm")
    n = index.size
    i, j = index // n_value, index % n_value
    s = (i + 0.5) / n_phase / p.f
    d = np.full(n, float(offset))
    surface = -p.A * np.sin(p.omega * s) - floor_depth(p, d)
    cell, vx = np.zeros(n, dtype=np.int64), np.zeros(n)
    if family == "dropped":
        cap = speed_cap(p)
        lo, hi = _range("drop_height", drop_height, cap**2 / (2.0 * p.g), "mm",
                        "the height a particle at speed_cap rises to")
        h = lo + (j + 0.5) * (hi - lo) / n_value
        return InitialState(cell, d, surface + h, vx, np.zeros(n), s, np.zeros(n, bool), h == 0.0)
    lo, hi = _range("launch_speed", launch_speed, speed_cap(p) - p.A * p.omega, "mm/s",
                    "speed_cap less the floor's peak speed")
    u = lo + (j + 0.5) * (hi - lo) / n_value
    floor_v = -p.A * p.omega * np.cos(p.omega * s)
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
