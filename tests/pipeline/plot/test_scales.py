"""The one rule of value axes and colour scales (pipeline/plot/scales.py): log past two
decades (symmetric-log with a 0), linear otherwise; a signed quantity linear and diverging,
centred at 0."""

from __future__ import annotations

import numpy as np
from matplotlib.colors import CenteredNorm, LogNorm, Normalize, SymLogNorm

from pipeline.plot.scales import DIVERGING, SEQUENTIAL, decades, value_scale


def test_decades_count_the_positive_finite_values_only():
    assert decades([1.0, 10.0, 1000.0, np.nan, 0.0, -5.0]) == 3.0
    assert decades([4.0]) == 0.0


def test_d_spanning_more_than_two_decades_is_log_and_at_most_two_is_linear():
    assert value_scale("D", [0.5, 5.0, 50.1]).kind == "log"
    assert value_scale("D", [0.5, 5.0, 50.0]).kind == "linear"  # exactly two decades
    assert value_scale("D", [3.0, 40.0, np.nan]).kind == "linear"


def test_a_zero_among_values_spanning_decades_makes_the_axis_symlog_keeping_the_zero():
    s = value_scale("D", [0.0, 0.02, 30.0])
    assert (s.kind, s.linthresh) == ("symlog", 0.02)
    norm = s.norm([0.0, 0.02, 30.0])
    assert isinstance(norm, SymLogNorm) and norm(0.0) == 0.0  # 0 drawn, not masked


def test_a_signed_quantity_is_linear_and_diverging_centred_at_zero_whatever_its_values():
    for values in ([-15.0, 3.0], [0.01, 400.0]):  # even all positive, spanning decades
        s = value_scale("v", values)
        assert (s.kind, s.signed, s.cmap) == ("linear", True, DIVERGING)
        norm = s.norm(values)
        assert isinstance(norm, CenteredNorm) and norm(0.0) == 0.5
        assert np.isclose(norm(-values[1]), 1 - norm(values[1]))
    assert value_scale("v_lo", [1.0]).signed


def test_an_unsigned_quantity_is_sequential_log_or_linear():
    assert value_scale("D", [1.0, 5000.0]).cmap == SEQUENTIAL
    assert isinstance(value_scale("D", [1.0, 5000.0]).norm([1.0, 5000.0]), LogNorm)
    norm = value_scale("D", [1.0, 5.0]).norm([1.0, 5.0])
    assert type(norm) is Normalize and (norm.vmin, norm.vmax) == (1.0, 5.0)
