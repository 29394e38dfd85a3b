"""The make_figures entry: its scenes are valid workflows, and --fast makes draft versions."""

from __future__ import annotations

import tomllib

import pytest

from pipeline.make_figures import SCENES, _toml_dump, draft_text, load_scene, scene_path


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
    assert scene_path("figure2").parent.name == "workflows"
    assert scene_path("locking").parent.name == "scenes"


def test_toml_dump_round_trips_a_workflow_document():
    text = scene_path("ergodicity").read_text()
    doc = tomllib.loads(text)
    assert tomllib.loads(_toml_dump(doc)) == doc
    assert tomllib.loads(draft_text(text))["accuracy"] == {"preset": "draft"}


def test_the_run_log_records_paths_relative_to_the_repository(tmp_path):
    import os

    from pipeline.make_figures import ROOT, run_log_entry

    for store in (ROOT / "runs" / "figure2.zarr", tmp_path / "runs" / "figure2.zarr"):
        entry = run_log_entry("figure2", str(store))
        assert not any(os.path.isabs(v) for v in entry.values()), entry
        assert (ROOT / entry["store"]).resolve() == store.resolve()
        assert (ROOT / entry["workflow"]).resolve() == scene_path("figure2").resolve()
    assert run_log_entry("locking", str(ROOT / "runs" / "locking.zarr")) == {
        "workflow": "pipeline/scenes/locking.toml", "store": "runs/locking.zarr"}


def test_the_committed_run_log_holds_no_absolute_path():
    import json

    from pipeline.make_figures import ROOT

    log = json.loads((ROOT / "figures" / "run_log.json").read_text())
    for name, entry in log["scenes"].items():
        for key in ("workflow", "store"):
            assert not entry[key].startswith("/"), (name, key, entry[key])
