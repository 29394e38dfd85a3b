"""What the D(f) table says where nothing leaves its cell and where the drift accelerates
(pipeline.tables.diffusion, pipeline.tables.notes): a real conveyor, simulated and reduced
(tests/pipeline/conveyor.py), and a steady drift written through the store."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from ..conveyor import ABOVE, BELOW, conveyor_store, reduce_conveyor
from .test_notes import _reduce, _store


@pytest.fixture(scope="module")
def conveyor(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("conveyor")
    return reduce_conveyor(conveyor_store(tmp / "conveyor.zarr"), tmp / "out")


def test_below_lift_off_x_moves_by_rounding_only_and_no_particle_counts_as_moving(conveyor):
    df, _ = conveyor
    row = df.iloc[BELOW]
    assert row["f"] == 50.0 and row["n_particles"] == 8 and row["n_moving"] == 0
    assert abs(row["D"]) < 1e-20  # x changed by rounding: D is no diffusion coefficient


def test_below_lift_off_d_status_says_no_mover_and_no_d_drift_or_pe_is_quoted(conveyor):
    df, _ = conveyor
    row = df.iloc[BELOW]
    assert row["D_status"].startswith("no mover among 8")
    # a finite D_hi (the CI the stopping rule read) is said to be motion within the cells
    assert ("motion within the cells" in row["D_status"]) == (not math.isnan(row["D_hi"]))
    assert row["mover_share_hi"] == pytest.approx(1 - 0.05 ** (1 / 8))
    assert row["D_drift_status"].startswith("no mover among 8")
    for col in ("D_drift", "D_drift_lo", "D_drift_hi", "Pe", "v_lo", "v_hi"):
        assert math.isnan(row[col]), col
    assert row["v_status"] == "no mover"


def test_below_lift_off_no_ergodicity_verdict_is_given(conveyor):
    df, _ = conveyor
    row = df.iloc[BELOW]
    for col in ("ergodic", "families_agree", "eb_ok", "level_ok", "decay_ok", "spread_ok",
                "steady"):
        assert pd.isna(row[col]), col
    assert row["verdict"].startswith("n/a: no particle left its cell")


def test_above_lift_off_the_running_away_conveyor_is_accelerating_with_a_not_v_plus_ci(conveyor):
    df, _ = conveyor
    row = df.iloc[ABOVE]
    assert row["n_moving"] == 8 and row["v_status"] == "accelerating" and not row["steady"]
    assert math.isnan(row["v_lo"]) and math.isnan(row["v_hi"]) and math.isnan(row["Pe"])
    assert row["v"] < 0 and row["a_lo"] <= row["a"] <= row["a_hi"] < 0  # speeding up downhill
    # a is dv over half the analysed run (T_a = 9 s), its CI dv's scaled alike
    for s in ("", "_lo", "_hi"):
        assert row[f"a{s}"] == pytest.approx(row[f"dv{s}"] / 4.5, rel=1e-12)
    assert row["D_status"].endswith("accelerating (v_status): D includes the acceleration")


def test_reduce_says_once_on_stderr_where_the_drift_accelerates(conveyor):
    _, lines = conveyor
    (line,) = [s for s in lines if "accelerates" in s]
    assert line.startswith("conveyor: warning: the drift accelerates") and "1 point (80 Hz)" in line
    assert "not a drift" in line


def test_a_steady_drift_stays_ok_with_its_ci_and_no_line(tmp_path):
    # every particle drifts at -2 mm/s with noise (D = 0.45 mm²/s), tilt 5°
    steps = np.random.default_rng(2).standard_normal((64, 201)) * 0.3 - 0.2
    df, lines = _reduce(_store(tmp_path, np.cumsum(steps, axis=1), "tilt = 5.0"), tmp_path)
    row = df.iloc[0]
    assert row["v_status"] == "ok" and row["steady"] and row["n_moving"] == 64
    assert row["v_lo"] <= -2.0 <= row["v_hi"] and math.isfinite(row["Pe"])
    assert row["a_lo"] <= 0.0 <= row["a_hi"]
    assert not any("accelerates" in s for s in lines)
