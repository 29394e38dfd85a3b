import math

import pandas as pd
import pytest

from pipeline.studies.dissipation.cuts import RESOLVED, compare_cut


def table(rows):
    return pd.DataFrame(rows, columns=["f", "D", "D_lo", "D_hi", "stop"])


def test_only_shared_frequencies_are_compared():
    a = table([(50.0, 1.0, 0.9, 1.1, "target met"), (51.0, 1.0, 0.9, 1.1, "target met")])
    b = table([(50.0, 1.0, 0.9, 1.1, "target met"), (50.4, 1.0, 0.9, 1.1, "target met")])
    assert compare_cut(a, b, 9.0, 9.0)["f"].tolist() == [50.0]


def test_two_values_agree_within_the_combined_half_widths_facing_each_other():
    a = table([(60.0, 100.0, 90.0, 110.0, "target met")])
    # 110 - 100 faces up, 112 - 104 faces down: sqrt(10² + 8²) = 12.8 ≥ 12; 114 - 110: 10.8 < 14
    assert compare_cut(a, table([(60.0, 112.0, 104.0, 130.0, "target met")]), 9, 9)["agree"][0] == 1
    assert compare_cut(a, table([(60.0, 114.0, 110.0, 130.0, "target met")]), 9, 9)["agree"][0] == 0


def test_a_point_resolved_to_d_resolved_is_judged_at_its_scenes_resolution():
    zero = table([(54.0, 0.0, 0.0, 1e-6, RESOLVED)])
    small = table([(54.0, 6.0, 5.0, 7.0, "target met")])
    assert compare_cut(zero, small, 9.0, 9.0)["agree"][0] == 1  # within the 9 mm²/s resolution
    assert compare_cut(zero, small, 0.75, 0.75)["agree"][0] == 0  # not at 0.75 mm²/s


def test_a_failed_estimator_is_not_compared():
    a = table([(55.6, math.nan, math.nan, math.nan, "target met")])
    b = table([(55.6, 1.0, 0.5, 1.5, "target met")])
    assert math.isnan(compare_cut(a, b, 9.0, 9.0)["agree"][0])


def test_the_resolutions_are_kept_beside_each_row():
    a = table([(60.0, 1.0, 0.9, 1.1, "target met")])
    row = compare_cut(a, a, 9.0, 0.75).iloc[0]
    assert (row["d_resolved"], row["d_resolved_ref"]) == pytest.approx((9.0, 0.75))


def test_a_fixed_size_scene_without_stop_reasons_is_compared_too():
    a = table([(60.0, 1.0, 0.9, 1.1, "target met")]).drop(columns="stop")
    b = table([(60.0, 1.05, 0.95, 1.15, "target met")]).drop(columns="stop")
    row = compare_cut(a, b, 0.0, 0.0).iloc[0]
    assert row["agree"] == 1 and row["stop"] == "" and row["stop_ref"] == ""
