import math

import numpy as np
import pytest

from bbb.analysis.period1 import frequency_at, gamma_1, gamma_at, gamma_prime


def test_the_thresholds_at_the_papers_alpha_are_luck_and_mehtas():
    # Γ₁ = π 0.3 / 1.7, Γ' = sqrt(Γ₁² + (2 · 1.49 / 2.89)²)
    assert gamma_1(0.7) == pytest.approx(0.554399, abs=1e-6)
    assert gamma_prime(0.7) == pytest.approx(1.170731, abs=1e-6)


def test_the_thresholds_at_the_papers_amplitude_are_37_and_54_hz():
    assert frequency_at(gamma_1(0.7), 0.1, 9800.0) == pytest.approx(37.1, abs=0.05)
    assert frequency_at(gamma_prime(0.7), 0.1, 9800.0) == pytest.approx(53.9, abs=0.05)


def test_an_elastic_ball_locks_from_zero_and_loses_stability_at_gamma_one():
    # α = 1: no dissipation, Γ₁ = 0 and Γ' = 2 · 2 / 4 = 1
    assert gamma_1(1.0) == 0.0
    assert gamma_prime(1.0) == pytest.approx(1.0)


def test_the_stability_window_lies_above_the_existence_threshold_for_every_alpha():
    a = np.linspace(0.05, 1.0, 96)
    assert np.all(gamma_prime(a) > gamma_1(a))
    assert np.all(np.diff(gamma_1(a)) < 0)  # less dissipation, the orbit exists earlier


def test_frequency_and_gamma_are_inverse():
    f = np.array([37.1, 49.85, 100.0])
    assert frequency_at(gamma_at(f, 0.1, 9800.0), 0.1, 9800.0) == pytest.approx(f)
    assert gamma_at(49.8226, 0.1, 9800.0) == pytest.approx(1.0, abs=1e-4)


@pytest.mark.parametrize("alpha", [0.0, -0.2, 1.01, math.nan])
def test_a_restitution_outside_zero_one_is_refused(alpha):
    with pytest.raises(ValueError, match="alpha"):
        gamma_1(alpha)
