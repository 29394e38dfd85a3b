"""Collisions: each particle's first ``record`` post-collision states (t, x, y, vx, vy, phase;
bbb.record.COLLISION_FIELDS) from ``record_from`` on, NaN-padded, and how many are valid."""

from __future__ import annotations

import numpy as np

from bbb.record import COLLISION_FIELDS

from .contract import Array, Chunk, Coord, Observable

__all__ = ["Collisions", "FIELD_UNITS", "collision_field_units"]

#: units of the recorded collision fields (bbb.record.COLLISION_FIELDS), "1": dimensionless
FIELD_UNITS = {"t": "s", "x": "mm", "y": "mm", "vx": "mm/s", "vy": "mm/s", "phase": "1"}


def collision_field_units() -> tuple[str, ...]:
    """Units of bbb.record.COLLISION_FIELDS in storage order ('?' for a field this module does
    not know yet: tests/pipeline/store/test_study_store.py fails on it, so it is named here)."""
    return tuple(FIELD_UNITS.get(name, "?") for name in COLLISION_FIELDS)


class Collisions(Observable):
    name = "collisions"
    tables = ("locking",)

    def on(self, obs) -> bool:
        return obs.collisions

    def rows(self, study) -> int:
        return study.observables.collisions_record

    def coords(self, study):
        obs = study.observables
        return (Coord("collision", np.arange(obs.collisions_record), "int64", "",
                      f"collision index from t = {obs.collisions_from:g} s"),
                Coord("field", list(COLLISION_FIELDS), str, ", ".join(collision_field_units()),
                      "post-collision state component"))

    def arrays(self, study):
        K, n = study.observables.collisions_record, len(COLLISION_FIELDS)
        units = ", ".join(collision_field_units())
        return (Array("collisions", (("collision", K), ("field", n)), "float64", np.nan, units,
                      f"post-collision ({', '.join(COLLISION_FIELDS)}), NaN-padded"),
                Array("n_recorded", (), "int64", 0, "", "valid rows of collisions"))

    def compute(self, chunk: Chunk):
        # the recording may be longer (another observable's rows): its first K rows
        K, run = chunk.study.observables.collisions_record, chunk.run
        return {"collisions": run.collisions_dense[:, :K],
                "n_recorded": np.minimum(run.n_recorded, K)}
