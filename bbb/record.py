"""What a run records: positions at sample times, post-collision states, counters."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .numerics import Numerics
from .params import Params

__all__ = ["COLLISION_FIELDS", "COUNTER_NAMES", "EVENT_FIELDS", "SimRun"]

#: columns of a recorded post-collision state: t (s, from the particle's start), x, y (mm),
#: vx, vy (mm/s), and the floor phase f·t_floor mod 1 at the collision (the surface there
#: is at -A sin(2π phase) - c(d), whatever the particle's random start phase was)
COLLISION_FIELDS = ("t", "x", "y", "vx", "vy", "phase")
#: the same plus ``event`` (0 collision, 1 lift-off), when lift-offs are recorded too
#: (``simulate(record_liftoffs=True)``): a lift-off row holds the state leaving the floor
EVENT_FIELDS = COLLISION_FIELDS + ("event",)
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
