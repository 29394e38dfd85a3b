"""The ratchet claims on synthetic maps with known answers: each turns each way on its cases,
and the rules' pieces (mirror sums, reversal intervals) give the known numbers."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.claims.claim import evaluate_claim
from pipeline.claims.registry import case_problems
from pipeline.studies.ratchet.cases import F, map_table
from pipeline.studies.ratchet.claims import CLAIMS, line_reversals, map_lines, mirror_sums


@pytest.mark.parametrize("claim", CLAIMS, ids=lambda c: c.id)
def test_each_ratchet_claim_turns_each_way_on_its_cases_and_a_perturbation_flips_it(claim):
    assert case_problems(claim) == []


def test_a_mirror_sum_of_an_odd_map_is_zero_and_of_an_even_map_twice_the_drift():
    odd = mirror_sums(map_lines(map_table(peaks=(0.3, 0.5, 0.7))))
    assert list(odd) == [(0.7, 0.3)]
    assert np.allclose(odd[(0.7, 0.3)]["sum"], 0.0)
    # SE 0.1 on each side in quadrature: the sum's half-width is 1.96 x 0.1 x sqrt 2
    half = odd[(0.7, 0.3)]["sum_hi"] - odd[(0.7, 0.3)]["sum"]
    assert np.allclose(half, 1.959963984540054 * 0.1 * np.sqrt(2.0))
    even = mirror_sums(map_lines(map_table(c=lambda p: 2.0, peaks=(0.3, 0.7))))
    assert np.allclose(even[(0.7, 0.3)]["sum"], 4.0)


def test_a_reversal_at_70_hz_is_located_between_the_neighbouring_grid_frequencies():
    lines = map_lines(map_table(g=lambda f: np.tanh((70.0 - f) / 3.0)))
    found, s = line_reversals(lines[(0.7, 0.3)])
    assert found == [(68.0, 72.0, -1)]
    assert (s[F < 70] == 1).all() and (s[F > 70] == -1).all() and s[F == 70] == 0
    assert line_reversals(lines[(0.7, 0.7)])[0] == [(68.0, 72.0, 1)]


def test_the_centred_rule_is_bonferroni_over_every_centred_line_together():
    # 3.3 SE at one f: significant over one line's 31 points (z = 3.19), not over 93 (z = 3.52)
    def blip(p):
        return 3.3 * 0.1 if p == 0.5 else 0.0
    g = lambda f: np.where(f == 70.0, 1.0, 0.0)  # noqa: E731
    one = map_table(g=g, c=blip)
    three = map_table(g=g, c=blip, alphas=(0.5, 0.7, 0.9))
    centred = next(c for c in CLAIMS if c.id == "R2")
    assert evaluate_claim(centred, {"tables": {"ratchet_diffusion": one}}).verdict == "disagrees"
    assert evaluate_claim(centred, {"tables": {"ratchet_diffusion": three}}).verdict == "agrees"
