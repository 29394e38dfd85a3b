"""The ratchet scenes: the shipped scene and its draft load through the engine on a level,
vertically vibrated sawtooth floor, with independent particles, every off-centre peak beside
its mirror partner and the centred control, on the grid the claims' scope names."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.studies.ratchet.claims import ALPHAS, CENTRE, F_STEP, PEAKS, SCENE
from pipeline.workflow.scenes import load_scene


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_scene_and_its_draft_pair_every_peak_with_its_mirror_and_hold_the_centred_control(fast):
    study = load_scene(SCENE, fast)
    grid = dict(study.grid)
    peaks = [float(p) for p in grid["peak"]]
    assert CENTRE in peaks
    assert all(any(np.isclose(1 - p, q) for q in peaks) for p in peaks)
    p = study.points[0].params
    assert p.floor == "sawtooth" and p.depth > 0 and p.tilt == 0.0 and p.throw == 90.0
    assert [fam.mirror for fam in study.families] == [False]
    assert dict(study.observables.more).get("impacts") is not None


def test_the_shipped_scene_is_the_grid_the_claims_scope_names():
    study = load_scene(SCENE, False)
    grid = dict(study.grid)
    assert tuple(float(p) for p in grid["peak"]) == PEAKS
    assert tuple(float(a) for a in grid["alpha"]) == ALPHAS
    f = sorted({pt.f for pt in study.points})
    assert np.allclose(np.diff(f), F_STEP) and (f[0], f[-1]) == (40.0, 100.0)


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_states_scene_records_every_collision_from_the_start_on_off_centre_teeth(fast):
    from pipeline.studies.ratchet.reversal_states import STATES_SCENE, WINDOW

    study = load_scene(STATES_SCENE, fast)
    obs = study.observables
    assert obs.collisions_from == 0.0 and obs.collisions_record >= 1000
    assert all(pt.params.floor == "sawtooth" and pt.params.peak < CENTRE for pt in study.points)
    assert [fam.mirror for fam in study.families] == [False]
    assert study.accuracy.t_max >= 2 * WINDOW
