"""Former home of the paper floor's collision search, now :mod:`bbb.dynamics.search_level`: a thin
re-export kept for one release (docs/design.md lists the old paths)."""

from __future__ import annotations

from .dynamics.search_level import (
    NO_COLLISION,
    STACK_DEPTH,
    curvature_bound,
    gap,
    lower_bound,
    next_collision,
    refine_root,
    search_piece,
    start_step,
)

__all__ = ["NO_COLLISION", "STACK_DEPTH", "curvature_bound", "gap", "lower_bound",
           "next_collision", "refine_root", "search_piece", "start_step"]
