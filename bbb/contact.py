"""Former home of the contact phase's integrator, now :mod:`bbb.dynamics.slide`: a thin re-export
kept for one release (docs/design.md lists the old paths)."""

from __future__ import annotations

from .dynamics.contact_level import enter_contact, holds_at_rest
from .dynamics.slide import (
    BUDGET,
    CUSP,
    END,
    LIFT,
    MAX_ANGLE_STEP,
    PAYBACK,
    STEPS_PER_PERIOD,
    STEPS_PER_SWING,
    STOP,
    STRETCH_BUDGET,
    clear_of_cusp,
    g_eff,
    normal_force,
    rates,
    rk4,
    slide,
    step_bounds,
    tangential_force,
)

__all__ = ["BUDGET", "CUSP", "END", "LIFT", "MAX_ANGLE_STEP", "PAYBACK", "STEPS_PER_PERIOD",
           "STEPS_PER_SWING", "STOP", "STRETCH_BUDGET", "clear_of_cusp", "enter_contact", "g_eff",
           "holds_at_rest", "normal_force", "rates", "rk4", "slide", "step_bounds",
           "tangential_force"]
