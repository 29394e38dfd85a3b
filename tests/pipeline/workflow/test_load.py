"""Workflow TOML -> Study: schema, presets, grids, seeds, and one-line errors."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import pytest

from pipeline.workflow.accuracy import ACCURACY_PRESETS
from pipeline.workflow.keys import (
    README,
    SECTIONS,
    readme_with_reference,
    reference_markdown,
)
from pipeline.workflow.load import WorkflowError, load_workflow, parse_workflow
from pipeline.workflow.schema import InputError, Reader, declared, key

from ..helpers import TINY

WORKFLOWS = Path(__file__).resolve().parents[3] / "workflows"


def parse(text: str):
    return parse_workflow(text, source="wf.toml")


def error_of(text: str) -> WorkflowError:
    with pytest.raises(WorkflowError) as e:
        parse(text)
    assert "\n" not in str(e.value)
    return e.value


def test_smoke_workflow_parses():
    s = load_workflow(WORKFLOWS / "smoke.toml")
    assert s.name == "smoke"
    assert s.observables.positions and s.observables.collisions
    assert len(s.families) >= 2


@pytest.mark.parametrize("name", ["figure2", "figure3", "ergodicity"])
def test_shipped_workflows_parse(name):
    assert load_workflow(WORKFLOWS / f"{name}.toml").name == name


def test_figure2_has_124_frequencies_over_the_papers_range():
    f = load_workflow(WORKFLOWS / "figure2.toml").frequencies
    assert len(f) == 124 and f[0] == 50.0 and f[-1] == 99.2 and 70.8 in f


def test_figure3_records_collisions_at_the_six_frequencies():
    s = load_workflow(WORKFLOWS / "figure3.toml")
    assert s.frequencies == (54.0, 58.0, 60.0, 66.0, 72.0, 78.0)
    assert s.observables.collisions and not s.observables.positions


def test_ergodicity_has_several_families_and_the_named_frequencies():
    s = load_workflow(WORKFLOWS / "ergodicity.toml")
    assert len(s.families) >= 3
    assert {55.0, 58.0, 59.0, 60.0, 61.0, 62.0} <= set(s.frequencies)


def test_tiny_workflow_resolves_preset_and_overrides():
    s = parse(TINY)
    assert s.accuracy.preset == "draft"
    assert (s.accuracy.n_particles, s.accuracy.chunk_size, s.accuracy.n_chunks) == (8, 4, 2)
    assert s.accuracy.tol_t == ACCURACY_PRESETS["draft"]["tol_t"]  # not overridden
    assert s.params(60.0).f == 60.0 and s.params(60.0).alpha == 0.7
    assert s.sample_times()[-1] == 10.0 and len(s.sample_times()) == 21


def test_accuracy_may_be_a_preset_name():
    s = _with_accuracy('"paper"')
    assert s.accuracy == type(s.accuracy)(preset="paper", **ACCURACY_PRESETS["paper"])


_ACC_TABLE = TINY[TINY.index("[accuracy]"):TINY.index("[observables.positions]")]


def _with_accuracy(value: str):
    text = TINY.replace(_ACC_TABLE, "")
    return parse(f"accuracy = {value}\n" + text)


def test_frequency_grid_is_inclusive_and_in_mhz():
    s = parse(TINY.replace("values = [54.0, 60.0]", "start = 50.0\nstop = 51.0\nstep = 0.1"))
    assert s.frequencies == tuple(round(50 + 0.1 * i, 3) for i in range(11))
    assert s.f_mhz == tuple(range(50000, 51001, 100))


# -- errors: one line, file, line, key, allowed ---------------------------------------------
def test_syntax_error_names_file_and_line():
    e = error_of(TINY.replace("seed = 7", "seed = = 7"))
    assert e.line == 3 and str(e).startswith("wf.toml:3: TOML syntax error")


def test_unknown_key_names_line_and_allowed_keys():
    e = error_of(TINY.replace("t_max = 10.0", "t_max = 10.0\ntmax = 5"))
    assert e.key == "accuracy.tmax" and e.line == TINY.splitlines().index("t_max = 10.0") + 2
    assert "allowed: preset, n_particles" in str(e)


def test_unknown_top_level_table():
    assert error_of(TINY + "[extras]\nx = 1\n").key == "extras"


def test_wrong_type_is_named():
    e = error_of(TINY.replace("n_particles = 8", 'n_particles = "8"'))
    assert e.key == "accuracy.n_particles" and "integer" in str(e)


@pytest.mark.parametrize("bad", ["nan", "inf", "-1.0", "0.0"])
def test_bad_t_max_values(bad):
    assert error_of(TINY.replace("t_max = 10.0", f"t_max = {bad}")).key == "accuracy.t_max"


def test_chunk_size_must_divide_the_ensemble():
    e = error_of(TINY.replace("chunk_size = 4", "chunk_size = 3"))
    assert e.key == "accuracy.chunk_size" and "divide" in str(e)


def test_invalid_params_name_the_field_and_range():
    e = error_of(TINY.replace('preset = "klages2004"', 'preset = "klages2004"\nalpha = 1.5'))
    assert e.key == "params.alpha" and "0 < alpha ≤ 1" in str(e) and e.line == 7


def test_r_below_half_s_is_refused():
    e = error_of(TINY.replace('preset = "klages2004"', 'preset = "klages2004"\nR = 0.5'))
    assert e.key == "params.R" and "S/2" in str(e)


def test_f_is_not_a_params_override():
    assert error_of(TINY.replace('preset = "klages2004"',
                                 'preset = "klages2004"\nf = 60.0')).key == "params.f"


def test_empty_frequency_list():
    assert error_of(TINY.replace("[54.0, 60.0]", "[]")).key == "frequencies.values"


def test_frequency_finer_than_mhz_is_refused():
    e = error_of(TINY.replace("[54.0, 60.0]", "[54.0, 60.0005]"))
    assert "0.001 Hz" in str(e)


def test_repeated_frequency_is_refused():
    assert "repeated" in str(error_of(TINY.replace("[54.0, 60.0]", "[54.0, 54.0]")))


def test_grid_step_must_fit():
    e = error_of(TINY.replace("values = [54.0, 60.0]", "start = 50.0\nstop = 51.0\nstep = 0.3"))
    assert e.key == "frequencies.step"


def test_unknown_family_kind():
    e = error_of(TINY.replace('initial = "rest"', 'initial = "thrown"'))
    assert e.key == "families.rest.initial" and "rest, dropped, launched" in str(e)


def test_family_option_for_the_wrong_kind():
    e = error_of(TINY.replace('initial = "rest"', 'initial = "rest"\nlaunch_speed = [0, 1]'))
    assert e.key == "families.rest.launch_speed"


def test_no_observables_is_refused():
    text = TINY[: TINY.index("[observables.positions]")]
    assert error_of(text).key == "observables"


def test_record_from_beyond_t_max():
    e = error_of(TINY.replace("record_from = 2.0", "record_from = 20.0"))
    assert e.key == "observables.collisions.record_from" and "t_max" in str(e)


def test_unknown_accuracy_preset():
    e = error_of(TINY.replace('preset = "draft"', 'preset = "quick"'))
    assert "draft, standard, paper, reference" in str(e)


def test_missing_file():
    with pytest.raises(WorkflowError, match="no such workflow file"):
        load_workflow("/nonexistent/wf.toml")


# -- the declared schema --------------------------------------------------------------------
def test_readme_workflow_reference_is_the_one_generated_from_the_declarations():
    """pipeline/README.md holds the table that `python -m pipeline.workflow --reference --write`
    generates: a key's doc, range or default changed without regenerating it fails here."""
    readme = README.read_text(encoding="utf-8")
    assert readme == readme_with_reference(readme), (
        "pipeline/README.md's workflow reference is stale: run "
        "`python -m pipeline.workflow --reference --write`")


def test_the_reference_names_every_declared_key_with_its_default():
    ref = reference_markdown()
    for _, cls, _ in SECTIONS:
        for k in declared(cls):
            assert f"| `{k.name}` |" in ref and k.default_text() in ref


def test_a_key_added_later_with_omit_default_keeps_the_fingerprint_of_older_stores():
    """The way issues 12-15 add keys: declared once, omit_default=True, so a store made before
    the key existed still matches a workflow that leaves it at its default (target_ci, issue 12,
    is such a key)."""
    s = parse(TINY)
    at_default = replace(s, accuracy=replace(s.accuracy, target_ci=None))
    given = replace(s, accuracy=replace(s.accuracy, target_ci=0.03))
    assert at_default.fingerprint() == s.fingerprint() != given.fingerprint()
    assert "target_ci" not in s.to_dict()["accuracy"]


def test_a_declared_key_is_validated_with_its_range_in_one_line():
    @dataclass(frozen=True)
    class Target:
        target_ci: float = key(0.03, "relative CI half-width of D", units="fraction of D",
                               gt=0, lt=1)

    text = "[accuracy]\ntarget_ci = 1.5\n"
    with pytest.raises(InputError) as e:
        Reader(text, "wf.toml").table(Reader(text, "wf.toml").doc["accuracy"], ("accuracy",),
                                      Target)
    assert str(e.value) == ("wf.toml:2: accuracy.target_ci: 1.5 is out of range; allowed: "
                            "fraction of D, 0 < target_ci < 1")


# -- "did you mean": the closest allowed name, and the line of a misspelled section ----------
@pytest.mark.parametrize("edit, where, message", [
    (("[accuracy]", "[acuracy]"), "[acuracy]",
     "acuracy: unknown section (did you mean 'accuracy'?); allowed: study, params, frequencies"),
    (("[observables.collisions]", "[observables.colisions]"), "[observables.colisions]",
     "observables.colisions: unknown section (did you mean 'collisions'?); allowed: positions, "
     "collisions"),
    (("record = 40", "recrd = 40"), "recrd = 40",
     "observables.collisions.recrd: unknown key (did you mean 'record'?); allowed: record, "
     "record_from"),
    (("t_max = 10.0", "tmax = 10.0"), "tmax = 10.0",
     "accuracy.tmax: unknown key (did you mean 't_max'?); allowed: preset, n_particles"),
])
def test_an_unknown_key_or_section_names_its_line_and_the_closest_allowed_one(edit, where, message):
    text = TINY.replace(*edit)
    line = text.splitlines().index(where) + 1
    assert str(error_of(text)).startswith(f"wf.toml:{line}: {message}")


def test_a_misspelled_section_given_only_by_an_empty_sub_table_header_has_its_line():
    # [observablse.positions] holds no key: the section's line is its sub-table's header
    text = TINY.replace("[observables.positions]", "[observablse.positions]")
    e = error_of(text)
    assert e.key == "observablse" and e.line == text.splitlines().index("[observablse.positions]") + 1
    assert "(did you mean 'observables'?)" in str(e)


def test_an_unknown_key_far_from_every_allowed_one_suggests_nothing():
    assert "did you mean" not in str(error_of(TINY.replace("t_max = 10.0", "t_max = 10.0\nxyz = 1")))
