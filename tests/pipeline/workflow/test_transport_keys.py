"""The conveyor keys [params] tilt/throw (degrees) and the transport columns of `bbb reduce`."""

from __future__ import annotations

import pandas as pd
import pytest

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.reduce import reduce_store
from pipeline.workflow.load import WorkflowError, parse_workflow
from pipeline.workflow.scenes import load_scene

from ..helpers import TINY

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
    # mechanisms: records per-collision jumps from 5 s since 2026-11-25 (x_jumps; the scene explains)
    "mechanisms": "3f917dc4900752a2632e5178276b796503be2693386c2eb8ed5ca8a4b6f11455",
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
    # a steady drift has its CI below 0; an accelerating one (no v CI) speeds up downhill
    steady = tilted["v_status"] == "ok"
    assert (tilted.loc[steady, "v_hi"] < 0).all(), tilted[["f", "v", "v_lo", "v_hi", "v_status"]]
    assert (tilted.loc[~steady, "v_status"] == "accelerating").all()
    assert (tilted.loc[~steady, "a_hi"] < 0).all(), tilted[["f", "a", "a_lo", "a_hi"]]
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


# -- mirror pairs ([families.NAME] mirror) ------------------------------------------------
#: fingerprints of the transport scenes on main before the mirror key: a scene that keeps
#: mirror at its default (or counts images by symmetry) stores exactly what it stored
TRANSPORT_BEFORE = {  # transport_t5 uses pairs (benchmarks/calibrations/transport_mirror.py): new data
    "transport_t0": "d29bf86c5ec522246c2568ba735018d228d8e8f87a3550cea362069a038ca875",
    "transport_t2": "dde996d3bb705442da2e8715a778c0b01d7c49cdc1f8ba79d628d21cd398a9f7",
    "transport_p60": "873d6e45b890d5a630bb4301499bd8e0564896c18d299fa18bc2d66ffe7d1d81",
    "transport_p30": "6ae9e64c635c68e5418383db81db026000d0e850ffe95c8046655bc0d165d904",
    "transport_sliding_stick": "dd56949fc5b88fe3807d60240e1a1b0ee5b192cc7ec0a8f7e5c99387404ddf19",
    "transport_sliding_coulomb": "9256f5bc024fa5f88b1d56e0a469a64fa86ebc1eefc2eb58433861bec8c232a6",
}
ODD = {"v", "v_lo", "v_hi", "dv", "dv_lo", "dv_hi", "dv_tol", "steady", "Pe", "v_by", "D_drift",
       "D_drift_lo", "D_drift_hi", "msd_slope_ratio", "msd_slope_ratio_lo", "msd_slope_ratio_hi",
       "diffusive", "v_status", "a", "a_lo", "a_hi"}
LEVEL = _with("tilt = 0.0\nthrow = 90.0")  # the transport columns on the paper's floor


def _mirror(text: str, value: str) -> str:
    return (text.replace('initial = "rest"', f'initial = "rest"\nmirror = {value}')
            .replace('initial = "launched"', f'initial = "launched"\nmirror = {value}'))


@pytest.mark.parametrize("name", sorted(TRANSPORT_BEFORE))
def test_transport_scenes_without_simulated_pairs_keep_their_fingerprint(name):
    """Now lines of the transport maps: each line, as the scene without a grid with its values
    in [params], has the fingerprint the scene had."""
    from pipeline.studies.transport.claims import LINES, SLIDING, SLIDING_MAP

    scene = SLIDING_MAP if name in {s for s, _, _ in SLIDING} else "transport"
    assert load_scene(scene).line(LINES[name]).fingerprint() == TRANSPORT_BEFORE[name]


def test_on_the_level_floor_mirror_images_change_nothing_stored_and_make_v_zero(tmp_path):
    on, off = parse_workflow(LEVEL), parse_workflow(_mirror(LEVEL, "false"))
    assert on.fingerprint() == off.fingerprint() == parse_workflow(TINY).fingerprint()
    a, b = _reduced(LEVEL, tmp_path / "on"), _reduced(_mirror(LEVEL, "false"), tmp_path / "off")
    assert (a["v_by"] == "mirror symmetry").all() and (b["v_by"] == "independent").all()
    for col in ("v", "v_lo", "v_hi", "dv", "dv_lo", "dv_hi"):
        assert (a[col] == 0.0).all(), col
    assert a["steady"].all() and (b["v"] != 0.0).any()
    # every even column (D, EB, stationarity, ...) bit for bit as without images
    even = [c for c in a.columns if c not in ODD]
    pd.testing.assert_frame_equal(a[even], b[even])


@pytest.mark.parametrize("text,problem", [
    (_mirror(_with("tilt = 2.0"), '"yes"'), "must be true or false"),
    (_mirror(_with("tilt = 2.0"), "true").replace("chunk_size = 4", "chunk_size = 1"), "is odd"),
    (_with("tilt = 2.0").replace('initial = "launched"', 'initial = "launched"\nmirror = true'),
     "the same mirror for every family"),
])
def test_a_bad_mirror_is_one_line_naming_the_key(text, problem):
    with pytest.raises(WorkflowError) as e:
        parse_workflow(text, source="wf.toml")
    msg = str(e.value)
    assert "\n" not in msg and "wf.toml:" in msg and ".mirror" in msg and problem in msg


def test_an_odd_chunk_is_fine_where_images_are_not_simulated():
    study = parse_workflow(TINY.replace("chunk_size = 4", "chunk_size = 1"))
    assert {study.pairing(f) for f in study.families} == {"mirror symmetry"}


def test_a_conveyor_chunk_with_mirror_pairs_is_the_familys_draw_then_the_partners(tmp_path):
    import numpy as np

    from bbb import simulate
    from bbb.analysis.stats import bootstrap_D
    from bbb.ensemble import initial_state, mirror_pair_units
    from pipeline.workflow.identity import reduce_seed

    text = _mirror(_with("tilt = 2.0"), "true")
    study = parse_workflow(text)
    assert study.fingerprint() != parse_workflow(_with("tilt = 2.0")).fingerprint()
    store = StudyStore.create_or_open(tmp_path / "s.zarr", study)
    compute_chunk(store, 1, 0, 1)
    x = store.read_done("positions", 1, 0, np.array([False, True]))
    p, acc = study.params(60.0), study.accuracy
    drawn = initial_state(p, 2, study.seed_sequence(60.0, study.families[0], 1), "rest")
    first = simulate(p, 2, acc.t_max, 0, drawn, sample_times=study.sample_times(),
                     numerics=acc.numerics())
    assert np.array_equal(x[:2], first.positions)  # the drawn half: the family's own draw
    assert not np.array_equal(x[2:], x[:2])  # partners, not copies
    # the D column resamples pairs
    table = _reduced(text, tmp_path / "all")
    assert (table["v_by"] == "pairs").all()
    study, row = parse_workflow(text), table.iloc[0]
    s = StudyStore.open(tmp_path / "all" / "s.zarr")
    xs = np.concatenate([s.read_done("positions", 0, mi, s.done()[0, mi]) for mi in range(2)])
    units = np.concatenate([mirror_pair_units(8, 4), 4 + mirror_pair_units(8, 4)])
    T = study.analysis.duration(acc.t_max)
    d = bootstrap_D(xs, study.sample_times(), n_resamples=acc.n_resamples, seed=reduce_seed(
        study, 54.0), fit_from=0.05 * T, fit_to=0.25 * T, discard=0.1, units=units)
    assert (row["D"], row["D_lo"], row["D_hi"]) == tuple(d)
