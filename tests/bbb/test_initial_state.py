"""An InitialState is checked: its arrays on construction, its place on the floor in
bbb.simulate (bbb.ensemble.InitialState.check), and the families' heights and speeds."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.ensemble import SPEED_CAP_FACTOR, InitialState, initial_state, speed_cap

P = Params.preset("klages2004", f=60.0)


def one(**changes) -> dict:
    """A particle at rest 1 mm above the top of arc 0 at floor phase 0, as field arrays."""
    arrays = dict(cell=np.zeros(1, np.int64), d=np.zeros(1), y=np.ones(1), vx=np.zeros(1),
                  vy=np.zeros(1), s=np.zeros(1), stuck=np.zeros(1, bool),
                  from_surface=np.zeros(1, bool))
    for k, v in changes.items():
        arrays[k] = np.full(1, v, dtype=arrays[k].dtype) if np.isscalar(v) else v
    return arrays


def test_the_speed_cap_is_a_multiple_of_the_floors_peak_speed_and_of_a_fall_through_a_cell():
    # independent arithmetic: A·2πf = 0.1·2π·60 = 37.699 mm/s, √(9800·2) = 140.0 mm/s
    assert speed_cap(P) == pytest.approx(SPEED_CAP_FACTOR * (37.69911 + 140.0), rel=1e-6)


@pytest.mark.parametrize("field", ["d", "y", "vx", "vy", "s"])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_a_non_finite_value_is_refused_naming_the_field_and_particle(field, bad):
    with pytest.raises(ValueError, match=rf"InitialState\.{field} of particle 0: {bad!r} .*allowed: finite"):
        InitialState(**one(**{field: bad}))


@pytest.mark.parametrize(("field", "value", "what"), [
    ("d", "a", "real numbers"), ("d", None, "real numbers"), ("cell", np.zeros(1), "integers"),
    ("stuck", np.zeros(1), "bools"), ("vx", np.zeros((1, 1)), "real numbers"),
    ("vy", np.array([1j]), "real numbers")])
def test_a_wrong_type_or_shape_is_refused(field, value, what):
    with pytest.raises(ValueError, match=rf"InitialState\.{field} must be a 1-d array of {what}"):
        InitialState(**one() | {field: value})


def test_fields_of_different_lengths_are_refused():
    with pytest.raises(ValueError, match=r"InitialState\.y holds 2 particles, InitialState\.cell 1"):
        InitialState(**one(y=np.ones(2)))


def test_numbers_become_float64_and_int64():
    st = InitialState(**one(d=np.zeros(1, np.float32), cell=np.zeros(1, np.int32)))
    assert st.d.dtype == np.float64 and st.cell.dtype == np.int64


@pytest.mark.parametrize(("changes", "match"), [
    (dict(d=5.0), r"InitialState\.d of particle 0: 5\.0 .*allowed: \|d\| ≤ S/2 = 1 \(mm\)"),
    (dict(d=5.0, y=-3.0), r"InitialState\.d of particle 0: 5\.0"),
    (dict(y=-3.0), r"InitialState\.y of particle 0: -3\.0 .*on or above the surface"),
    (dict(s=1.0 / 60.0), r"InitialState\.s of particle 0: .*0 ≤ s < 1/f"),
    (dict(s=-1e-9), r"InitialState\.s of particle 0"),
    (dict(vx=1e300), r"InitialState\.vx, vy of particle 0: speed 1e\+300 .*speed_cap = 17769\.9 mm/s"),
    (dict(y=1e12), r"InitialState\.y of particle 0: 1000000000000\.0 .*at most speed_cap²/\(2g\) = "
                   r"16110\.7 mm above"),
])
def test_a_state_off_the_floor_or_beyond_the_caps_is_refused_by_simulate(changes, match):
    with pytest.raises(ValueError, match=match):
        simulate(P, 1, 0.1, 0, InitialState(**one(**changes)))


def test_a_state_just_inside_every_cap_runs():
    cap = speed_cap(P)
    st = InitialState(**one(d=0.5 * P.S, vx=0.6 * cap, vy=0.79 * cap))
    assert simulate(P, 1, 0.05, 0, st).counters["anomalies"][0] == 0


def test_a_state_on_the_surface_to_rounding_is_accepted():
    # the surface at d = 0.7 mm, s = 3 ms computed as another caller might, 1e-13 mm low
    s, d = 0.003, 0.7
    y = -P.A * math.sin(P.omega * s) - (P.R - math.sqrt(P.R**2 - d**2)) - 1e-13
    simulate(P, 1, 0.05, 0, InitialState(**one(d=d, y=y, s=s, from_surface=np.ones(1, bool))))


@pytest.mark.parametrize(("family", "kw", "match"), [
    ("launched", dict(launch_speed=(0.0, 1e6)), r"launch_speed = \(0\.0, 1000000\.0\) is out of range; "
                                                r"allowed: 0 ≤ low ≤ high ≤ 17732\.2 \(mm/s"),
    ("dropped", dict(drop_height=(0.0, 1e300)), r"drop_height = .* ≤ 16110\.7 \(mm"),
    ("launched", dict(launch_speed=(0.0, "x")), r"launch_speed must be a pair"),
    ("dropped", dict(drop_height=(0.0, math.nan)), r"drop_height = .* is out of range"),
])
def test_a_family_beyond_the_caps_is_refused(family, kw, match):
    with pytest.raises(ValueError, match=match):
        initial_state(P, 2, np.random.SeedSequence(0), family, **kw)


def test_a_family_at_its_caps_passes_the_state_check():
    cap = speed_cap(P)
    for family, kw in (("launched", dict(launch_speed=(0.99 * (cap - P.A * P.omega),
                                                       cap - P.A * P.omega))),
                       ("dropped", dict(drop_height=(0.0, 0.999 * cap**2 / (2 * P.g))))):
        initial_state(P, 50, np.random.SeedSequence(1), family, **kw).check(P)
