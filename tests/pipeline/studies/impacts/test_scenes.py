"""The impact-phase scenes: the shipped scene and its draft load through the engine, ask for
the impacts observable, and reach from below the claims' frequencies into them."""

from __future__ import annotations

import pytest

from pipeline.studies.impacts.claims import F_FROM, SCENE
from pipeline.workflow.scenes import load_scene


@pytest.mark.parametrize("fast", [False, True], ids=["scene", "draft"])
def test_the_scene_and_its_draft_select_impacts_on_the_papers_floor_around_the_claims_frequencies(fast):
    study = load_scene(SCENE, fast)
    f = sorted(p.f for p in study.points)
    impacts = dict(study.observables.more).get("impacts")
    assert impacts is not None and dict(impacts)["lags"] >= 1
    assert study.preset == "klages2004" and not study.overrides
    assert {fam.name for fam in study.families} == {"rest", "launched"}
    assert f[0] < F_FROM <= f[-1] and sum(x >= F_FROM for x in f) >= 3
