"""`bbb.simulate`: run an ensemble through the collision map, recording only what is asked."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .numerics import Numerics
from .params import Params

__all__ = ["SimRun", "simulate"]


@dataclass(frozen=True)
class SimRun:
    """What one call of :func:`simulate` recorded.

    positions        -- float64 (n_particles, n_samples): x (mm) at ``sample_times`` (s),
                        or None when no sample times were asked for.
    collisions_dense -- float64 (n_particles, record_collisions, 5): post-collision
                        (t, x, y, vx, vy) of each particle's first ``record_collisions``
                        collisions at t ≥ record_from, NaN-padded; None when not asked for.
    n_recorded       -- int64 (n_particles,): valid rows of ``collisions_dense``.
    counters         -- int64 arrays (n_particles,): 'collisions', 'sticks', 'liftoffs'.
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
    def collisions(self) -> np.ndarray:
        """Recorded collisions as one structured array (t, x, y, vx, vy, particle)."""
        raise NotImplementedError  # filled in with the kernel


def simulate(*args, **kwargs) -> SimRun:  # placeholder: the kernel lands in the next commit
    raise NotImplementedError
