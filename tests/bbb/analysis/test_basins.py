"""bbb.analysis.basins: shares with Wilson intervals, the escape rate of an exponential
transient, the basin entropy of grids whose entropy is known, and the classes D is held in."""

import math

import numpy as np

from bbb.analysis import basins as bs
from bbb.analysis import states as st


def test_shares_count_the_known_labels_and_name_the_unknown_share():
    lab = np.array([st.STUCK] * 30 + [st.DIFFUSING] * 10 + [st.UNKNOWN] * 10, np.int8)
    out = bs.shares(lab, 0.95)
    assert out["stuck"][0] == 0.75 and out["diffusing"][0] == 0.25
    assert out["unknown"][0] == 0.2
    lo, hi = out["stuck"][1:]
    assert lo < 0.75 < hi  # a real interval, never zero width


def test_escape_rate_of_an_exponential_transient_recovers_its_rate():
    rng = np.random.default_rng(5)
    rate, t_max, t0 = 0.2, 20.0, 0.5
    tau = t0 + rng.exponential(1 / rate, 4000)
    settled = tau < t_max
    k, lo, hi = bs.escape_rate(np.minimum(tau, t_max), settled, t0, t_max, rng, 300, 0.95)
    assert lo < rate < hi and abs(k - rate) < 0.02


def test_escape_rate_with_nobody_leaving_is_not_measured():
    tau = np.full(10, 20.0)
    k, lo, hi = bs.escape_rate(tau, np.zeros(10, bool), 0.5, 20.0, np.random.default_rng(1), 100, 0.95)
    assert math.isnan(k) and math.isnan(lo) and math.isnan(hi)


def test_basin_entropy_of_one_basin_is_zero_and_of_a_checkerboard_is_ln2():
    one = np.full((16, 16), st.STUCK, np.int8)
    s_b, s_bb, nb, n = bs.basin_entropy(one, 4)
    assert s_b == 0 and s_bb == 0 and nb == 0 and n == 16
    board = np.where((np.add.outer(np.arange(16), np.arange(16)) % 2) == 0, st.STUCK,
                     st.DIFFUSING).astype(np.int8)
    s_b, s_bb, nb, n = bs.basin_entropy(board, 4)
    assert math.isclose(s_bb, math.log(2)) and nb == n == 16


def test_basin_entropy_of_a_smooth_boundary_is_below_ln2():
    # a straight boundary: only the boxes it crosses mix, each at most half/half
    g = np.full((16, 16), st.STUCK, np.int8)
    g[:, 7:] = st.DIFFUSING  # the boundary inside the second column of boxes
    s_b, s_bb, nb, n = bs.basin_entropy(g, 4)
    assert 0 < s_bb <= bs.LOG2 and nb == 4 and s_b < s_bb


def test_basin_entropy_leaves_out_boxes_with_an_unknown_cell():
    g = np.full((8, 8), st.STUCK, np.int8)
    g[0, 0] = st.UNKNOWN
    assert bs.basin_entropy(g, 4)[3] == 3


def test_held_class_joins_chaotic_and_diffusing_and_refuses_a_change():
    lab = np.array([[st.CHAOTIC, st.STUCK, st.CHAOTIC, st.DIFFUSING],
                    [st.DIFFUSING, st.DIFFUSING, st.LOCKED_1, st.LOCKED_1],
                    [st.STUCK, st.STUCK, st.STUCK, st.LOCKED_1]], np.int8)
    x = np.array([[0.0, 0, 1.0, 3.0], [0, 0, 0, 0], [0, 0, 0, 0]], float)
    x = np.concatenate([x, x[:, -1:]], axis=1)  # 5 edges
    held, d = bs.held_classes(lab, x, 0.5)
    assert list(held) == [bs.IRREGULAR, bs.CLASSES.index("locked_1"), bs.NO_CLASS]
    assert math.isclose(d[0], (3.0 - 1.0) ** 2 / (2 * 1.0))
