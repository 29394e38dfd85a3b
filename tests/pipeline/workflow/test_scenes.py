"""The shipped scenes by name (pipeline/workflow/scenes.py): one resolver for every WORKFLOW
argument -- a path that exists wins, else a scene's name, else one line naming the closest
names -- and what `bbb scenes` lists of each (study, description)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from pipeline.workflow.scenes import (
    ROOT,
    load_named,
    scene_description,
    scene_names,
    scene_path,
    scene_study,
    workflow_file,
)
from pipeline.workflow.study import WorkflowError

from ..helpers import TINY


def test_a_scene_name_loads_the_shipped_scene_from_any_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    study = load_named("smoke")
    assert study.name == "smoke" and study.source == "workflows/smoke.toml"


def test_a_path_that_exists_wins_over_the_scene_of_that_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("smoke").write_text(TINY)  # a file named like a scene
    assert load_named("smoke").name == "tiny" and workflow_file("smoke") == Path("smoke")


def test_an_unknown_name_is_one_line_naming_the_closest_scenes_and_bbb_scenes(tmp_path,
                                                                              monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(WorkflowError) as e:
        load_named("smok")
    assert str(e.value) == ("smok: no such workflow file or shipped scene (did you mean "
                            "'smoke'?); allowed: a TOML file, or a scene name that `bbb scenes` "
                            "lists")


def test_the_file_of_a_scene_name_is_the_packages_not_the_current_directorys(tmp_path,
                                                                             monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = workflow_file("accuracy")
    assert path.is_absolute() and path == Path(str(scene_path("accuracy")))
    assert tomllib.loads(path.read_text())["study"]["name"] == "accuracy"


def test_every_shipped_scene_has_a_one_line_description():
    missing = [n for n in scene_names() if not scene_description(n)]
    assert missing == []
    assert all("\n" not in scene_description(n) and len(scene_description(n)) < 100
               for n in scene_names())


def test_a_scenes_study_is_its_folder():
    assert scene_study("smoke") == "workflows" and scene_study("contact") == "contact"
    assert all((ROOT / "pipeline" / "studies" / scene_study(n)).is_dir()
               for n in scene_names() if scene_study(n) != "workflows")
