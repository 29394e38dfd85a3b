"""Claims about bbb.stats.ergodicity: EB, its Brownian value and the verdict."""

from __future__ import annotations

import numpy as np
import pytest

from bbb.stats import (
    eb_brownian,
    ergodic_verdict,
    ergodicity_breaking,
)

from .walks import DT, brownian, jumps, times


def test_eb_brownian_exact_value_at_lag_one_and_its_four_thirds_limit():
    # L = 1: δ² is a mean of W = n - 1 independent squares, Var/mean² = 2/W = 2/100.
    assert eb_brownian(1, 101) == pytest.approx(0.02, rel=1e-12)
    # 1 ≪ L ≪ W: 4/3 · L/W = 4/3 · 100/99_900.
    assert eb_brownian(100, 100_000) == pytest.approx(4 / 3 * 100 / 99_900, rel=0.01)


def test_eb_of_brownian_motion_is_close_to_four_thirds_lag_over_T():
    # 2000 particles, analysed T = 399 dt (no transient), lag 20 dt: 4/3 · 20/399 ≈ 0.067.
    # The estimator's relative SE with 2000 particles is ≈ sqrt(2/1999) ≈ 3 %.
    rng = np.random.default_rng(9)
    x = brownian(rng, 2000, 400, D=1.0)
    eb = ergodicity_breaking(x, times(400), lag=20 * DT, discard=0.0)
    assert eb == pytest.approx(4 / 3 * 20 / 399, rel=0.15)


def test_eb_of_a_mixture_of_D_and_10D_is_far_above_brownian():
    # Half D, half 10 D: EB ≥ Var(D_i)/⟨D_i⟩² = (4.5/5.5)² ≈ 0.67 vs Brownian ≈ 0.07.
    rng = np.random.default_rng(10)
    x = np.vstack([brownian(rng, 500, 400, D=0.1), brownian(rng, 500, 400, D=1.0)])
    eb = ergodicity_breaking(x, times(400), lag=20 * DT, discard=0.0)
    assert eb > 5 * eb_brownian(20, 400)


def test_verdict_on_brownian_families_with_equal_D_is_ergodic():
    rng = np.random.default_rng(11)
    families = {"rest": brownian(rng, 300, 400, D=1.0), "uniform": brownian(rng, 300, 400, 1.0)}
    verdict = ergodic_verdict(families, times(400), seed=1)
    assert verdict.ergodic, verdict.reasons


def test_verdict_on_families_mixing_D_and_10D_is_non_ergodic_by_eb():
    rng = np.random.default_rng(12)

    def mixed() -> np.ndarray:
        return np.vstack([brownian(rng, 150, 400, D=0.1), brownian(rng, 150, 400, D=1.0)])

    verdict = ergodic_verdict({"a": mixed(), "b": mixed()}, times(400), seed=1)
    assert not verdict.ergodic
    assert not verdict.eb_ok, verdict.reasons


def test_verdict_on_families_with_clearly_different_D_fails_agreement():
    # Each family is homogeneous Brownian, but D differs by 50 %: rule (a) must fail.
    rng = np.random.default_rng(13)
    families = {"slow": brownian(rng, 300, 400, D=1.0), "fast": brownian(rng, 300, 400, D=1.5)}
    verdict = ergodic_verdict(families, times(400), seed=1)
    assert not verdict.ergodic
    assert not verdict.agreement_ok, verdict.reasons


def test_ergodic_motion_with_eb_above_the_brownian_level_passes_by_its_decay():
    rng = np.random.default_rng(14)
    n, rate = 4000, 0.3  # 40 s runs, 12 jumps per particle: EB ~ 3/(rate T) > 2 x Brownian
    families = {"a": jumps(rng, 1000, n, rate), "b": jumps(rng, 1000, n, rate)}
    verdict = ergodic_verdict(families, times(n), seed=1)
    assert verdict.eb["(pooled)"] > verdict.eb_threshold  # the level rule alone would fail
    assert verdict.ergodic, verdict.reasons
