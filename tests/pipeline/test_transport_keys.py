"""The conveyor keys [params] tilt/throw (degrees) and the transport columns of `bbb reduce`."""

from __future__ import annotations

import pandas as pd
import pytest

from pipeline.reduce import reduce_store
from pipeline.scenes import load_scene
from pipeline.store import StudyStore
from pipeline.task import compute_chunk
from pipeline.workflow import WorkflowError, parse_workflow

from .helpers import TINY

#: fingerprints of the committed scenes without tilt/throw in the schema (main at f1f58a4,
#: computed from `git archive main`); the transport scenes are new and not listed
BEFORE = {
    "accuracy": "48ceb931f6416a71899aa64e03fe1d2b637cd3aa16de345e51f3b4e6949b080c",
    "ergodicity": "22cba6687e47cc436b14eed099def3c328fe50bf4db3595e4e39efadf5fdb267",
    "figure2": "dfea61bbcf49c107d38f4b6d84bc093e87046960225b5f7c3548b5cb03e4e48f",
    # figure2_matyas2004: its own target since 2026-11-23 (5 %, cap 4096; the scene explains)
    "figure2_matyas2004": "47781735b4ef9334c03da2ef5606aac1ec79ef4ff1af724ed3afe19e08a8ec17",
    "figure3": "2ca6f48b9bea73ce17807d694b11bdf6a7f0654ac8693c435d7972fa39aac377",
    "finescale": "5d2d9b20f6715454931ae2fa5a1c5aeaa2fab121a9cf89803f7b7d4fab118c7c",
    "locking": "d2b86776f65b2503595163072a4233b9cf84d6a51fa161e1cd2a9019994ac524",
    "locking_matyas2004": "5f6e4ec1397a51b6b3ddf0b41f2b9faea8540e9d35071ca4b435bc941f50d29c",
    "mechanisms": "4286ca121359b87343825282b8f73e165053d927535ba7ac4bbd8275377b39f9",
    "smoke": "27388bc65e6950507b8067cc506473e2a493d294ff3ad699bf8474b8454a2f86",
}
TRANSPORT_COLUMNS = {"v", "v_lo", "v_hi", "D_drift", "D_drift_lo", "D_drift_hi", "Pe"}


def _with(params: str) -> str:
    return TINY.replace('preset = "klages2004"', f'preset = "klages2004"\n{params}', 1)


@pytest.mark.parametrize("name", sorted(BEFORE))
def test_committed_scenes_keep_their_fingerprint(name):
    assert load_scene(name).fingerprint() == BEFORE[name]


def test_tilt_and_throw_at_their_defaults_keep_the_fingerprint_and_others_change_it():
    plain = parse_workflow(TINY).fingerprint()
    assert parse_workflow(_with("tilt = 0.0\nthrow = 90.0")).fingerprint() == plain
    tilted = parse_workflow(_with("tilt = 2.0"))
    assert tilted.fingerprint() != plain
    assert (tilted.params(60.0).tilt, tilted.params(60.0).throw) == (2.0, 90.0)
    assert parse_workflow(_with("throw = 60.0")).fingerprint() not in (plain, tilted.fingerprint())


@pytest.mark.parametrize("line,allowed", [("tilt = 40.0", "|tilt| ≤ 30"),
                                          ("throw = 5.0", "10 ≤ throw ≤ 170")])
def test_an_out_of_range_angle_is_one_line_naming_the_key(line, allowed):
    with pytest.raises(WorkflowError) as e:
        parse_workflow(_with(line), source="wf.toml")
    msg = str(e.value)
    assert "\n" not in msg and "params." + line.split()[0] in msg and allowed in msg


def _reduced(text: str, tmp_path) -> pd.DataFrame:
    study = parse_workflow(text)
    store = StudyStore.create_or_open(tmp_path / "s.zarr", study)
    for fi in range(len(study.frequencies)):
        for mi in range(len(study.families)):
            for ci in range(study.accuracy.n_chunks):
                compute_chunk(store, fi, mi, ci)
    return reduce_store(tmp_path / "s.zarr", tmp_path / "out", echo=lambda s: None)["diffusion"]


def test_reduce_adds_transport_columns_only_for_a_conveyor(tmp_path):
    plain = _reduced(TINY, tmp_path / "plain")
    assert not TRANSPORT_COLUMNS & set(plain.columns)
    tilted = _reduced(_with("tilt = 10.0"), tmp_path / "tilted")
    assert TRANSPORT_COLUMNS <= set(tilted.columns)
    # downhill is -x (gravity along the plane -g sin φ): every frequency drifts that way
    assert (tilted["v_hi"] < 0).all(), tilted[["f", "v", "v_lo", "v_hi"]]
    assert (tilted["D_drift"] < tilted["D"]).all()  # the drift's v² Δ² is out of the MSD


def test_a_contact_model_on_the_conveyor_runs_and_near_vertical_cusps_are_one_line():
    study = parse_workflow(_with('tilt = 2.0\ncontact = "coulomb"\nmu = 0.3'), source="wf.toml")
    assert study.params(60.0).contact == "coulomb" and study.params(60.0).transport
    with pytest.raises(WorkflowError) as e:
        parse_workflow(_with('tilt = 2.0\ncontact = "coulomb"\nmu = 0.3\nR = 1.0'),
                       source="wf.toml")
    msg = str(e.value)
    assert "\n" not in msg and "wf.toml" in msg and "contact" in msg and "R = 1.0" in msg
    assert "allowed" in msg and "stick" in msg
