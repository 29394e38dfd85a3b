"""benchmarks/calibrations/compare.py: a remade calibration is the committed one when, provenance
aside, every number lies within a relative 1e-9 and everything else is equal."""

from __future__ import annotations

import json
import math

from benchmarks.calibrations.compare import PROVENANCE, REL_TOL, differences, dump

COMMITTED = {"date": "2026-11-25", "kernel": "abc1234", "theta": 0.6666666666666666, "n": 100,
             "cases": [{"expected": "both", "share_cover": math.nan, "rates": [0.25, 1.0]}],
             "passes": {"0.5": True}, "maker": {"script": "benchmarks/calibrations/x.py", "args": []}}


def copy(d: dict) -> dict:
    return json.loads(dump(d))


def test_a_json_equals_itself_through_its_written_text_nan_included():
    assert differences(copy(COMMITTED), COMMITTED) == []


def test_provenance_keys_are_not_compared():
    made = copy(COMMITTED) | {"date": "2026-12-01", "kernel": "fffffff", "cpu": "other"}
    assert {"date", "kernel", "cpu"} <= PROVENANCE
    assert differences(made, COMMITTED) == []


def test_a_number_within_the_tolerance_is_the_same_and_one_beyond_it_is_named():
    made = copy(COMMITTED)
    made["theta"] *= 1 + REL_TOL / 10
    assert differences(made, COMMITTED) == []
    made["theta"] = COMMITTED["theta"] * (1 + 10 * REL_TOL)
    assert [d.split(":")[0] for d in differences(made, COMMITTED)] == ["/theta"]


def test_a_nested_value_a_nan_a_flag_and_a_missing_key_are_each_named():
    made = copy(COMMITTED)
    made["cases"][0]["share_cover"] = 0.99
    made["passes"]["0.5"] = False
    del made["n"]
    found = differences(made, COMMITTED)
    assert sorted(d.split(":")[0] for d in found) == ["/cases[0]/share_cover", "/n", "/passes/0.5"]


def test_a_maker_record_that_differs_is_named_it_is_not_provenance():
    made = copy(COMMITTED)
    made["maker"]["args"] = ["--seeds", "10"]
    assert differences(made, COMMITTED) != []
