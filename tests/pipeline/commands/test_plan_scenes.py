"""`bbb scenes` (pipeline/commands/plan_scenes.py): one line per shipped scene with its study,
description and cost, the cost read from `bbb plan`'s pilot cache, never measured unless
asked (--cost)."""

from __future__ import annotations

import os
from pathlib import Path

from pipeline.cli import main
from pipeline.commands.plan_scenes import study_cost
from pipeline.execute.pilot import pilot_rates
from pipeline.execute.plan import predict
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.scenes import scene_description, scene_names, scene_study

from ..helpers import TINY


def test_bbb_scenes_prints_one_line_per_shipped_scene_with_study_and_description(
        tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)  # no pilot cache here: every cost points to bbb plan
    assert main(["scenes"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [ln.split()[0] for ln in lines] == scene_names()
    for name, line in zip(scene_names(), lines, strict=True):
        assert line.split()[1] == scene_study(name)
        assert f"? (bbb plan {name})" in line and line.endswith(scene_description(name))


def test_without_a_cached_pilot_the_cost_points_to_bbb_plan_and_nothing_is_measured(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    study = parse_workflow(TINY, source="tiny.toml")
    assert study_cost(study, hint="bbb plan tiny") == "? (bbb plan tiny)"
    assert not Path("runs").exists()  # no pilot was run (it would have cached itself)


def test_with_a_cached_pilot_the_cost_is_the_plans_prediction_on_this_machine(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    study = parse_workflow(TINY, source="tiny.toml")
    rates = pilot_rates(study)  # what `bbb plan` runs first: cached in runs/plan-cache
    cores = os.cpu_count() or 1
    plan = predict(study, rates, cores)
    cost = study_cost(study)
    assert cost == f"CPU {plan.cpu_s:.0f} s, wall {plan.wall_s:.0f} s on {cores} cores"
