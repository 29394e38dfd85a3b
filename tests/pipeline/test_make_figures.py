"""The make_figures entry: its scenes are valid workflows, and --fast makes draft versions."""

from __future__ import annotations

import tomllib

import pytest

from pipeline.make_figures import (
    SCENES,
    _toml_dump,
    draft_text,
    load_scene,
    scene_label,
    scene_names,
    scene_path,
)


@pytest.mark.parametrize("name", SCENES)
def test_every_scene_is_a_valid_workflow_at_both_accuracies(name):
    paper, draft = load_scene(name), load_scene(name, fast=True)
    assert draft.accuracy.preset == "draft"
    assert draft.frequencies == paper.frequencies and draft.families == paper.families
    assert draft.fingerprint() != paper.fingerprint()  # a separate store


def test_draft_collision_scenes_are_short_and_record_after_a_transient():
    study = load_scene("locking", fast=True)
    assert study.accuracy.t_max == 60.0 and study.accuracy.n_particles == 4
    assert study.observables.collisions_from < study.accuracy.t_max


def test_a_workflow_file_wins_over_the_built_in_scene():
    assert scene_label("figure2") == "workflows/figure2.toml"
    assert scene_label("locking") == "pipeline/scenes/locking.toml"


def test_every_scene_and_workflow_is_found_through_the_package():
    assert set(SCENES) | {"smoke", "accuracy"} <= set(scene_names())
    with pytest.raises(FileNotFoundError, match="allowed: .*smoke"):
        scene_path("no_such_scene")


def test_toml_dump_round_trips_a_workflow_document():
    text = scene_path("ergodicity").read_text()
    doc = tomllib.loads(text)
    assert tomllib.loads(_toml_dump(doc)) == doc
    assert tomllib.loads(draft_text(text))["accuracy"] == {"preset": "draft"}
