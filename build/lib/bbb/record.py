"""What a run records: positions at sample times, post-collision states, counters."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .numerics import Numerics
from .params import Params

__all__ = ["COLLISION_FIELDS", "COUNTER_NAMES", "SimRun"]

#: columns of a recorded post-collision state: t (s, from the particle's start), x, y (mm),
#: vx, vy (mm/s), and the floor phase f·t_floor mod 1 at the collision (the surface there
#: is at -A sin(2π phase) - c(d), whatever the particle's random start phase was)
COLLISION_FIELDS = ("t", "x", "y", "vx", "vy", "phase")
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
    n_recorded       -- int64 (n_particles,): valid rows of ``collisions_dense``.
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

    @property
    def n_particles(self) -> int:
        return int(self.n_recorded.shape[0])

    @property
    def collisions(self) -> np.ndarray:
        """Recorded collisions as one structured array: COLLISION_FIELDS and particle."""
        dtype = [(name, "f8") for name in COLLISION_FIELDS] + [("particle", "i8")]
        if self.collisions_dense is None:
            return np.zeros(0, dtype=dtype)
        valid = np.arange(self.collisions_dense.shape[1])[None, :] < self.n_recorded[:, None]
        rows = self.collisions_dense[valid]
        out = np.empty(rows.shape[0], dtype=dtype)
        for i, name in enumerate(COLLISION_FIELDS):
            out[name] = rows[:, i]
        out["particle"] = np.nonzero(valid)[0]
        return out
