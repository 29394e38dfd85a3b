"""The figure run finds its studies through the registry: ``--list`` names every registered
study with its scenes, without running anything."""

from __future__ import annotations

from pipeline.make_figures import main, scenes
from pipeline.studies.registry import STUDIES, study


def test_list_names_every_registered_study_with_its_scenes(capsys):
    assert main(["--list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines == [f"{n}: {', '.join(study(n).scenes)}" for n in STUDIES]
    assert {"figure2", "mechanisms", "transport", "contact", "protocol", "dissipation"} <= set(
        scenes())
