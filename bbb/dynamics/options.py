"""The kernel's options and a contact step's state as small records, so that no jitted
function takes more than a handful of arguments: the floor, the run, the conveyor's frame,
and a particle in sustained contact with what its step did.

``Frame`` or None selects the floor at compile time: with ``frame = None`` numba prunes
every conveyor branch (``if frame is None``), as ``friction = None`` prunes the contact
models, so the paper's floor compiles to its own code with the paper's exact expressions.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import inlined, jitted

#: the paper's floor (Sec. 2): gravity g (mm/s²), amplitude A (mm), angular frequency w
#: (rad/s), arc radius R and spacing S (mm), restitution alpha, beta (Eqs. 5-6)
Floor = namedtuple("Floor", "g A w R S alpha beta")
#: one run: t_max (s), recording from rec_from (s), root tolerance tol_t (s), sticking speed
#: v_stick (mm/s), longest search step h_max_periods (floor periods)
Run = namedtuple("Run", "t_max rec_from tol_t v_stick h_max_periods")
#: a particle in sustained contact (bbb.dynamics.contact_step): its cell,
#: offset d (mm), height y (mm), velocity (vx, vy) (mm/s), floor time s (s) in its period
#: count tp, the next position sample isamp, held at rest (stuck) or sliding, the contact
#: angle q (rad; d on a flat floor), the tangential speed vt (mm/s) relative to the floor,
#: whether the last collision kicked, the rows recorded n_rec
Contact = namedtuple("Contact", "cell d y vx vy s tp isamp stuck sliding q vt kicked n_rec")
#: what a contact step did: collisions, sticking episodes, lift-offs, time slid (s), and the
#: stretch's peak step debt (bbb.dynamics.slide)
Tally = namedtuple("Tally", "collisions sticks lifts slid worst")
#: a conveyor (bbb.dynamics.bounds's module doc): gravity (−gx, −gy) (mm/s²) and floor
#: amplitudes (Ax, Ay) (mm) along and normal to the floor's plane
Frame = namedtuple("Frame", "gx gy Ax Ay")


@jitted
def conveyor_frame(g, A, tilt, throw):
    """(gx, gy, Ax, Ay) of a floor tilted by ``tilt`` and thrown at ``throw`` (degrees)."""
    gx = g * math.sin(math.radians(tilt))
    gy = g * math.cos(math.radians(tilt))
    # from ψ − 90° so that ψ → 180° − ψ flips Ax's sign bit-exactly and ψ = 90 gives Ay = A
    dev = math.radians(throw - 90.0)
    return gx, gy, -A * math.sin(dev), A * math.cos(dev)


@inlined
def heave(fl, frame):
    """(gravity (mm/s²), floor amplitude (mm)) normal to the floor's plane: the paper's (g, A)
    for frame None, the conveyor's (gy, Ay)."""
    if frame is None:
        return fl.g, fl.A
    return frame.gy, frame.Ay


def frame_of(g: float, A: float, tilt: float, throw: float) -> Frame:
    """The conveyor's Frame, computed by the jitted arithmetic the kernel always used."""
    return Frame(*conveyor_frame(g, A, tilt, throw))
