"""The contact scenes: one per model that differ only in the contact model, each with a shipped
draft of the same model and families; the drafts and scenes ship in the wheel."""

from __future__ import annotations

import json

import pytest

from pipeline.make_figures import SCENES as PAPER_SCENES
from pipeline.studies.contact import SCENES
from pipeline.studies.contact.claims import MODELS
from pipeline.workflow.scenes import load_scene, scene_label, shipped_draft

from ..klages2004.test_make_figures import _run_outside, installed  # noqa: F401 (fixture)


def _model(study) -> tuple:
    return study.overrides.get("contact", "stick"), study.overrides.get("mu")


@pytest.mark.parametrize("name", SCENES)
def test_the_draft_has_the_scenes_model_families_and_observables(name):
    full, draft = load_scene(name), load_scene(name, fast=True)
    assert draft.source.startswith("pipeline/studies/contact/scenes/draft/")
    assert _model(draft) == _model(full)
    assert draft.families == full.families and draft.name == full.name
    assert draft.observables == full.observables
    assert set(draft.frequencies) <= set(full.frequencies)
    assert draft.fingerprint() != full.fingerprint()  # a store of its own


def test_the_model_scenes_differ_only_in_the_contact_model():
    scenes = [load_scene(f"contact_{m}") for m in MODELS]
    assert len({_model(s) for s in scenes}) == len(MODELS)
    for s in scenes[1:]:
        assert (s.frequencies, s.families, s.accuracy, s.observables) == (
            scenes[0].frequencies, scenes[0].families, scenes[0].accuracy, scenes[0].observables)
    f = scenes[0].frequencies
    assert min(f) == 46.0 and max(f) == 99.0
    assert {48.0 + 0.5 * i for i in range(21)} <= set(f)  # 0.5 Hz steps through 48-58


def test_scenes_without_a_shipped_draft_keep_the_generic_draft():
    for name in PAPER_SCENES:
        assert shipped_draft(name) is None
        assert load_scene(name, fast=True).source == scene_label(name)


def test_the_wheel_ships_the_contact_scenes_and_their_drafts(installed, tmp_path):  # noqa: F811
    code = ("import json; from pipeline.workflow.scenes import load_scene\n"
            "from pipeline.studies.contact import SCENES\n"
            "print(json.dumps([load_scene(n, fast=True).source for n in SCENES]))")
    got = json.loads(_run_outside(installed, code, tmp_path).strip().splitlines()[-1])
    assert got == [f"pipeline/studies/contact/scenes/draft/{n}.toml" for n in SCENES]
