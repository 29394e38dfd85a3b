"""The mechanisms claim rules on synthetic tables with known answers."""

from __future__ import annotations

import pandas as pd

from pipeline.claims import evaluate_claim
from pipeline.studies.mechanisms.claims import CLAIMS


def _table(d0: float, dinf: float, lam60: float, lam_spiral: float) -> pd.DataFrame:
    rows = []
    for f in (52.0, 54.0, 56.0, 58.0, 60.0, 62.0, 64.0, 66.0, 70.0, 80.0, 82.0):
        lam = lam60 if f == 60.0 else lam_spiral
        rows.append(dict(f=f, D_0=d0, D_0_lo=0.95 * d0, D_0_hi=1.05 * d0, D_inf=dinf,
                         D_inf_lo=0.95 * dinf, D_inf_hi=1.05 * dinf, lag=10, converged=True,
                         lam=lam, lam_lo=0.98 * lam, lam_hi=1.02 * lam))
    return pd.DataFrame(rows)


def _verdict(claim, table) -> str:
    return evaluate_claim(claim, {"tables": {"mechanisms": table}}).verdict


def test_memory_share_agrees_when_memory_makes_most_of_d():
    assert _verdict(CLAIMS[3], _table(2.0, 100.0, 40, 50)) == "agrees"  # 80 Hz: share 0.98


def test_memory_share_disagrees_for_uncorrelated_jumps():
    assert _verdict(CLAIMS[3], _table(100.0, 101.0, 40, 50)) == "disagrees"  # share ≈ 0.01


def test_nothing_diffusing_is_not_measured():
    assert _verdict(CLAIMS[0], _table(0.0, 0.0, 40, 50)) == "not measured"


def test_lyapunov_ratio_follows_the_spiral_regime():
    assert _verdict(CLAIMS[-1], _table(2, 100, 40.0, 50.0)) == "agrees"
    assert _verdict(CLAIMS[-1], _table(2, 100, 50.0, 40.0)) == "disagrees"


def test_draft_scene_caps_lyapunov_particles():
    from pipeline.scenes import load_scene

    study = load_scene("mechanisms", fast=True)
    assert study.observables.lyapunov_particles <= study.accuracy.n_particles
    assert load_scene("mechanisms").observables.lyapunov_particles == 128
