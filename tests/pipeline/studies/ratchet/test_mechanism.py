"""The collisions at each ratchet reversal and the conveyor's reversals, on synthetic tables
with known answers."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pipeline.studies.ratchet.cases import F, map_table
from pipeline.studies.ratchet.mechanism import (
    BINS,
    conveyor_reversals,
    resultant,
    reversal_table,
)


def test_the_phase_resultant_is_one_at_a_single_bin_and_zero_for_an_even_spread():
    one = np.zeros(BINS)
    one[6] = 1.0
    rho, phase = resultant(one)
    assert rho == pytest.approx(1.0) and phase == pytest.approx(6.5 * 360 / BINS)
    assert resultant(np.full(BINS, 1 / BINS))[0] == pytest.approx(0.0, abs=1e-12)
    # two opposite bins, equal shares: no mean direction
    two = np.zeros(BINS)
    two[[0, BINS // 2]] = 0.5
    assert resultant(two)[0] == pytest.approx(0.0, abs=1e-12)
    assert all(math.isnan(x) for x in resultant(np.full(BINS, np.nan)))


def _impacts_counters(t: pd.DataFrame, drop_f: float | None = None):
    keys = t[["f", "peak", "alpha"]]
    phase = {f"phase_{b}": (1.0 if b == 3 else 0.0) for b in range(BINS)}
    imp = keys.assign(**phase, vx_within_1=0.5, vx_within_1_lo=0.4, vx_within_1_hi=0.6)
    if drop_f is not None:
        imp = imp[imp["f"] != drop_f]
    cnt = keys.assign(collisions_per_s=2.0 * keys["f"])
    return imp, cnt


def test_each_reversal_end_reads_the_collisions_there_and_a_missing_point_stays_blank():
    t = map_table(g=lambda f: np.tanh((70.0 - f) / 3.0))
    imp, cnt = _impacts_counters(t, drop_f=72.0)
    rev = reversal_table({"ratchet_diffusion": t, "ratchet_impacts": imp,
                          "ratchet_counters": cnt})
    # the two off-centre lines, each one reversal 68-72 Hz with two ends
    assert len(rev) == 4 and set(rev["peak"]) == {0.3, 0.7}
    assert (rev["f_a"] == 68.0).all() and (rev["f_b"] == 72.0).all()
    assert list(rev[rev["peak"] == 0.3]["sign_after"]) == [-1, -1]
    assert np.allclose(rev["per_period"], 2.0)  # 2 f collisions per s over f
    a = rev[rev["end"] == "a"]
    assert np.allclose(a["rho"], 1.0) and np.allclose(a["vx_within_1"], 0.5)
    b = rev[rev["end"] == "b"]  # the impacts table lacks 72 Hz: blank, not 0
    assert b["rho"].isna().all() and b["vx_within_1"].isna().all()


def test_a_one_signed_map_has_no_reversal_rows():
    t = map_table()
    imp, cnt = _impacts_counters(t)
    assert reversal_table({"ratchet_diffusion": t, "ratchet_impacts": imp,
                           "ratchet_counters": cnt}).empty


def test_the_conveyors_reversals_are_found_per_line_with_the_same_sign_rules():
    t = map_table(g=lambda f: np.tanh((70.0 - f) / 3.0), peaks=(0.3,))
    conv = t.drop(columns=["peak", "alpha"])
    rows = pd.concat([conv.assign(tilt=2.0, throw=60.0, contact="stick"),
                      conv.assign(tilt=2.0, throw=90.0, contact="stick", v=1.0, v_lo=0.8,
                                  v_hi=1.2)])
    out = conveyor_reversals({"transport_reversal_diffusion.csv": rows})
    assert len(out) == 2
    r60 = out[out["throw"] == 60.0].iloc[0]
    assert (r60["f_a"], r60["f_b"], r60["sign_after"]) == (68.0, 72.0, -1)
    assert math.isnan(out[out["throw"] == 90.0].iloc[0]["f_a"])
    assert len(F) == 31


def _states_row(**shares) -> dict:
    from bbb.analysis.states import LABELS

    row = {lab: 0.0 for lab in LABELS} | {"period_k": float("nan")}
    return row | shares


def test_the_states_text_names_the_states_of_at_least_5_percent_commonest_first():
    from pipeline.studies.ratchet.mechanism import states_text

    assert states_text(pd.Series(_states_row(diffusing=0.9, chaotic=0.06, stuck=0.04))) == \
        "diffusing 0.90, chaotic 0.06"
    assert states_text(pd.Series(_states_row(locked_k=0.75, locked_1=0.25, period_k=2.0))) == \
        "locked_k (k = 2) 0.75, locked_1 0.25"
    assert states_text(None) == ""


def test_each_reversal_end_carries_the_states_reached_there_and_none_where_not_run():
    t = map_table(g=lambda f: np.tanh((70.0 - f) / 3.0), peaks=(0.3, 0.5, 0.7))
    imp, cnt = _impacts_counters(t)
    sts = pd.DataFrame([{"alpha": 0.7, "peak": 0.3, "f": 68.0, **_states_row(locked_1=1.0)},
                        {"alpha": 0.7, "peak": 0.3, "f": 72.0, **_states_row(diffusing=1.0)}])
    rev = reversal_table({"ratchet_diffusion": t, "ratchet_impacts": imp,
                          "ratchet_counters": cnt, "ratchet_states_classes": sts})
    low = rev[rev["peak"] == 0.3].set_index("end")["states"]
    assert (low["a"], low["b"]) == ("locked_1 1.00", "diffusing 1.00")
    assert (rev[rev["peak"] == 0.7]["states"] == "").all()  # the states scene lacks p = 0.7
