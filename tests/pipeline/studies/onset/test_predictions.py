"""The committed predictions (predictions.json) are what the theory computes: the first
lift-off f(Γ = 1), f_c(α) to the file's tolerance, the chattering cycle horizontally stable at
the sine's valleys, and the flat floor's measured motion from rest -- one stick a period below
f_c, fewer above."""

from __future__ import annotations

import math

import pytest

from bbb.analysis.onset_theory import chatter_limit
from pipeline.studies.onset.predictions import compute, load


def test_the_committed_f_c_and_lift_off_are_the_theorys():
    p, again = load(), compute(alphas=(0.7,), depths=(0.3,))
    assert p["f_liftoff"] == pytest.approx(again["f_liftoff"], abs=1e-9)
    assert p["alpha"]["0.7"]["f_c"] == pytest.approx(again["alpha"]["0.7"]["f_c"],
                                                     abs=2 * p["tol_Hz"])
    assert p["alpha"]["0.7"]["sine"]["0.3"]["max_abs_lambda"] == pytest.approx(
        again["alpha"]["0.7"]["sine"]["0.3"]["max_abs_lambda"], abs=1e-9)


def test_the_chattering_cycle_is_horizontally_stable_at_every_sine_valley_below_f_c():
    for a in load()["alpha"].values():
        for s in a["sine"].values():
            assert s["max_abs_lambda"] < 1.0


def test_f_c_falls_with_alpha_as_the_measured_end_of_chattering_on_the_flat_floor():
    p = load()
    for a, rows in p["reached_flat"].items():
        fc = p["alpha"][a]["f_c"]
        for f, r in rows.items():
            if float(f) < fc:
                assert r["sticks"] == 1.0, (a, f)
            elif float(f) > fc + 0.5:
                assert r["sticks"] < 0.5, (a, f)
    assert chatter_limit(0.9, tol=0.05) < p["alpha"]["0.7"]["f_c"] < p["alpha"]["0.5"]["f_c"]
    assert math.isfinite(p["f_liftoff"])
