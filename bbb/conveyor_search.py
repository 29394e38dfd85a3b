"""Former home of the conveyor's collision search, now :mod:`bbb.dynamics.search_conveyor`: a thin
re-export kept for one release (docs/design.md lists the old paths)."""

from __future__ import annotations

from .dynamics.search_conveyor import (
    CUSP_REACH,
    cusp_side,
    gap_c,
    lower_bound_c,
    nearest,
    next_collision_c,
    offset_range,
    refine_root_c,
    round_half_away,
    search_c,
    start_step_arc,
    start_step_c,
    times_or_zero,
    upper_curvature,
)

__all__ = ["CUSP_REACH", "cusp_side", "gap_c", "lower_bound_c", "nearest", "next_collision_c",
           "offset_range", "refine_root_c", "round_half_away", "search_c", "start_step_arc",
           "start_step_c", "times_or_zero", "upper_curvature"]
