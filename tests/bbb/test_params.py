import math

import pytest

from bbb import Numerics, Params


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
        ("R", 0.9, "R ≥ S/2"),
        ("alpha", 0.0, "0 < alpha ≤ 1"),
        ("alpha", 1.5, "0 < alpha ≤ 1"),
        ("beta", -0.1, "0 ≤ beta ≤ 1"),
        ("beta", 1.01, "0 ≤ beta ≤ 1"),
        ("A", -0.1, "A ≥ 0"),
        ("f", 0.0, "f > 0"),
        ("g", -9800.0, "g > 0"),
        ("S", 0.0, "S > 0"),
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


def test_unknown_preset_lists_the_allowed_ones():
    with pytest.raises(ValueError, match="klages2004"):
        Params.preset("nope", f=60.0)


def test_params_are_frozen():
    p = Params.preset("klages2004", f=60.0)
    with pytest.raises(AttributeError):
        p.f = 61.0  # type: ignore[misc]


@pytest.mark.parametrize(("field", "value"), [("tol_t", 0.0), ("tol_t", 1e-3), ("v_stick", -1.0),
                                              ("max_step", 2.0), ("max_step", math.nan)])
def test_invalid_numerics_name_the_knob(field, value):
    with pytest.raises(ValueError, match=f"Numerics.{field}"):
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
