"""Collision jumps: x and t of recorded collision n + 1 minus those of collision n, for the first
``[observables.collisions] x_jumps`` + 1 collisions from record_from (float32; NaN beyond a
particle's recorded ones): the per-collision Green–Kubo expansion."""

from __future__ import annotations

import numpy as np

from .contract import Array, Chunk, Coord, Observable


class CollisionJumps(Observable):
    name = "collision_jumps"
    # the mechanisms table's _coll columns, when that table exists (with jumps or lyapunov):
    # alone, collision jumps make no table (as before they were a plug-in)
    tables = ()

    def on(self, obs) -> bool:
        return bool(obs.collisions and obs.collisions_x_jumps)

    def rows(self, study) -> int:
        return study.observables.collisions_x_jumps + 1

    def coords(self, study):
        return (Coord("collision_jump", np.arange(study.observables.collisions_x_jumps),
                      "int64", "", "jump n: recorded collision n to n + 1"),)

    def arrays(self, study):
        J = study.observables.collisions_x_jumps
        return tuple(Array(name, (("collision_jump", J),), "float32", np.nan, unit,
                           f"{what} of recorded collision n + 1 minus {what} of collision n, "
                           "NaN beyond")
                     for name, unit, what in (("collision_dx", "mm", "x"),
                                              ("collision_dt", "s", "t")))

    def compute(self, chunk: Chunk):
        from bbb.analysis.greenkubo import collision_jumps

        J, run = chunk.study.observables.collisions_x_jumps, chunk.run
        dx, dt = collision_jumps(run.collisions_dense[:, : J + 1],
                                 np.minimum(run.n_recorded, J + 1))
        return {"collision_dx": dx.astype(np.float32), "collision_dt": dt.astype(np.float32)}
