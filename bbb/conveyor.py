"""Former home of the conveyor's map, now :mod:`bbb.dynamics` (one ``evolve`` for both floors,
the conveyor selected by its Frame): a thin re-export kept for one release (docs/design.md
lists the old paths); ``evolve_c``/``evolve_ensemble_c`` keep their old positional signatures."""

from __future__ import annotations

from numba import njit

from .dynamics.collide import wall_met
from .dynamics.evolve import evolve as _evolve
from .dynamics.evolve import evolve_ensemble as _evolve_ensemble
from .dynamics.liftoff import letgo_delay, liftoff_wait_c, liftoff_wait_cusp, normal_load
from .dynamics.options import Floor, Frame, Run, conveyor_frame

__all__ = ["evolve_c", "evolve_ensemble_c", "letgo_delay", "liftoff_wait_c", "liftoff_wait_cusp",
           "normal_load", "wall_met"]


@njit(cache=True)
def evolve_c(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta, tilt,
             throw, t_max, sample_times, pos, rec_from, rec, tol_t, v_stick, h_max_periods,
             stack, counters, friction, times, status):
    """bbb.dynamics.evolve.evolve on the conveyor, with the old positional arguments."""
    gx, gy, Ax, Ay = conveyor_frame(g, A, tilt, throw)
    _evolve(cell, d, y, vx, vy, s, stuck, from_surface, Floor(g, A, w, R, S, alpha, beta),
            Run(t_max, rec_from, tol_t, v_stick, h_max_periods), Frame(gx, gy, Ax, Ay),
            friction, sample_times, (pos, rec, counters, times, status), stack)


@njit(cache=True)
def evolve_ensemble_c(cell, d, y, vx, vy, s, stuck, from_surface, g, A, w, R, S, alpha, beta,
                      tilt, throw, t_max, sample_times, pos, rec_from, rec, tol_t, v_stick,
                      h_max_periods, counters, friction, times, status):
    """bbb.dynamics.evolve.evolve_ensemble on the conveyor, old positional arguments."""
    gx, gy, Ax, Ay = conveyor_frame(g, A, tilt, throw)
    _evolve_ensemble(cell, d, y, vx, vy, s, stuck, from_surface, Floor(g, A, w, R, S, alpha, beta),
                     Run(t_max, rec_from, tol_t, v_stick, h_max_periods), Frame(gx, gy, Ax, Ay),
                     friction, sample_times,
                     (pos, rec, counters, times, status))
