"""The transport map's rules (pipeline/studies/transport/reversal.py) on synthetic tables
with known answers: the throw number, the airborne share, the hopping boundary, the sign
changes along ψ."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from bbb import Params
from pipeline.studies.transport.reversal import (
    AIRBORNE_MIN,
    REVERSAL_LINES,
    REVERSAL_MAP,
    airborne,
    f_ranges,
    hopping_boundary,
    judge_boundary,
    throw_cuts,
    throw_number_frequency,
    throw_reversals,
)
from pipeline.workflow.scenes import load_scene

F = np.arange(30.0, 100.1, 2.0)  # the scene's 36 frequencies


@pytest.mark.parametrize("tilt, throw", [(0.0, 90.0), (2.0, 60.0), (5.0, 30.0)])
def test_the_throw_number_is_one_at_its_frequency(tilt, throw):
    f = throw_number_frequency(tilt, throw)
    p = Params.preset("klages2004", f=f)
    gamma = p.A * (2 * math.pi * f) ** 2 / p.g
    assert gamma * math.sin(math.radians(throw)) / math.cos(math.radians(tilt)) == \
        pytest.approx(1.0, rel=1e-12)
    if (tilt, throw) == (0.0, 90.0):  # the paper's floor: Γ = 1 at 49.8 Hz (docs/design.md)
        assert f == pytest.approx(49.8, abs=0.05)


def _contact(held, slide, half=0.01) -> pd.DataFrame:
    held, slide = np.asarray(held, float), np.asarray(slide, float)
    return pd.DataFrame({"f": F[::-1], "held_frac": held[::-1], "slide_frac": slide[::-1],
                         "held_frac_lo": held[::-1] - half, "held_frac_hi": held[::-1] + half,
                         "slide_frac_lo": slide[::-1] - half,
                         "slide_frac_hi": slide[::-1] + half})


def test_the_airborne_share_is_what_is_neither_held_nor_sliding_with_a_conservative_ci():
    held = np.linspace(1.0, 0.0, F.size)
    slide = 0.5 * (1.0 - held)
    a = airborne(_contact(held, slide))
    assert list(a["f"]) == list(F)
    assert np.allclose(a["air"], 0.5 * (1.0 - held))
    assert np.allclose(a["air_lo"], a["air"] - 0.02) and np.allclose(a["air_hi"], a["air"] + 0.02)


def test_the_hopping_boundary_lies_between_the_last_share_below_and_the_first_above():
    share = np.where(F < 55.0, 0.0, 0.4)  # hops from 56 Hz
    assert hopping_boundary(F, share - 0.01, share + 0.01) == (54.0, 56.0)
    share[F == 56.0] = AIRBORNE_MIN  # a CI straddling H widens the interval
    assert hopping_boundary(F, share - 0.01, share + 0.01) == (54.0, 58.0)
    assert hopping_boundary(F, np.zeros(F.size), np.full(F.size, 0.01)) is None  # never hops
    always = np.full(F.size, 0.5)
    assert hopping_boundary(F, always, always) is None  # hops from the first frequency
    rare = np.where(F < 55.0, 0.0, np.where(F < 70.0, 0.003, 0.4))  # rare hops: not a regime
    assert hopping_boundary(F, rare, rare + 0.001) == (68.0, 70.0)


def test_a_boundary_is_judged_against_the_throw_number_within_one_frequency_step():
    assert judge_boundary((52.0, 54.0), 53.5)[0] == "agrees"
    assert judge_boundary((54.0, 56.0), 53.5)[0] == "agrees within the CI"
    assert judge_boundary((58.0, 60.0), 53.5)[0] == "disagrees"
    assert judge_boundary(None, 53.5)[0] == "disagrees"
    q = judge_boundary((54.0, 56.0), 53.5)[1]
    assert (q.value, q.lo, q.hi) == (1.5, 0.5, 2.5)


def _line(v, se=0.5) -> pd.DataFrame:
    v = np.asarray(v, float)
    return pd.DataFrame({"f": F, "v": v, "v_lo": v - 1.96 * se, "v_hi": v + 1.96 * se,
                         "steady": True})


def test_sign_changes_along_the_throw_are_found_at_each_frequency_per_floor():
    lines = {}
    for name, vals in REVERSAL_LINES.items():
        p = vals["throw"]
        # downhill at ψ ≥ 75°, uphill below, only where 50 ≤ f ≤ 60 Hz (else downhill)
        v = np.where((p < 70.0) & (F >= 50.0) & (F <= 60.0), 5.0, -5.0)
        lines[name] = (vals, _line(v))
    cuts = throw_cuts(lines)
    assert len(cuts) == 2 * F.size  # one cut per (contact model, f)
    found = throw_reversals(cuts)
    assert {(dict(fl)["contact"], f) for fl, f, _ in found} == {
        (c, f) for c in ("stick", "coulomb") for f in F if 50.0 <= f <= 60.0}
    assert all(change == (75.0, 60.0, 1) for _, _, change in found)
    for name, (vals, _) in lines.items():  # a uniform sign: no change anywhere
        lines[name] = (vals, _line(np.full(F.size, -5.0)))
    assert throw_reversals(throw_cuts(lines)) == []


def test_unsteady_points_are_left_out_of_the_cuts():
    vals = {n: v for n, v in REVERSAL_LINES.items() if v["contact"] == "stick"}
    lines = {n: (v, _line(np.full(F.size, 5.0 if v["throw"] < 70 else -5.0))) for n, v in
             vals.items()}
    for _, t in lines.values():
        t["steady"] = F < 40.0
    cuts = throw_cuts(lines)
    assert sorted({f for _, f in cuts}) == list(F[F < 40.0])


def test_frequency_ranges_join_neighbours():
    assert f_ranges([46.0, 48.0, 50.0, 56.0, 60.0, 62.0]) == "46–50, 56, 60–62 Hz"


def test_the_map_holds_the_lines_the_rules_assume():
    study = load_scene(REVERSAL_MAP)
    assert {tuple(p.grid) for p in study.points} == {tuple(v.items())
                                                    for v in REVERSAL_LINES.values()}
    for vals in REVERSAL_LINES.values():
        line = study.line(vals)
        p = line.params(50.0)
        assert (p.tilt, p.throw, p.contact, p.mu) == (vals["tilt"], vals["throw"],
                                                      vals["contact"], vals["mu"])
        assert list(line.frequencies) == list(F)
    assert study.observables.contact  # the airborne share needs the time held and sliding
