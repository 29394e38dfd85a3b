import math
import re

import numpy as np
import pytest

from bbb import Numerics, Params
from bbb.numerics import NUMERICS_RANGES
from bbb.params import PARAM_RANGES


def test_klages2004_preset_has_the_papers_parameters_and_the_corrected_amplitude():
    p = Params.preset("klages2004", f=60.0)
    assert (p.R, p.S, p.alpha, p.beta, p.g, p.A, p.f) == (15.0, 2.0, 0.7, 0.99, 9800.0, 0.1, 60.0)


def test_matyas2004_preset_has_the_earlier_parameters():
    p = Params.preset("matyas2004", f=60.0)
    assert (p.R, p.alpha, p.beta) == (25.0, 0.5, 0.99)


def test_gamma_is_one_near_the_papers_onset_of_diffusion():
    # docs/design.md, "Units and the amplitude": with A = 0.1 mm, Γ = A(2πf)²/g = 1 at f ≈ 49.8 Hz
    assert Params.preset("klages2004", f=49.82).gamma == pytest.approx(1.0, abs=2e-3)


@pytest.mark.parametrize(
    ("field", "value", "allowed"),
    [
        ("R", 0.9, "S/2 = 1 ≤ R ≤ 1e+15 (mm"),
        ("R", 1e16, "S/2 = 1 ≤ R ≤ 1e+15 (mm"),
        ("alpha", 0.0, "0 < alpha ≤ 1"),
        ("alpha", 1.5, "0 < alpha ≤ 1"),
        ("beta", -0.1, "0 ≤ beta ≤ 1"),
        ("beta", 1.01, "0 ≤ beta ≤ 1"),
        ("A", -0.1, "0 ≤ A ≤ 1e+06 (mm)"),
        ("f", 0.0, "0.001 ≤ f ≤ 100000 (Hz)"),
        ("f", 2e5, "0.001 ≤ f ≤ 100000 (Hz)"),
        ("g", -9800.0, "1 ≤ g ≤ 1e+08 (mm/s²)"),
        ("g", 1e9, "1 ≤ g ≤ 1e+08 (mm/s²)"),
        ("S", 0.0, "1e-06 ≤ S ≤ 1e+06 (mm)"),
        ("S", 1e300, "1e-06 ≤ S ≤ 1e+06 (mm)"),
        ("A", 100.0, "Γ = A(2πf)²/g = 1450.23 ≤ 1000, i.e. A ≤ 68.9547 mm at f = 60 Hz"),
    ],
)
def test_invalid_value_names_field_value_and_range(field, value, allowed):
    with pytest.raises(ValueError) as err:
        Params.preset("klages2004", **{"f": 60.0, field: value})
    message = str(err.value)
    assert f"Params.{field}" in message and repr(value) in message and allowed in message


@pytest.mark.parametrize("field", ["g", "A", "f", "S", "alpha", "beta"])
def test_non_finite_values_are_refused_except_an_infinite_radius(field):
    for bad in (math.nan, math.inf):
        with pytest.raises(ValueError, match=f"Params.{field}"):
            Params.preset("klages2004", **{"f": 60.0, field: bad})
    assert Params.preset("klages2004", f=60.0, R=math.inf).flat


def test_every_range_in_the_message_is_the_one_in_param_ranges():
    # the workflow reference (pipeline/README.md) reads the same Range objects
    for name, rng in PARAM_RANGES.items():
        if name in ("R", "mu"):
            continue
        above = rng.hi * 2 if rng.hi > 0 else 1.0
        with pytest.raises(ValueError, match=re.escape(rng.text(name))):
            Params.preset("klages2004", **{"f": 60.0, "A": 0.0, name: above})


@pytest.mark.parametrize("value", [np.float32(60.0), np.float64(60.0), np.int64(60), np.int32(60)])
def test_numpy_scalars_are_real_numbers(value):
    p = Params.preset("klages2004", f=value)
    assert p.f == 60.0 and type(p.f) is float
    assert Numerics(max_step=np.float32(0.5)).max_step == 0.5


@pytest.mark.parametrize("value", [True, np.bool_(True), "60", None, 60 + 0j, [60.0]])
def test_bools_strings_none_and_complex_are_not_real_numbers(value):
    with pytest.raises(ValueError, match=r"Params\.f must be a real number"):
        Params.preset("klages2004", f=value)


def test_unknown_preset_lists_the_allowed_ones():
    with pytest.raises(ValueError, match="klages2004"):
        Params.preset("nope", f=60.0)


def test_params_are_frozen():
    p = Params.preset("klages2004", f=60.0)
    with pytest.raises(AttributeError):
        p.f = 61.0  # type: ignore[misc]


@pytest.mark.parametrize(("field", "value"), [("tol_t", 0.0), ("tol_t", 1e-3), ("v_stick", -1.0),
                                              ("v_stick", 1e300), ("max_step", 2.0),
                                              ("max_step", 1e-300), ("max_step", math.nan)])
def test_invalid_numerics_name_the_knob_its_value_and_range(field, value):
    with pytest.raises(ValueError, match=re.escape(f"Numerics.{field} = {value!r} is out of range; "
                                                   f"allowed: {NUMERICS_RANGES[field].text(field)}")):
        Numerics(**{field: value})


@pytest.mark.parametrize("geometry", [dict(tilt=2.0), dict(throw=60.0)])
def test_every_contact_model_runs_on_the_conveyor(geometry):
    for contact in ("stick", "slide", "coulomb"):
        assert Params.preset("klages2004", f=60.0, contact=contact, **geometry).transport


def test_a_conveyor_with_near_vertical_cusp_walls_is_refused_with_what_is_allowed():
    with pytest.raises(ValueError, match=r"tilt = -30.0.*R = 1.0.*allowed: R ≥ S/2 · 1.05"):
        Params(g=9800.0, A=0.1, f=60.0, R=1.0, S=2.0, alpha=0.7, beta=0.99, tilt=-30.0)
    with pytest.raises(ValueError, match="vertical cusp walls"):
        Params(g=9800.0, A=0.1, f=60.0, R=1.049, S=2.0, alpha=0.7, beta=0.99, throw=45.0)
    assert Params(g=9800.0, A=0.1, f=60.0, R=1.05, S=2.0, alpha=0.7, beta=0.99, throw=45.0).transport
    assert Params(g=9800.0, A=0.1, f=60.0, R=1.0, S=2.0, alpha=0.7, beta=0.99).R == 1.0
