"""The contact scenes: maps of contact x mu with one line per model, each with a shipped draft
of the same lines and families; the drafts and scenes ship in the wheel."""

from __future__ import annotations

import json

import pytest

from pipeline.studies.contact import SCENES
from pipeline.studies.contact.claims import LINES
from pipeline.studies.klages2004.make_figures import SCENES as PAPER_SCENES
from pipeline.workflow.scenes import load_scene, scene_label, shipped_draft

from ...helpers import run_outside


@pytest.mark.parametrize("name", SCENES)
def test_the_draft_has_the_maps_lines_families_and_observables(name):
    full, draft = load_scene(name), load_scene(name, fast=True)
    assert draft.source.startswith("pipeline/studies/contact/scenes/draft/")
    assert (draft.grid, draft.overrides) == (full.grid, full.overrides)
    assert draft.families == full.families and draft.name == full.name
    assert draft.observables == full.observables
    assert set(draft.frequencies) <= set(full.frequencies)
    assert draft.fingerprint() != full.fingerprint()  # a store of its own


@pytest.mark.parametrize("name", SCENES)
def test_the_maps_lines_are_the_contact_models(name):
    study = load_scene(name)
    assert {tuple(p.grid) for p in study.points} == {tuple(v.items()) for v in LINES.values()}
    for m, values in LINES.items():
        p = study.line(values).params(54.0)
        assert (p.contact, p.mu) == (values["contact"], values["mu"]), m
    f = load_scene("contact").frequencies
    assert min(f) == 46.0 and max(f) == 99.0
    assert {48.0 + 0.5 * i for i in range(21)} <= set(f)  # 0.5 Hz steps through 48-58


def test_scenes_without_a_shipped_draft_keep_the_generic_draft():
    for name in PAPER_SCENES:
        assert shipped_draft(name) is None
        assert load_scene(name, fast=True).source == scene_label(name)


def test_the_wheel_ships_the_contact_scenes_and_their_drafts(installed, tmp_path):
    code = ("import json; from pipeline.workflow.scenes import load_scene\n"
            "from pipeline.studies.contact import SCENES\n"
            "print(json.dumps([load_scene(n, fast=True).source for n in SCENES]))")
    got = json.loads(run_outside(installed, code, tmp_path).strip().splitlines()[-1])
    assert got == [f"pipeline/studies/contact/scenes/draft/{n}.toml" for n in SCENES]
