"""Positions: x (mm) at the sample times 0, sample_dt, ..., t_max (what D's MSD needs)."""

from __future__ import annotations

from .contract import Array, Chunk, Coord, Observable


class Positions(Observable):
    name = "positions"
    tables = ("diffusion",)

    def on(self, obs) -> bool:
        return bool(obs.positions)

    def sample_times(self, study, f):
        return study.sample_times()

    def coords(self, study):
        return (Coord("time", study.sample_times(), "float64", "s", "sample time"),)

    def arrays(self, study):
        return (Array("positions", (("time", len(study.sample_times())),), "float64",
                      float("nan"), "mm", "horizontal position x"),)

    def compute(self, chunk: Chunk):
        return {"positions": chunk.positions_at(chunk.study.sample_times())}
