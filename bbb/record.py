"""What a run records: positions at sample times, post-collision states, counters."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .numerics import Numerics
from .params import Params

__all__ = ["COLLISION_FIELDS", "CONTACT_TIME_NAMES", "COUNTER_NAMES", "EVENT_CODES",
           "EVENT_FIELDS", "SimRun"]

#: columns of a recorded post-collision state: t (s, from the particle's start), x, y (mm),
#: vx, vy (mm/s), and the floor phase f·t_floor mod 1 at the collision (the surface there
#: is at -A sin(2π phase) - c(d), whatever the particle's random start phase was)
COLLISION_FIELDS = ("t", "x", "y", "vx", "vy", "phase")
#: the same plus ``event`` (0 collision, 1 lift-off), when lift-offs are recorded too
#: (``simulate(record_liftoffs=True)``): a lift-off row holds the state leaving the floor
EVENT_FIELDS = COLLISION_FIELDS + ("event",)
#: values of ``event``: 0 a collision (its post-collision state; at rest relative to the
#: floor when it ended a cascade and the particle is held), 1 a lift-off of a held particle;
#: under the contact models (Params.contact = slide, coulomb) also 4 a collision that starts
#: sliding contact (the state on the arc, relative normal speed 0), 5 a lift-off from
#: sliding (N = 0; the state leaving, with normal speed v_stick), 6 a Coulomb stop (v = 0;
#: held there if static friction can, else it slides back), 7 arrival at a cusp while
#: sliding (the state on the old arc; the collision with the neighbouring arc follows)
EVENT_CODES = {"collision": 0, "liftoff": 1, "contact": 4, "contact_lift": 5, "stop": 6,
               "cusp": 7}
#: per-particle times (s): held at rest relative to the floor (stuck / static friction), and
#: sliding on an arc (contact models only)
CONTACT_TIME_NAMES = ("held", "sliding")
#: per-particle counters of a run; 'anomalies' (non-finite velocities repaired) must stay 0
COUNTER_NAMES = ("collisions", "sticks", "liftoffs", "recorded", "anomalies")


@dataclass(frozen=True)
class SimRun:
    """What one call of :func:`bbb.simulate` recorded.

    positions        -- float64 (n_particles, n_samples): x (mm) at ``sample_times`` (s),
                        or None when no sample times were asked for.
    collisions_dense -- float64 (n_particles, record_collisions, 6): post-collision
                        (t, x, y, vx, vy, phase) of each particle's first ``record_collisions``
                        collisions at t ≥ record_from, NaN-padded; None when not asked for.
                        With lift-offs recorded: 7 columns (EVENT_FIELDS) and the rows are
                        collisions and lift-offs in time order.
    n_recorded       -- int64 (n_particles,): valid rows of ``collisions_dense``.
    liftoffs         -- whether lift-off rows were recorded.
    counters         -- int64 arrays (n_particles,) named by ``COUNTER_NAMES``.
    contact_time     -- float64 arrays (n_particles,) named by ``CONTACT_TIME_NAMES``, s
                        (the paper's floor and the conveyor alike).
    """

    params: Params
    numerics: Numerics
    initial: str
    t_max: float
    sample_times: np.ndarray | None
    positions: np.ndarray | None
    collisions_dense: np.ndarray | None
    n_recorded: np.ndarray
    counters: dict[str, np.ndarray]
    liftoffs: bool = False
    contact_time: dict[str, np.ndarray] | None = None

    def contact_fraction(self) -> np.ndarray:
        """Per particle, the fraction of t_max spent in sustained contact (held + sliding)."""
        assert self.contact_time is not None
        return (self.contact_time["held"] + self.contact_time["sliding"]) / self.t_max

    @property
    def fields(self) -> tuple[str, ...]:
        """Names of the columns of ``collisions_dense``."""
        return EVENT_FIELDS if self.liftoffs else COLLISION_FIELDS

    @property
    def n_particles(self) -> int:
        return int(self.n_recorded.shape[0])

    @property
    def collisions(self) -> np.ndarray:
        """Recorded rows as one structured array: ``fields`` and particle."""
        dtype = [(name, "f8") for name in self.fields] + [("particle", "i8")]
        if self.collisions_dense is None:
            return np.zeros(0, dtype=dtype)
        valid = np.arange(self.collisions_dense.shape[1])[None, :] < self.n_recorded[:, None]
        rows = self.collisions_dense[valid]
        out = np.empty(rows.shape[0], dtype=dtype)
        for i, name in enumerate(self.fields):
            out[name] = rows[:, i]
        out["particle"] = np.nonzero(valid)[0]
        return out
