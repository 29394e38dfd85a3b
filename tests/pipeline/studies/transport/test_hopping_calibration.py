"""The hopping threshold's calibration (pipeline/studies/transport/hopping_calibration.py):
the committed hopping.json is what the rule reads, H passes on every flat floor and a
threshold of one half fails, and a flat floor rerun gives the committed shares."""

from __future__ import annotations

import numpy as np

from pipeline.studies.transport.hopping_calibration import THRESHOLD, flat_share
from pipeline.studies.transport.reversal import (
    AIRBORNE_MIN,
    HOPPING_CALIBRATION,
    hopping_boundary,
    judge_boundary,
    throw_number_frequency,
)


def test_the_rule_reads_the_calibrated_threshold_which_finds_the_throw_number_on_flat_floors():
    assert AIRBORNE_MIN == THRESHOLD == HOPPING_CALIBRATION["threshold"]
    assert HOPPING_CALIBRATION["passes"][f"{THRESHOLD:g}"] is True
    assert HOPPING_CALIBRATION["passes"]["0.5"] is False  # the check can fail
    floors = HOPPING_CALIBRATION["floors"]
    assert len(floors) == 10 and {f["contact"] for f in floors} == {"stick", "coulomb"}
    for fl in floors:
        assert fl["verdicts"][f"{THRESHOLD:g}"]["verdict"] == "agrees"


def test_a_flat_floor_rerun_gives_the_committed_shares_and_boundary():
    fl = next(f for f in HOPPING_CALIBRATION["floors"]
              if f["throw"] == 60.0 and f["contact"] == "stick")
    fs = [f for f in fl["f"] if abs(f - fl["f_v"]) <= 4.0]
    got = np.array([flat_share(fl["tilt"], fl["throw"], fl["contact"], fl["mu"], f) for f in fs])
    want = [s for f, s in zip(fl["f"], fl["share"], strict=True) if f in fs]
    assert np.array_equal(got[:, 0], want)
    f_v = throw_number_frequency(fl["tilt"], fl["throw"])
    assert judge_boundary(hopping_boundary(fs, got[:, 1], got[:, 2], THRESHOLD), f_v)[0] == \
        "agrees"
    assert judge_boundary(hopping_boundary(fs, got[:, 1], got[:, 2], 0.5), f_v)[0] != "agrees"
