"""The kernel's options as three small records, so that :func:`bbb.dynamics.evolve.evolve`
takes a handful of arguments instead of 27: the floor, the run, and the conveyor's frame.

``Frame`` or None selects the floor at compile time: with ``frame = None`` numba prunes
every conveyor branch (``if frame is None``), as ``friction = None`` prunes the contact
models, so the paper's floor compiles to its own code with the paper's exact expressions.
"""

from __future__ import annotations

import math
from collections import namedtuple

from numba import njit

#: the paper's floor (Sec. 2): gravity g (mm/s²), amplitude A (mm), angular frequency w
#: (rad/s), arc radius R and spacing S (mm), restitution alpha, beta (Eqs. 5-6)
Floor = namedtuple("Floor", "g A w R S alpha beta")
#: one run: t_max (s), recording from rec_from (s), root tolerance tol_t (s), sticking speed
#: v_stick (mm/s), longest search step h_max_periods (floor periods)
Run = namedtuple("Run", "t_max rec_from tol_t v_stick h_max_periods")
#: a conveyor (bbb.dynamics.bounds_conveyor's module doc): gravity (−gx, −gy) (mm/s²) and floor
#: amplitudes (Ax, Ay) (mm) along and normal to the floor's plane
Frame = namedtuple("Frame", "gx gy Ax Ay")


@njit(cache=True)
def conveyor_frame(g, A, tilt, throw):
    """(gx, gy, Ax, Ay) of a floor tilted by ``tilt`` and thrown at ``throw`` (degrees)."""
    gx = g * math.sin(math.radians(tilt))
    gy = g * math.cos(math.radians(tilt))
    # from ψ − 90° so that ψ → 180° − ψ flips Ax's sign bit-exactly and ψ = 90 gives Ay = A
    dev = math.radians(throw - 90.0)
    return gx, gy, -A * math.sin(dev), A * math.cos(dev)


def frame_of(g: float, A: float, tilt: float, throw: float) -> Frame:
    """The conveyor's Frame, computed by the jitted arithmetic the kernel always used."""
    return Frame(*conveyor_frame(g, A, tilt, throw))
