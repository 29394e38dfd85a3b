import math

import numpy as np
import pytest

from bbb import Params
from bbb.surface import cell_of, depth, surface_height, surface_normal


def test_depth_is_free_of_cancellation_for_tiny_offsets():
    # R - sqrt(R² - d²) → d²/(2R) for d ≪ R; the naive form returns 0 at d = 1e-9
    R = 15.0
    d = 1e-9
    assert depth(d, R) == pytest.approx(d * d / (2 * R), rel=1e-12)
    assert R - math.sqrt(R * R - d * d) == 0.0


def test_depth_at_the_cusp_of_a_half_circle_is_the_radius():
    assert depth(1.0, 1.0) == pytest.approx(1.0, rel=1e-15)


def test_flat_floor_has_zero_depth_and_vertical_normal():
    p = Params.preset("klages2004", f=60.0, R=math.inf)
    x = np.linspace(-3, 3, 13)
    assert np.all(depth(x, math.inf) == 0.0)
    nx, ny = surface_normal(p, x)
    assert np.all(nx == 0.0) and np.all(ny == 1.0)


def test_surface_is_periodic_in_x_and_time():
    p = Params.preset("klages2004", f=60.0)
    x = np.linspace(-1, 1, 7)
    t = 0.003
    h = surface_height(p, x, t)
    assert np.allclose(surface_height(p, x + 5 * p.S, t), h, atol=1e-12)
    assert np.allclose(surface_height(p, x, t + 7 / p.f), h, atol=1e-12)


def test_arc_tops_follow_the_floor_and_cusps_are_the_lowest_points():
    p = Params.preset("klages2004", f=60.0)
    t = 0.25 / p.f  # y_f = -A at a quarter period
    assert surface_height(p, 0.0, t) == pytest.approx(-p.A)
    cusp = surface_height(p, 1.0, t)
    assert cusp == pytest.approx(-p.A - (15 - math.sqrt(15**2 - 1)))
    assert np.all(surface_height(p, np.linspace(-1, 1, 101), t) >= cusp - 1e-15)


def test_normal_is_unit_perpendicular_to_the_surface_and_points_away_from_the_arc_centre():
    p = Params.preset("klages2004", f=60.0)
    x = np.array([-0.9, -0.3, 0.0, 0.4, 0.99, 2.4, -5.7])  # the last two in other cells
    nx, ny = surface_normal(p, x)
    assert np.allclose(nx**2 + ny**2, 1.0, rtol=0.0, atol=1e-14)
    # perpendicular to the tangent (1, dh/dx), the slope by central differences of the height
    h, t = 1e-6, 0.003
    slope = (surface_height(p, x + h, t) - surface_height(p, x - h, t)) / (2 * h)
    assert np.allclose(nx + ny * slope, 0.0, atol=1e-8)
    _, d = cell_of(x, p.S)
    assert np.array_equal(np.sign(nx), np.sign(d))  # away from the centre; 0 at the arc top
    assert np.all(ny > 0)


def test_cell_index_and_offset_reconstruct_x():
    x = np.array([-3.0, -1.0, 0.0, 0.999, 1.0, 123.4])
    k, d = cell_of(x, 2.0)
    assert np.allclose(k * 2.0 + d, x)
    assert np.all((d >= -1.0) & (d < 1.0))
