"""Former home of the paper floor's map, now :mod:`bbb.dynamics`: a thin re-export kept for
one release (docs/design.md lists the old paths).  ``evolve``/``evolve_ensemble`` keep their
old positional signatures and run :func:`bbb.dynamics.evolve.evolve` with ``frame = None``."""

from __future__ import annotations

from numba import njit

from .dynamics.collide import collide
from .dynamics.events import (
    EV_COLLISION,
    EV_CONTACT,
    EV_CONTACT_LIFT,
    EV_CUSP,
    EV_STOP,
    EVENT_BUDGET,
    EVENT_WINDOW,
    STOP_EVENTS,
    STOP_OK,
    STOP_STEPS,
    count_event,
    put_row,
    wrap_period,
)
from .dynamics.evolve import evolve as _evolve
from .dynamics.evolve import evolve_ensemble as _evolve_ensemble
from .dynamics.liftoff import liftoff_wait
from .dynamics.options import Floor, Run

__all__ = ["EVENT_BUDGET", "EVENT_WINDOW", "EV_COLLISION", "EV_CONTACT", "EV_CONTACT_LIFT",
           "EV_CUSP", "EV_STOP", "STOP_EVENTS", "STOP_OK", "STOP_STEPS", "collide", "count_event",
           "evolve", "evolve_ensemble", "liftoff_wait", "put_row", "wrap_period"]


@njit(cache=True)
def evolve(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
           t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
           stack, counters, friction, times, status):
    """bbb.dynamics.evolve.evolve on the paper's floor, with the old positional arguments."""
    _evolve(cell, d, y, vx, vy, s, stuck, from_surface, Floor(g, A, w, R, S, alpha, beta),
            Run(t_max, rec_from, tol_t, v_stick, h_max_periods), None, friction, sample_times,
            (pos, rec, counters, times, status), stack)


@njit(cache=True)
def evolve_ensemble(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
                    t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
                    counters, friction, times, status):
    """bbb.dynamics.evolve.evolve_ensemble on the paper's floor, old positional arguments."""
    _evolve_ensemble(cell, d, y, vx, vy, s, stuck, from_surface, Floor(g, A, w, R, S, alpha, beta),
                     Run(t_max, rec_from, tol_t, v_stick, h_max_periods), None, friction,
                     sample_times, (pos, rec, counters, times, status))
