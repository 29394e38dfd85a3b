"""Jumps: x((n+1)/f) − x(n/f) (mm, float32) over every floor period n < floor(t_max f), NaN
beyond (the period axis is as long as the highest frequency's, and grows with a map)."""

from __future__ import annotations

import math

import numpy as np

from .contract import Array, Chunk, Coord, Observable

__all__ = ["Jumps", "n_periods"]


def n_periods(t_max: float, f: float) -> int:
    """Whole floor periods in t_max s at f Hz (the jumps of one particle)."""
    return int(math.floor(t_max * f + 1e-9))


def period_times(t_max: float, f: float) -> np.ndarray:
    """The period ends n/f, n = 0 … floor(t_max f), s (t_max at most)."""
    return np.minimum(np.arange(n_periods(t_max, f) + 1) / f, t_max)


class Jumps(Observable):
    name = "jumps"
    tables = ("mechanisms",)
    growing_dims = ("period",)

    def on(self, obs) -> bool:
        return bool(obs.jumps)

    def sample_times(self, study, f):
        return period_times(study.accuracy.t_max, f)

    def _P(self, study) -> int:
        return max(n_periods(study.accuracy.t_max, p.f) for p in study.points)

    def coords(self, study):
        return (Coord("period", np.arange(self._P(study)), "int64", "",
                      "floor period n: jump from n/f to (n+1)/f"),)

    def arrays(self, study):
        return (Array("jumps", (("period", self._P(study)),), "float32", np.nan, "mm",
                      "displacement over floor period n, NaN beyond t_max f"),)

    def compute(self, chunk: Chunk):
        x = chunk.positions_at(self.sample_times(chunk.study, chunk.point.f))
        return {"jumps": np.diff(x, axis=1).astype(np.float32)}
