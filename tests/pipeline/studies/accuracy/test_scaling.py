"""The accuracy study's scaling (pipeline.studies.accuracy.scaling): per-particle D is
unbiased, its spread falls like N^-1/2 and does not shrink with t_max."""

from __future__ import annotations

import numpy as np

from pipeline.studies.accuracy.scaling import per_particle_D
from pipeline.workflow.keys import DEFAULT_ANALYSIS, Analysis

ANALYSIS = Analysis(**DEFAULT_ANALYSIS)  # the analysis of a workflow that sets none


def _brownian(n, t_max, D=50.0, dt=0.5, seed=1):
    rng = np.random.default_rng(seed)
    steps = rng.normal(0.0, np.sqrt(2 * D * dt), size=(n, int(round(t_max / dt))))
    return np.concatenate([np.zeros((n, 1)), np.cumsum(steps, axis=1)], axis=1), np.arange(
        steps.shape[1] + 1) * dt


def test_statistical_error_of_D_shrinks_like_one_over_sqrt_N_and_not_with_t_max():
    an = ANALYSIS
    x, t = _brownian(4096, 100.0)
    d_i = per_particle_D(x, t, an)
    assert abs(d_i.mean() - 50.0) < 3 * d_i.std() / np.sqrt(d_i.size)  # unbiased
    ns = np.array([16, 64, 256, 1024])
    spread = [d_i[: (4096 // n) * n].reshape(-1, n).mean(1).std(ddof=1) for n in ns]
    slope = np.polyfit(np.log(ns), np.log(spread), 1)[0]
    assert -0.62 < slope < -0.38
    # 4x longer runs: the fit lags grow with t_max, the relative spread of D_i stays put
    x4, t4 = _brownian(1024, 400.0, seed=2)
    d4 = per_particle_D(x4, t4, an)
    ratio = (d4.std() / d4.mean()) / (d_i.std() / d_i.mean())
    assert 0.8 < ratio < 1.25
