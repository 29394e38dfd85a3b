"""Former home of the paper floor's collision search, now :mod:`bbb.dynamics.search` (one
driver for both floors) and :mod:`bbb.dynamics.bounds_level` (this floor's certificates): a
thin re-export kept for one release (docs/design.md lists the old paths).  ``next_collision``
keeps its old signature (with a full step budget); ``search_piece`` and ``refine_root``
take the new driver's."""

from __future__ import annotations

from numba import njit

from .dynamics.bounds_level import curvature_bound, gap, lower_bound, start_step
from .dynamics.events import SEARCH_BURST
from .dynamics.search import NO_COLLISION, STACK_DEPTH, refine_root, search_piece
from .dynamics.search import next_collision as _next_collision

__all__ = ["NO_COLLISION", "STACK_DEPTH", "curvature_bound", "gap", "lower_bound",
           "next_collision", "refine_root", "search_piece", "start_step"]


@njit(cache=True)
def next_collision(y, vy, vx, d, s, from_surface, lifting, g, A, w, R, S, tau_limit, tol_t, h_max,
                   stack):
    """bbb.dynamics.search.next_collision on the paper's floor, with a full step budget: (τ, j)."""
    tau, j, _left = _next_collision(y, vy, vx, d, s, from_surface, lifting, g, A, w, R, S, None,
                                    tau_limit, tol_t, h_max, stack, SEARCH_BURST)
    return tau, j
