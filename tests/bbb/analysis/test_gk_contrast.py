"""The split of a log contrast of D into random walk and memory (bbb.analysis.gk_contrast), on AR(1)
jump sequences with a known split, judged by the calibrated rule (θ and the CI level read
from bbb/analysis/gk_contrast_rule.json, as the claims read them)."""

import math

import numpy as np
import pytest

from bbb.analysis.gk_contrast import calibrated_rule, carrier, combine_sides, contrast
from bbb.analysis.greenkubo import expansion

N_P, N_STEPS = 256, 2000


def ar1(var: float, m: float, seed: int, sigma_sd: float = 0.0) -> np.ndarray:
    """Stationary AR(1) jumps with ⟨σ²⟩ = var and memory factor m = D_∞/D_0 = (1+ρ)/(1−ρ);
    per-particle σ_i log-normal with sd ``sigma_sd`` of ln σ."""
    rng = np.random.default_rng(seed)
    rho = (m - 1) / (m + 1)
    sigma = math.sqrt(var) * np.exp(sigma_sd * rng.standard_normal(N_P) - sigma_sd**2)
    eps = rng.standard_normal((N_P, N_STEPS)) * math.sqrt(1 - rho * rho)
    x = np.empty((N_P, N_STEPS))
    x[:, 0] = rng.standard_normal(N_P)
    for n in range(1, N_STEPS):
        x[:, n] = rho * x[:, n - 1] + eps[:, n]
    return x * sigma[:, None]


def gk(var: float, m: float, seed: int, **kw):
    return expansion(ar1(var, m, seed, **kw), 1.0, seed=seed)


def verdict_of(ext, neighbours, kind="max"):
    rule = calibrated_rule()
    sides = [carrier(contrast(ext, nb, rule["ci"]), kind, rule["theta"]) for nb in neighbours]
    return sides, combine_sides(sides)


def test_an_extremum_of_correlation_alone_is_carried_by_memory():
    # same jump variance at all three "frequencies"; the middle one is more correlated
    ext = gk(1.0, 12.0, 1)
    sides, v = verdict_of(ext, [gk(1.0, 6.0, 2), gk(1.0, 4.0, 3)])
    assert sides == ["memory", "memory"] and v == "memory"


def test_an_extremum_of_jump_variance_alone_is_carried_by_the_random_walk():
    # same correlation everywhere; the middle one has the largest jumps
    ext = gk(2.0, 8.0, 4)
    sides, v = verdict_of(ext, [gk(1.0, 8.0, 5), gk(1.2, 8.0, 6)])
    assert sides == ["random walk", "random walk"] and v == "random walk"


def test_a_minimum_made_by_both_parts_in_equal_shares_is_both():
    # ln D ratio −ln 4 at each side: −ln 2 from the variance and −ln 2 from the memory
    ext = gk(1.0, 4.0, 7)
    sides, v = verdict_of(ext, [gk(2.0, 8.0, 8), gk(2.0, 8.0, 9)], kind="min")
    assert sides == ["both", "both"] and v == "both"


def test_no_contrast_is_not_resolved_and_the_wrong_sign_is_no_extremum():
    ext = gk(1.0, 6.0, 10)
    same = gk(1.0, 6.0, 11)
    larger = gk(1.0, 12.0, 12)
    sides, v = verdict_of(ext, [same, larger])
    assert sides == ["not resolved", "wrong sign"] and v == "no extremum"


def test_the_parts_add_up_to_the_log_contrast_of_the_expansions():
    a, b = gk(1.0, 12.0, 1), gk(0.7, 5.0, 2)
    c = contrast(a, b, 0.95)
    assert c.total[0] == pytest.approx(math.log(a.D_inf / b.D_inf), rel=1e-12)
    assert c.walk[0] == pytest.approx(math.log(a.D_n[0] / b.D_n[0]), rel=1e-12)
    assert c.memory[0] == pytest.approx(c.total[0] - c.walk[0], rel=1e-12)
    assert c.share[0] == pytest.approx(c.memory[0] / c.total[0], rel=1e-12)
    # the truth: walk = ln(1/0.7), memory = ln(12/5); within 4 CI-σ
    for (v, lo, hi), exact in ((c.walk, math.log(1 / 0.7)), (c.memory, math.log(12 / 5))):
        assert abs(v - exact) <= 4 * (hi - lo) / (2 * 1.96)


def test_pairing_within_a_frequency_cancels_the_particles_spread_in_the_memory_part():
    # particles with very different jump sizes (sd 1 of ln σ) but one correlation: D_0 and
    # D_∞ of a resample move together, so the memory part's CI is much narrower than the
    # random walk's; resampled independently (D_∞ replicates shuffled) it would not be
    a, b = gk(2.0, 6.0, 13, sigma_sd=1.0), gk(1.0, 6.0, 14, sigma_sd=1.0)
    c = contrast(a, b, 0.95)
    width = {k: getattr(c, k)[2] - getattr(c, k)[1] for k in ("walk", "memory")}
    assert width["memory"] < 0.5 * width["walk"]


def test_a_d_at_or_below_zero_is_not_measured():
    a, b = gk(1.0, 6.0, 15), gk(1.0, 6.0, 16)
    import dataclasses

    zero = dataclasses.replace(b, D_inf_boot=np.where(np.arange(b.D_inf_boot.size) == 0, -1.0,
                                                      b.D_inf_boot))
    c = contrast(a, zero, 0.95)
    assert not c.measured and carrier(c, "max", 0.7) == "not measured"


@pytest.mark.parametrize(("sides", "expected"), [
    (["memory", "memory"], "memory"),
    (["memory", "not measured"], "memory"),
    (["memory", "random walk"], "both"),
    (["memory", "undecided"], "undecided"),
    (["both", "random walk"], "both"),
    (["not resolved", "not measured"], "not resolved"),
    (["not measured", "not measured"], "not measured"),
    (["memory", "wrong sign"], "no extremum"),
])
def test_combining_the_two_sides(sides, expected):
    assert combine_sides(sides) == expected


def test_the_calibrated_rule_is_read_from_its_file_and_met_its_error_target():
    rule = calibrated_rule()
    assert 0.5 < rule["theta"] < 1 and 0 < rule["ci"] < 1
    assert rule["worst_wrong"] <= rule["max_wrong"]
    assert rule["source"].startswith("benchmarks/results/contrast-calibration-")
