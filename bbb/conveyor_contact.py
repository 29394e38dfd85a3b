"""Former home of the conveyor's contact step, now :mod:`bbb.dynamics.contact_conveyor`: a thin
re-export kept for one release (docs/design.md lists the old paths)."""

from __future__ import annotations

from .dynamics.collide import collide_c
from .dynamics.contact_conveyor import (
    DONE,
    HELD,
    NEXT,
    STALLED,
    TWO_PI,
    above,
    contact_c,
    cut,
    enter_contact_c,
    enter_wait,
    exit_wait,
    forces_at_rest,
    hold_interval,
    slip_wait_c,
    wall_slip,
)

__all__ = ["DONE", "HELD", "NEXT", "STALLED", "TWO_PI", "above", "collide_c", "contact_c", "cut",
           "enter_contact_c", "enter_wait", "exit_wait", "forces_at_rest", "hold_interval",
           "slip_wait_c", "wall_slip"]
