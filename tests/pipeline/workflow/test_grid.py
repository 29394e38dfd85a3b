"""The [grid] table (pipeline.workflow.grid, Study.axes and Study.points): sweep axes over
bbb.Params keys, their points and each point's Params, the one-line refusals of bad grids, and
the grid in the fingerprint while a workflow without one keeps its own."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.workflow.identity import f_key
from pipeline.workflow.load import GridNotRunnable, WorkflowError, parse_workflow

from ..helpers import TINY

# TINY is 30 lines; the [grid] header is line 31, its first axis line 32
GRID = TINY + "[grid]\nalpha = [0.5, 0.7]\n"


def parse(text: str):
    return parse_workflow(text, source="wf.toml")


def with_grid(axes: str) -> str:
    return TINY + "[grid]\n" + axes + "\n"


def with_param(line: str, text: str = TINY) -> str:
    return text.replace('preset = "klages2004"', f'preset = "klages2004"\n{line}', 1)


def error_of(text: str) -> str:
    with pytest.raises(WorkflowError) as e:
        parse(text)
    assert "\n" not in str(e.value)
    return str(e.value)


def test_points_are_the_grid_axes_in_order_with_frequency_innermost():
    s = parse(with_grid('contact = ["stick", "slide"]\nalpha = [0.5, 0.7]'))
    assert [a for a, _ in s.axes] == ["contact", "alpha", "f"]
    assert [(p.grid, p.f) for p in s.points] == [
        ((("contact", c), ("alpha", a)), f)
        for c in ("stick", "slide") for a in (0.5, 0.7) for f in (54.0, 60.0)]


def test_each_point_has_the_params_of_its_values_and_frequency():
    s = parse(GRID)
    assert [(p.params.alpha, p.params.f) for p in s.points] == [
        (0.5, 54.0), (0.5, 60.0), (0.7, 54.0), (0.7, 60.0)]


def test_without_a_grid_the_points_are_the_frequencies_with_their_params():
    s = parse(TINY)
    assert [(p.f, p.grid, p.params) for p in s.points] == [
        (f, (), s.params(f)) for f in s.frequencies]


def test_gamma_in_the_grid_gives_that_peak_acceleration_at_each_point():
    s = parse(with_grid("Gamma = [1.5, 3.0]"))
    assert [round(p.params.gamma, 12) for p in s.points] == [1.5, 1.5, 3.0, 3.0]


def test_gamma_in_params_gives_that_peak_acceleration_at_each_frequency():
    s = parse(with_param("Gamma = 2.5"))
    assert [round(s.params(f).gamma, 12) for f in s.frequencies] == [2.5, 2.5]


def test_gamma_in_params_stands_for_A_in_the_resolved_parameters():
    s = parse(with_param("Gamma = 2.5"))
    assert s.base_params["Gamma"] == 2.5 and "A" not in s.base_params


def test_invalid_skip_leaves_out_exactly_the_points_params_refuses():
    # slide needs R >= 1.05 S/2 = 1.05: the (R = 1, slide) points are invalid
    s = parse(with_grid('R = [1.0, 15.0]\ncontact = ["stick", "slide"]\ninvalid = "skip"'))
    assert [(p.params.R, p.params.contact) for p in s.points[::2]] == [
        (1.0, "stick"), (15.0, "stick"), (15.0, "slide")]


def test_an_invalid_point_is_refused_in_one_line_naming_it():
    msg = error_of(with_grid('R = [1.0, 15.0]\ncontact = ["stick", "slide"]'))
    assert msg.startswith("wf.toml:33: grid.contact: invalid parameters at the point "
                          'f = 54 Hz, R = 1, contact = "slide": ')
    assert 'allowed: grid values that bbb.Params accepts at every point, or invalid = "skip"' in msg


def test_a_grid_of_only_invalid_points_is_refused_even_with_skip():
    msg = error_of(with_grid('alpha = [1.5, 2.0]\ninvalid = "skip"'))
    assert msg.startswith("wf.toml:32: grid.alpha: every point is invalid, e.g. f = 54 Hz, "
                          "alpha = 1.5: Params.alpha = 1.5 is out of range")


CONTACTS = "allowed: a non-empty list of distinct values, each a string: stick, slide, coulomb"
# id: (workflow text, the start of the one-line error, what it must say is allowed)
BAD = {
    "in params and grid": (with_param("alpha = 0.5", GRID), "wf.toml:33: grid.alpha: given in "
                           "both [params] and [grid]", "allowed: alpha in [params] (one value) "
                           "or in [grid] (an axis), not both"),
    "unknown axis": (with_grid("omega = [1.0, 2.0]"), "wf.toml:32: grid.omega: unknown key",
                     "allowed: an axis named by a [params] key (g, A, Gamma, R, S, alpha, beta, "
                     "tilt, throw, contact, mu, floor, depth, peak), or invalid"),
    "preset as an axis": (with_grid('preset = ["klages2004"]'), "wf.toml:32: grid.preset: "
                          "unknown key", "allowed: an axis named by a [params] key"),
    "empty list": (with_grid("alpha = []"), "wf.toml:32: grid.alpha: must be a non-empty list, "
                   "got array []", "allowed: a non-empty list of distinct values, each a number"),
    "not a list": (with_grid("alpha = 0.5"), "wf.toml:32: grid.alpha: must be a non-empty list, "
                   "got float 0.5", "allowed: a non-empty list of distinct values"),
    "mixed types": (with_grid('alpha = [0.5, "0.7"]'), "wf.toml:32: grid.alpha: mixed types "
                    "(number, string)", "allowed: a non-empty list of distinct values"),
    "a number for contact": (with_grid("contact = [1.0]"), "wf.toml:32: grid.contact: must be a "
                             "string, got float 1.0", CONTACTS),
    "unknown contact model": (with_grid('contact = ["stick", "glue"]'), "wf.toml:32: "
                              "grid.contact: unknown contact 'glue'",
                              CONTACTS),
    "duplicates": (with_grid("alpha = [0.5, 0.7, 0.5]"), "wf.toml:32: grid.alpha: repeated "
                   "values [0.5]", "allowed: a non-empty list of distinct values"),
    "duplicates as int and float": (with_grid("R = [15, 15.0]"), "wf.toml:32: grid.R: repeated "
                                    "values [15.0]", "allowed: a non-empty list"),
    "nan": (with_grid("alpha = [0.5, nan]"), "wf.toml:32: grid.alpha: must be finite",
            "allowed: a non-empty list of distinct values, each a number: 0 < alpha ≤ 1"),
    "Gamma with A in params": (with_param("A = 0.2", with_grid("Gamma = [1.5]")), "wf.toml:33: "
                               "grid.Gamma: Gamma with A", "allowed: A (mm) or Gamma (peak floor "
                               "acceleration in g), not both"),
    "A with Gamma in the grid": (with_grid("A = [0.1]\nGamma = [1.5]"), "wf.toml:32: grid.A: "
                                 "A with Gamma", "allowed: A (mm) or Gamma"),
    "Gamma with A in params only": (with_param("Gamma = 2.0\nA = 0.2"), "wf.toml:7: "
                                    "params.Gamma: given with A", "allowed: A (mm) or Gamma"),
    "negative Gamma": (with_grid("Gamma = [-1.0]"), "wf.toml:32: grid.Gamma: -1.0 is out of "
                       "range", "allowed: a non-empty list of distinct values, each a number: "
                       "0 ≤ Gamma ≤ 1000 (in g), not with A"),
    "no axis": (with_grid('invalid = "skip"'), "wf.toml:31: grid: no axis",
                "allowed: one or more axes such as alpha = [0.5, 0.7]"),
    "unknown invalid policy": (with_grid('alpha = [0.5]\ninvalid = "drop"'), "wf.toml:33: "
                               "grid.invalid: unknown invalid 'drop'", "allowed: refuse, skip"),
    "grid not a table": (TINY.replace("[study]", 'grid = "alpha"\n[study]'), "wf.toml:1: grid: "
                         "must be a table, got string", "allowed: [grid] with axes"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_a_bad_grid_is_refused_in_one_line_naming_line_key_and_what_is_allowed(case):
    text, start, allowed = BAD[case]
    msg = error_of(text)
    assert msg.startswith(start) and allowed in msg, msg


def test_grid_study_round_trips_through_its_dict():
    s = parse(with_grid('contact = ["stick", "slide"]\nalpha = [0.5, 0.7]\ninvalid = "skip"'))
    assert type(s).from_dict(s.to_dict()) == s


def test_the_fingerprint_holds_the_grid_axes_not_their_values():
    """A grid store grows along its points (a widened grid opens the same store)."""
    assert parse(GRID).fingerprint() == parse(GRID.replace("0.7]", "0.8]")).fingerprint()
    assert parse(GRID).fingerprint() != parse(GRID.replace("alpha", "beta")).fingerprint()


def test_a_grid_of_one_value_is_not_the_scene_without_a_grid():
    one = parse(GRID.replace("[0.5, 0.7]", "[0.5]"))
    assert one.fingerprint() != parse(with_param("alpha = 0.5")).fingerprint()


def test_invalid_skip_that_leaves_nothing_out_keeps_the_fingerprint():
    skip = GRID + 'invalid = "skip"\n'
    assert parse(GRID).fingerprint() == parse(skip).fingerprint()


def test_a_workflow_without_grid_stores_no_grid_keys():
    s = parse(TINY)
    assert not {"grid", "invalid"} & (set(s.to_dict()) | set(s.data_identity()))


def test_a_grid_point_has_the_chunk_seeds_of_the_1d_scene_at_its_value():
    """Common random numbers: the seed is (study seed, f, family, chunk), whatever the grid."""
    grid, line = parse(GRID), parse(with_param("alpha = 0.5"))
    for f in (54.0, 60.0):
        for fam_g, fam_l in zip(grid.families, line.families, strict=True):
            assert np.array_equal(grid.seed_sequence(f, fam_g, 1).generate_state(4),
                                  line.seed_sequence(f, fam_l, 1).generate_state(4))


def test_a_grid_points_key_is_its_frequency_key_and_grid_values():
    p = parse(GRID).points[3]
    assert p.key == (f_key(60.0), ("alpha", 0.7))


def test_the_per_frequency_params_refuse_a_grid_scene_in_one_line():
    with pytest.raises(GridNotRunnable, match=r"^wf\.toml:31: grid: "
                       r"Study\.params\(f\) knows one point per frequency, and this scene also "
                       r"sweeps alpha; allowed: a workflow without \[grid\]"):
        parse(GRID).params(60.0)


def test_a_tilt_axis_with_a_tilted_value_makes_the_floor_not_mirror_symmetric():
    assert not parse(with_grid("tilt = [0.0, 5.0]")).mirror_symmetric



def test_a_grid_line_is_the_study_with_its_values_in_params():
    assert parse(GRID).line({"alpha": 0.5}) == parse(with_param("alpha = 0.5"))


def test_a_grid_line_at_contact_stick_is_the_study_without_a_contact_override():
    assert parse(with_grid('contact = ["stick", "slide"]')).line({"contact": "stick"}) == parse(TINY)


def test_a_grid_line_keeps_the_fingerprint_of_the_scene_with_its_values_in_params():
    line = parse(with_grid("alpha = [0.5, 0.7]\nbeta = [0.9]")).line({"alpha": 0.7, "beta": 0.9})
    assert line.fingerprint() == parse(with_param("alpha = 0.7\nbeta = 0.9")).fingerprint()


def test_a_grid_line_whose_points_are_all_skipped_is_refused():
    s = parse(with_grid('R = [1.0, 15.0]\ncontact = ["stick", "slide"]\ninvalid = "skip"'))
    with pytest.raises(ValueError, match='^every point of the line R = 1, contact = "slide" is '
                       "skipped as invalid$"):
        s.line({"R": 1.0, "contact": "slide"})


def test_a_grid_line_off_the_grid_is_refused():
    with pytest.raises(ValueError, match=r"^alpha = 0.6 is not on the grid; allowed: 0.5, 0.7$"):
        parse(GRID).line({"alpha": 0.6})


# -- [grid.refine] --------------------------------------------------------------------------------
def test_grid_refine_reads_a_resolution_per_axis_and_its_settings():
    s = parse(GRID + "[grid.refine]\nf = 0.5\nalpha = 0.05\njumps = false\n")
    assert s.grid_refine.to == (("f", 0.5), ("alpha", 0.05))
    assert (s.grid_refine.extrema, s.grid_refine.jumps, s.grid_refine.quantity) == (
        True, False, "D")
    assert s.adaptive


def test_grid_refine_round_trips_through_the_stored_workflow():
    from pipeline.workflow.study import Study

    s = parse(GRID + "[grid.refine]\nalpha = 0.05\n")
    assert Study.from_dict(s.to_dict()).grid_refine == s.grid_refine


@pytest.mark.parametrize("body, needle", [
    ("beta = 0.1", "grid.refine.beta: unknown key (not an axis of this grid)"),
    ("alpha = 0", "grid.refine.alpha: must be a resolution, got 0"),
    ("f = 0.001", "grid.refine.f: must be a resolution, got 0.001"),
    ("alpha = true", "grid.refine.alpha: must be a resolution, got True"),
    ("extrema = true", "grid.refine: no axis to refine"),
    ('alpha = 0.1\nquantity = "v"', "grid.refine.quantity: v on a level floor"),
])
def test_a_bad_grid_refine_is_refused_in_one_line(body, needle):
    assert needle in error_of(GRID + "[grid.refine]\n" + body + "\n")


def test_a_string_axis_is_not_refined():
    text = with_grid('contact = ["stick", "slide"]') + "[grid.refine]\ncontact = 1\n"
    assert "unknown key (a string axis is not refined)" in error_of(text)


def test_frequency_refinement_of_a_map_points_to_grid_refine():
    text = GRID.replace("values = [54.0, 60.0]",
                        "values = [54.0, 57.0, 60.0]\nrefine = { to = 0.5 }")
    assert "allowed: [grid.refine] with a resolution f = ..." in error_of(text)


def test_mu_is_an_axis_of_the_coulomb_points_only():
    """contact x mu: one line per model without friction, one per mu under Coulomb."""
    s = parse(with_grid('contact = ["stick", "slide", "coulomb"]\nmu = [0.05, 0.3]'))
    lines = list(dict.fromkeys(p.grid for p in s.points))
    assert lines == [(("contact", "stick"), ("mu", 0.0)), (("contact", "slide"), ("mu", 0.0)),
                     (("contact", "coulomb"), ("mu", 0.05)), (("contact", "coulomb"), ("mu", 0.3))]
    assert [p.params.mu for p in s.points if p.grid == lines[3]] == [0.3, 0.3]


def test_the_frictionless_line_of_a_contact_mu_map_is_its_scene():
    s = parse(with_grid('contact = ["stick", "coulomb"]\nmu = [0.3]'))
    line = s.line({"contact": "stick", "mu": 0.0})
    assert [p.params for p in line.points] == [p.params for p in s.points
                                               if dict(p.grid)["contact"] == "stick"]
