"""`bbb.simulate`: run an ensemble through the collision map, recording only what is asked."""

from __future__ import annotations

import math

import numpy as np

from .dynamics.events import (
    EVENT_BUDGET,
    EVENT_WINDOW,
    SEARCH_BURST,
    SEARCH_RATE,
    STOP_EVENTS,
    STOP_OK,
    STOP_SEARCH,
)
from .dynamics.evolve import evolve_ensemble
from .dynamics.options import Floor, Run, frame_of
from .dynamics.slide import PAYBACK, STRETCH_BUDGET
from .ensemble import InitialState, initial_state
from .numerics import Numerics
from .params import Params, real
from .record import COLLISION_FIELDS, CONTACT_TIME_NAMES, COUNTER_NAMES, EVENT_FIELDS, SimRun
from .surface import shape_of

__all__ = ["MAX_PERIODS", "simulate"]

#: the longest run, in floor periods (t_max · f): the run's clock tp/f + s then resolves
#: ~1e-4 of a period, and the search budget (SEARCH_RATE per period) stays within int64
MAX_PERIODS = 1e12
#: columns of a particle's guard status row (bbb.dynamics.events)
GUARD_COLUMNS = 5


def simulate(
    params: Params,
    n_particles: int,
    t_max: float,
    seed: int | np.random.SeedSequence,
    initial: str | InitialState = "rest",
    *,
    sample_times: np.ndarray | None = None,
    record_collisions: int = 0,
    record_from: float = 0.0,
    record_liftoffs: bool = False,
    numerics: Numerics | None = None,
    drop_height: tuple[float, float] = (0.0, 2.0),
    launch_speed: tuple[float, float] = (0.0, 200.0),
    _force_conveyor: bool = False,
    _guards: np.ndarray | None = None,
) -> SimRun:
    """Evolve ``n_particles`` independent particles for ``t_max`` seconds.

    sample_times      -- sorted times (s) in [0, t_max] at which x (mm) is recorded.
    record_collisions -- per particle, how many post-collision states to keep, counted
                         from the first collision at t ≥ ``record_from`` (s).
    record_liftoffs   -- also record each lift-off that starts a flight (a row with the state
                         leaving the floor, column ``event`` = 1); the rows then count
                         collisions and lift-offs together.
    initial           -- a family name (see ``bbb.ensemble``) or an explicit InitialState.
    seed              -- int or SeedSequence; the same seed gives bit-identical output.
    A floor with ``tilt`` or ``throw`` (bbb.Params) runs the conveyor's kernel (bbb.dynamics); positions and
    recorded x are then along the floor's plane in the lab (x = cell·S + d + X_f(t)).
    ``_force_conveyor`` runs that kernel on the paper's floor too (tests compare the two);
    ``_guards`` (an array (n_particles, 5)) receives the guards' status rows (bbb.dynamics.events:
    why each particle stopped, its peak step debt, its most events in one window, when, its
    deepest draw on the search budget) — benchmarks/calibrations/guards.py measures the budgets' margins
    with it.
    Memory is O(n_particles × (n_samples + record_collisions)), never O(collisions).

    Inputs are checked first (ValueError, one line naming the argument): ``t_max`` finite,
    > 0 and at most MAX_PERIODS = 1e12 floor periods; an explicit InitialState within its
    floor (:meth:`bbb.ensemble.InitialState.check`: in its cell, on or above the surface,
    below the speed cap); numbers may be numpy scalars, never bools.

    No input loops without end: a particle whose contact stretch takes more than
    ``bbb.dynamics.slide.STRETCH_BUDGET`` steps beyond ``PAYBACK`` per nominal step of the time it
    covers, that has more than ``bbb.dynamics.events.EVENT_BUDGET`` events within
    ``EVENT_WINDOW`` floor periods, or that takes more collision-search steps than
    ``SEARCH_BURST`` plus ``SEARCH_RATE`` per floor period of its simulated time, stops the run
    with a RuntimeError naming the parameters, the seed and the particle.
    """
    if not isinstance(params, Params):
        raise ValueError(f"params must be a bbb.Params, got {type(params).__name__}")
    numerics = Numerics() if numerics is None else numerics
    if not isinstance(numerics, Numerics):
        raise ValueError(f"numerics must be a bbb.Numerics, got {type(numerics).__name__}")
    n_particles = _count("n_particles", n_particles)
    record_collisions = _count("record_collisions", record_collisions)
    t_max = real("simulate", "t_max", t_max)
    if not (math.isfinite(t_max) and 0 < t_max <= MAX_PERIODS / params.f):
        raise ValueError(f"t_max = {t_max!r} is out of range; allowed: 0 < t_max ≤ "
                         f"{MAX_PERIODS:g} floor periods = {MAX_PERIODS / params.f:.6g} s")
    record_from = real("simulate", "record_from", record_from)
    if not (math.isfinite(record_from) and record_from >= 0):
        raise ValueError(f"record_from = {record_from!r} is out of range; allowed: finite, ≥ 0 (s)")
    if sample_times is None:
        times = np.zeros(0)
    else:
        times = np.asarray(sample_times, dtype=np.float64)
        if times.ndim != 1:
            raise ValueError("sample_times must be one-dimensional")
        if times.size and not np.all(np.isfinite(times)):
            raise ValueError("sample_times must be finite")
        if times.size and (np.any(np.diff(times) < 0) or times[0] < 0 or times[-1] > t_max):
            raise ValueError(f"sample_times must be sorted and lie within [0, t_max = {t_max:g}] s")
    if not isinstance(seed, np.random.SeedSequence):
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise ValueError(f"seed must be a non-negative int or a SeedSequence, got {seed!r}")
        seed = np.random.SeedSequence(int(seed))

    if isinstance(initial, InitialState):
        st = initial
        if st.cell.shape != (n_particles,):
            raise ValueError(f"initial state holds {st.cell.shape} particles, n_particles = {n_particles}")
        initial = "custom"
    elif not isinstance(initial, str):
        raise ValueError(f"initial must be a family name or a bbb.InitialState, got "
                         f"{type(initial).__name__}")
    else:
        st = initial_state(params, n_particles, seed, initial,
                           drop_height=drop_height, launch_speed=launch_speed)
    st.check(params)
    pos = np.full((n_particles, times.size), np.nan)
    if not isinstance(record_liftoffs, bool):
        raise ValueError(f"record_liftoffs must be True or False, got {record_liftoffs!r}")
    fields = EVENT_FIELDS if record_liftoffs else COLLISION_FIELDS
    rec = np.full((n_particles, record_collisions, len(fields)), np.nan)
    counters = np.zeros((n_particles, len(COUNTER_NAMES)), dtype=np.int64)
    held = np.zeros((n_particles, len(CONTACT_TIME_NAMES)))
    status = np.zeros((n_particles, GUARD_COLUMNS)) if _guards is None else _guards
    if status.shape != (n_particles, GUARD_COLUMNS) or status.dtype != np.float64:
        raise ValueError(f"_guards must be a float64 array of shape ({n_particles}, {GUARD_COLUMNS})")
    status[:] = 0.0
    p = params
    # a tilted or thrown floor runs the conveyor's compiled kernel (frame), the paper's floor
    # its own (frame None: numba prunes the conveyor's branches)
    frame = frame_of(p.g, p.A, p.tilt, p.throw) if p.transport or _force_conveyor else None
    evolve_ensemble((st.cell, st.d, st.y, st.vx, st.vy, st.s, st.stuck, st.from_surface),
                    Floor(float(p.g), float(p.A), float(p.omega), shape_of(p), float(p.S),
                          float(p.alpha), float(p.beta)),
                    Run(float(t_max), float(record_from), numerics.tol_t, numerics.v_stick,
                        numerics.max_step), frame, None if p.contact == "stick" else p.mu,
                    times, (pos, rec, counters, held, status))
    _raise_on_guard(status, params, numerics, seed, initial)
    contact_time = {name: held[:, i].copy() for i, name in enumerate(CONTACT_TIME_NAMES)}
    return SimRun(
        params=params,
        numerics=numerics,
        initial=initial,
        t_max=float(t_max),
        sample_times=times if sample_times is not None else None,
        positions=pos if sample_times is not None else None,
        collisions_dense=rec if record_collisions > 0 else None,
        n_recorded=counters[:, 3].copy(),
        counters={name: counters[:, i].copy() for i, name in enumerate(COUNTER_NAMES)},
        liftoffs=record_liftoffs,
        contact_time=contact_time,
    )


def _raise_on_guard(status: np.ndarray, p: Params, numerics: Numerics,
                    seed: np.random.SeedSequence, initial: str) -> None:
    """The kernel's guards (bbb.dynamics.slide's step budget, bbb.dynamics.events' event and
    search budgets) stop a particle with a flag the jitted code cannot put into words: here it
    becomes one error."""
    stopped = np.nonzero(status[:, 0] != STOP_OK)[0]
    if not stopped.size:
        return
    i = int(stopped[0])
    if status[i, 0] == STOP_EVENTS:
        what = (f"more than {EVENT_BUDGET} events within {EVENT_WINDOW:g} floor period "
                "(a sequence of events that makes no progress in time)")
    elif status[i, 0] == STOP_SEARCH:
        what = (f"its collision searches took more than {SEARCH_BURST} steps beyond "
                f"{SEARCH_RATE} per floor period of simulated time (a search that makes no "
                "progress in time)")
    else:
        what = (f"a contact stretch ran a step debt above {STRETCH_BUDGET:g} (integration "
                f"steps tried beyond {PAYBACK:g} per nominal step of the time covered)")
    raise RuntimeError(
        f"bbb.simulate: the kernel's guard stopped particle {i} of {status.shape[0]} at "
        f"t = {status[i, 3]:.17g} s: {what}; it would loop without end.  Parameters: "
        f"{p.as_dict() | {'tilt': p.tilt, 'throw': p.throw, 'contact': p.contact, 'mu': p.mu}}, "
        f"numerics {numerics.as_dict()}, initial {initial!r}, seed entropy {seed.entropy} "
        f"spawn_key {seed.spawn_key}.  Please report these parameters.")


def _count(name: str, value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
        raise ValueError(f"{name} = {value!r} is out of range; allowed: an integer ≥ 0")
    return int(value)
