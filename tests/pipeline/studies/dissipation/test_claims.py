"""The map's claim rules on synthetic maps with known answers: each turns both ways."""

import numpy as np
import pandas as pd
import pytest

from pipeline.claims.claim import evaluate_claim
from pipeline.studies.dissipation.claims import CLAIMS, threshold_frequency
from pipeline.studies.dissipation.cuts import compare_cut

from .synthetic import ALPHAS, F, dmap

BY_ID = {c.id: c for c in CLAIMS}
ONSET_GP, ONSET_G1, FIRST_MAX, LOOPS, ERGODIC, CUTS = (BY_ID[f"A{i}"] for i in range(1, 7))


def verdict(claim, **tables):
    return evaluate_claim(claim, {"tables": tables}).verdict


def test_an_onset_at_gamma_prime_agrees_with_gamma_prime():
    assert verdict(ONSET_GP, dissipation_diffusion=dmap()) == "agrees"


def test_an_onset_fixed_in_alpha_disagrees_with_gamma_prime():
    assert verdict(ONSET_GP, dissipation_diffusion=dmap(onset_of=lambda a: 58.0)) == "disagrees"


def test_an_onset_that_tracks_gamma_prime_but_sits_high_is_only_partly_predicted():
    late = dmap(onset_of=lambda a: float(np.ceil(threshold_frequency("gamma_prime", a))) + 6)
    assert verdict(ONSET_GP, dissipation_diffusion=late) == "partly"


def test_an_onset_at_gamma_prime_disagrees_with_gamma_1():
    assert verdict(ONSET_G1, dissipation_diffusion=dmap()) in ("disagrees", "partly")


def test_a_first_maximum_moving_with_alpha_at_60_hz_for_the_paper_agrees():
    m = dmap(onset_of=lambda a: 50.0, max_of=lambda a, on: 60.0 + 20 * (0.7 - a))
    assert verdict(FIRST_MAX, dissipation_diffusion=m) == "agrees"


def test_a_first_maximum_fixed_in_alpha_does_not_move():
    m = dmap(onset_of=lambda a: 50.0, max_of=lambda a, on: 60.0)
    assert verdict(FIRST_MAX, dissipation_diffusion=m) == "partly"  # at 60 Hz, but not moving


def _lock(f_of_2):
    rows = []
    for a in ALPHAS:
        for f in F:
            k = 2.0 * (f - 30.0) / (f_of_2(a) - 30.0)
            rows.append({"f": f, "alpha": a, "k_max": k, "k_max_lo": k - 0.02, "k_max_hi": k + 0.02})
    return pd.DataFrame(rows)


def test_loops_reached_later_at_more_dissipation_move():
    assert verdict(LOOPS, dissipation_locking_locking=_lock(lambda a: 80.0 - 20 * a)) == "agrees"


def test_loops_at_the_same_frequency_for_every_alpha_do_not_move():
    assert verdict(LOOPS, dissipation_locking_locking=_lock(lambda a: 66.0)) == "disagrees"


def test_ergodicity_broken_just_above_the_onset_only_agrees():
    m = dmap(nonergodic=lambda f, f_on: f < f_on + 2)
    assert verdict(ERGODIC, dissipation_diffusion=m) == "agrees"


def test_ergodicity_broken_everywhere_is_not_a_break_next_to_the_onset():
    m = dmap(nonergodic=lambda f, f_on: int(f) % 3 == 0)
    assert verdict(ERGODIC, dissipation_diffusion=m) == "partly"  # a third broken beyond


def test_ergodic_everywhere_shows_no_break_to_locate():
    # none broken beyond (agrees), none inside either: the contrast's CI reaches 0
    assert verdict(ERGODIC, dissipation_diffusion=dmap()) == "inconclusive"


def _cuts(shift):
    line = dmap(refined=False).query("alpha == 0.7")
    ref = line.assign(D=line["D"] * shift, D_lo=line["D_lo"] * shift, D_hi=line["D_hi"] * shift)
    return compare_cut(line, ref, 9.0, 9.0).assign(cut="figure2")


def test_a_cut_equal_to_its_scene_agrees_and_a_shifted_one_does_not():
    assert verdict(CUTS, dissipation_cuts=_cuts(1.0)) == "agrees"
    assert verdict(CUTS, dissipation_cuts=_cuts(1.2)) == "disagrees"


@pytest.mark.parametrize("claim", CLAIMS, ids=lambda c: c.id)
def test_a_claim_without_its_table_is_not_measured(claim):
    assert verdict(claim) == "not measured"
