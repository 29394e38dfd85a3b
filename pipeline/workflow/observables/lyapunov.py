"""Lyapunov: the largest Lyapunov exponent (bbb.analysis.lyapunov, two trajectories) of the first
``[observables.lyapunov] particles`` particles of each (point, family), from the same initial
states as their chunk; NaN beyond them, −inf where the separation collapsed."""

from __future__ import annotations

import dataclasses

import numpy as np

from .contract import Array, Chunk, Observable


class Lyapunov(Observable):
    name = "lyapunov"
    tables = ("mechanisms",)

    def on(self, obs) -> bool:
        return obs.lyapunov

    def arrays(self, study):
        return (Array("lyapunov", (), "float64", np.nan, "1/s",
                      "largest Lyapunov exponent per unit time (NaN: not measured)"),
                Array("lyapunov_per_collision", (), "float64", np.nan, "1",
                      "largest Lyapunov exponent per collision"),
                Array("lyapunov_x_range", (), "float64", np.nan, "mm",
                      "max - min of x at the period ends of the λ window"))

    def compute(self, chunk: Chunk):
        """λ (1/s, per collision) of this chunk's particles among the first ``particles``."""
        from bbb.analysis.lyapunov import lyapunov
        from bbb.ensemble import InitialState, initial_state

        study = chunk.study
        obs, acc = study.observables, study.accuracy
        k = min(acc.chunk_size, obs.lyapunov_particles - chunk.index * acc.chunk_size)
        if k <= 0:
            return {}
        p = chunk.point.params
        kw = dict(chunk.initial)
        st = kw.pop("initial")
        if isinstance(st, str):
            st = initial_state(p, acc.chunk_size,
                               study.seed_sequence(chunk.point.f, chunk.family, chunk.index),
                               st, **kw)
        sub = InitialState(**{fd.name: getattr(st, fd.name)[:k] for fd in dataclasses.fields(st)})
        lam = lyapunov(p, k, acc.t_max, 0, sub, discard=obs.lyapunov_discard, d0=obs.lyapunov_d0,
                       numerics=acc.numerics(), n_resamples=10)
        return {"lyapunov": lam.lam_i, "lyapunov_per_collision": lam.per_coll_i,
                "lyapunov_x_range": lam.x_range}
