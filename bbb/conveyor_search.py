"""Former home of the conveyor's collision search, now :mod:`bbb.dynamics.search` (one driver
for both floors) and :mod:`bbb.dynamics.bounds_conveyor` (this floor's certificates): a thin
re-export kept for one release (docs/design.md lists the old paths).  ``next_collision_c``
keeps its old signature and returns τ."""

from __future__ import annotations

from numba import njit

from .dynamics.bounds_conveyor import (
    CUSP_REACH,
    cusp_side,
    gap_c,
    lower_bound_c,
    nearest,
    offset_range,
    round_half_away,
    start_step_arc,
    start_step_c,
    times_or_zero,
    upper_curvature,
)
from .dynamics.events import SEARCH_BURST
from .dynamics.options import Frame
from .dynamics.search import next_collision as _next_collision

__all__ = ["CUSP_REACH", "cusp_side", "gap_c", "lower_bound_c", "nearest", "next_collision_c",
           "offset_range", "round_half_away", "start_step_arc", "start_step_c", "times_or_zero",
           "upper_curvature"]


@njit(cache=True)
def next_collision_c(y, vy, vx, d0, s, from_surface, lifting, gx, gy, Ax, Ay, w, R, S,
                     tau_limit, tol_t, h_max, stack):
    """bbb.dynamics.search.next_collision on the conveyor, with a full step budget: τ only."""
    return _next_collision(y, vy, vx, d0, s, from_surface, lifting, 0.0, 0.0, w, R, S,
                           Frame(gx, gy, Ax, Ay), tau_limit, tol_t, h_max, stack, SEARCH_BURST)[0]
