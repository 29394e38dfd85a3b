"""The onset scenes: the D(f, R) map spans R from 1.05 S/2 to 50 mm at two or more α from
rest on the arcs, the sine scene runs the sine floor, both on the 1 Hz grid the claims' band
is, and each draft loads too."""

from __future__ import annotations

import pytest

from pipeline.studies.onset.claims import MAP, SINE
from pipeline.studies.onset.lines import step_of
from pipeline.workflow.scenes import load_scene


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_map_spans_r_from_1_05_half_s_to_50_mm_at_two_or_more_alphas_from_rest(fast):
    study = load_scene(MAP, fast)
    grid = dict(study.grid)
    S = study.points[0].params.S
    assert min(grid["R"]) == pytest.approx(1.05 * S / 2) and max(grid["R"]) == 50.0
    assert len(grid["alpha"]) >= 2
    assert {fam.name for fam in study.families} == {"rest"}
    assert {pt.params.floor for pt in study.points} == {"arc"}


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_sine_scene_runs_the_sine_floor_at_several_depths_from_rest(fast):
    study = load_scene(SINE, fast)
    grid = dict(study.grid)
    assert {pt.params.floor for pt in study.points} == {"sine"} and len(grid["depth"]) >= 2
    assert len(grid["alpha"]) >= 2 and {fam.name for fam in study.families} == {"rest"}


def test_both_scenes_state_the_claims_band_as_their_grid_step_of_1_hz():
    assert step_of(MAP) == step_of(SINE) == 1.0
