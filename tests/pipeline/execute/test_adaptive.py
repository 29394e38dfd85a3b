"""Adaptive studies (issue 12): waves of chunks until D's CI meets a target, decided from the
chunks in index order, and frequency refinement around extrema.  Real LocalClusters, real
Zarr stores; the rules themselves also on synthetic data with known answers."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import zarr

from bbb.analysis import stats
from pipeline.execute.adaptive import (
    CAP,
    OPEN,
    STOP_LEGEND,
    TARGET,
    ZERO,
    StoppingRule,
    advance,
    predicted_waves,
    refine_frequencies,
    remaining,
)
from pipeline.execute.run import RunFailed, run_study
from pipeline.store.status import status_text
from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import WorkflowError, parse_workflow

from ..helpers import QUIET, assert_same_store

# 3 frequencies x 2 families, chunks of 8 particles, at most 8 chunks: 54 Hz from rest stays
# at D = 0 (resolved to ±d_resolved after one chunk), 54 Hz launched decays into creeping (the cap), the
# others meet 30 % after 1-8 chunks (measured: chunks used 1, 8 / 8, 8 / 1, 6).
SCENE = """\
[study]
name = "adaptive"
seed = 7

[frequencies]
values = [54.0, 60.0, 72.0]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"

[accuracy]
preset = "draft"
chunk_size = 8
max_particles = 64
t_max = 10.0
sample_dt = 0.5
n_resamples = 100
target_ci = 0.3
d_resolved = 1.0

[observables.positions]
"""


@pytest.fixture(scope="module")
def scene(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("adaptive") / "adaptive.toml"
    path.write_text(SCENE)
    return path


@pytest.fixture(scope="module")
def two_workers(scene, tmp_path_factory) -> Path:
    """The scene on a 2-worker LocalCluster: the store every other run must equal."""
    path = tmp_path_factory.mktemp("two") / "adaptive.zarr"
    run_study(parse_workflow(SCENE, str(scene)), path, workers=2, **QUIET)
    return path


def _stops(path) -> tuple[np.ndarray, np.ndarray]:
    g = zarr.open_group(str(path), mode="r")
    return np.asarray(g["n_chunks_used"][...]), np.asarray(g["stop_reason"][...])


# -- determinism ---------------------------------------------------------------------------------
def test_one_and_two_workers_give_bit_identical_adaptive_stores(scene, two_workers, tmp_path):
    one = tmp_path / "one.zarr"
    run_study(parse_workflow(SCENE, str(scene)), one, workers=1, **QUIET)
    assert_same_store(one, two_workers)  # data arrays, done, n_chunks_used, stop_reason
    used, reason = _stops(two_workers)
    # the scene exercises every stop reason and more than one wave
    assert {TARGET, ZERO, CAP} <= set(reason.ravel().tolist())
    assert used.max() > 1


def test_the_done_chunks_are_exactly_the_first_n_chunks_used(two_workers):
    done = StudyStore.open(two_workers).done()
    used, reason = _stops(two_workers)
    assert (reason != OPEN).all()
    first = np.arange(done.shape[2])[None, None, :] < used[:, :, None]
    assert np.array_equal(done, first)


def test_an_existing_scheduler_gives_the_same_adaptive_store(scene, two_workers, dask_cluster,
                                                              tmp_path):
    store = tmp_path / "remote.zarr"
    run_study(parse_workflow(SCENE, str(scene)), store, scheduler=dask_cluster, **QUIET)
    assert_same_store(store, two_workers)


def test_a_run_failing_mid_wave_resumes_to_the_same_store(scene, two_workers, tmp_path):
    """72 Hz launched needs 6 chunks (waves 1, 2, 4, 6): its chunk 3 fails in the third wave,
    so 3 of its chunks are done, not a wave boundary.  The failed run leaves it open; the
    re-run replays the decisions from the first chunks (a resume that decided from the 3 done
    chunks instead ends with another number of chunks: the store differs)."""
    study = parse_workflow(SCENE, str(scene))
    store = tmp_path / "failed.zarr"
    with pytest.raises(RunFailed, match="f = 72 Hz, family launched, chunk 3"):
        run_study(study, store, workers=2, fail_chunks="72:launched:3", **QUIET)
    done = StudyStore.open(store).done()
    assert done[2, 1, :2].all() and not done[2, 1, 3]  # it did fail inside a later wave
    assert _stops(store)[1][2, 1] == OPEN
    run_study(study, store, workers=2, **QUIET)
    assert_same_store(store, two_workers)


@pytest.mark.slow
def test_a_damaged_chunk_inside_a_stopped_unit_is_repaired_without_replaying_its_waves(
        scene, two_workers, tmp_path):
    """60 Hz launched used 8 chunks; a byte flipped in its chunk 2: the re-run recomputes
    that chunk alone, before the waves look at the store (unmarking it would have shortened
    the unit's run of done chunks and dropped the chunks after it)."""
    import shutil

    store = Path(shutil.copytree(two_workers, tmp_path / "damaged.zarr"))
    chunk = store / "positions" / "c" / "1" / "1" / "2" / "0"
    data = bytearray(chunk.read_bytes())
    data[len(data) // 2] ^= 0x10
    chunk.write_bytes(bytes(data))
    said = []
    report = run_study(parse_workflow(SCENE, str(scene)), store, workers=1,
                       **{**QUIET, "echo": said.append})
    assert report.repaired == [(60.0, "launched", 2)] and report.computed == report.repaired
    assert not any("beyond what the rule asks" in line for line in said), said
    assert_same_store(store, two_workers)


def test_status_shows_the_chunks_used_and_why_each_stopped(two_workers):
    text = status_text(StudyStore.open(two_workers))
    used, reason = _stops(two_workers)
    row54 = next(line for line in text.splitlines() if line.startswith("54 "))
    assert f"{used[0, 0]}/8 {STOP_LEGEND[reason[0, 0]]}" in row54
    assert f"{used[0, 1]}/8 {STOP_LEGEND[reason[0, 1]]}" in row54


def test_the_reduced_table_says_where_d_is_only_resolved_to_zero(two_workers, tmp_path):
    # from rest at 54 Hz every particle creeps: D = 0 is resolved after one chunk, while the
    # launched family decays into creeping until the cap; at 72 Hz both families bounce
    from pipeline.tables.reduce import reduce_store

    t = reduce_store(two_workers, tmp_path / "out", echo=lambda _: None)["diffusion"]
    stop = dict(zip(t["f"], t["stop"], strict=True))
    assert stop[54.0] == "rest: resolved to ±d_resolved; launched: cap"
    assert "resolved to" not in stop[72.0] and "cap" not in stop[72.0]


# -- the stopping rule ---------------------------------------------------------------------------
def _brownian(n: int, times: np.ndarray, D: float, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    steps = rng.normal(0.0, math.sqrt(2 * D * (times[1] - times[0])), (n, times.size - 1))
    return np.concatenate([np.zeros((n, 1)), np.cumsum(steps, axis=1)], axis=1)


def test_the_target_is_met_after_the_waves_the_inverse_sqrt_n_law_predicts():
    """Brownian paths (D = 50 mm²/s, chunks of 16): the relative half-width c/sqrt(N) is
    calibrated on 4096 independent paths, then the rule must meet 5 % within +-1 wave of the
    waves the law predicts, and at a chunk count within 1/√N scatter of it."""
    times = np.linspace(0.0, 20.0, 41)
    fit = dict(fit_from=0.9, fit_to=4.5, discard=0.1)

    def ci(x, seed):
        r = stats.bootstrap_D(x, times, n_resamples=400, seed=seed, **fit)
        return r.D, r.lo, r.hi

    big = _brownian(4096, times, 50.0, seed=1)
    D, lo, hi = ci(big, 2)
    c = 0.5 * (hi - lo) / D * math.sqrt(big.shape[0])  # relative half-width x sqrt(N)
    target, chunk, cap = 0.05, 16, 256
    n_needed = math.ceil((c / target) ** 2 / chunk)
    paths = _brownian(cap * chunk, times, 50.0, seed=3)
    state = advance(StoppingRule(target, None, cap), None, cap,
                    lambda n: ci(paths[: n * chunk], n))
    assert state.reason == TARGET
    assert abs(len(state.waves) - predicted_waves(1, n_needed, cap)) <= 1, (state, n_needed)
    assert 0.6 * n_needed <= state.n <= 1.6 * n_needed, (state.n, n_needed)


def test_an_unreachable_target_stops_at_the_cap_and_says_so(tmp_path):
    """72 Hz from rest, at most 4 chunks of 8, target 1 %: waves 1, 2, 4, then the cap."""
    text = (SCENE.replace("[54.0, 60.0, 72.0]", "[72.0]").replace("target_ci = 0.3", "target_ci = 0.01")
            .replace("max_particles = 64", "max_particles = 32")
            .replace('[families.launched]\ninitial = "launched"\n', ""))
    store = tmp_path / "cap.zarr"
    run_study(parse_workflow(text, "cap.toml"), store, workers=1, **QUIET)
    used, reason = _stops(store)
    assert used.tolist() == [[4]] and reason.tolist() == [[CAP]]
    assert "4/4 cap" in status_text(StudyStore.open(store))


def test_the_run_summary_counts_the_chunks_used_against_the_cap(tmp_path):
    """54 Hz from rest: D = 0 is resolved by the first chunk; the summary must not call the
    other 7 chunks of the cap undone work."""
    text = (SCENE.replace("[54.0, 60.0, 72.0]", "[54.0]")
            .replace('[families.launched]\ninitial = "launched"\n', ""))
    report = run_study(parse_workflow(text, "zero.toml"), tmp_path / "zero.zarr", workers=1,
                       **QUIET)
    assert report.summary().startswith("adaptive: 1 chunks used (of 8 the cap allows)")


def test_d_near_zero_is_resolved_only_with_an_absolute_half_width():
    """D = 0 exactly (no particle moves): a relative target can never be met; d_resolved
    stops it at once."""
    zero = (0.0, 0.0, 0.0)
    assert advance(StoppingRule(0.03, None, 8), None, 8, lambda n: zero).reason == CAP
    assert advance(StoppingRule(0.03, 1.0, 8), None, 8, lambda n: zero).reason == ZERO


def test_a_unit_where_nothing_moved_is_not_resolved_but_sampled_to_the_cap():
    """No mover: D = 0 with no upper bound (hi NaN, bbb.analysis.stats.interval).  [0, 0] once counted
    as resolved after the first chunk; the data bound only the share of movers, which more
    particles shrink, so the unit keeps sampling until the cap."""
    still = (0.0, 0.0, math.nan)
    state = advance(StoppingRule(0.03, 1.0, 8), None, 8, lambda n: still)
    assert state.reason == CAP and state.n == 8 and state.waves == [1, 2, 4, 8]


def test_a_target_met_row_shows_the_very_ci_that_met_the_target(two_workers, tmp_path):
    """One CI for the stopping rule and the table: each family's D_<fam>_lo/hi is the CI its
    last decision read (same chunks, same seed), so a "target met" family never shows a
    half-width above its target (Fig. 2 showed 3.07-3.15 % against 3 % when the table
    bootstrapped again with its own seed)."""
    from pipeline.execute.waves import unit_ci
    from pipeline.tables.reduce import reduce_store

    store = StudyStore.open(two_workers)
    study = store.study
    t = reduce_store(store, tmp_path / "out", echo=lambda _: None)["diffusion"]
    used, reason = _stops(two_workers)
    met = 0
    for fi, f in enumerate(study.frequencies):
        row = t[t["f"] == f].iloc[0]
        for mi, fam in enumerate(study.families):
            D, lo, hi = (row[f"D_{fam.name}{s}"] for s in ("", "_lo", "_hi"))
            assert (D, lo, hi) == unit_ci(store, fi, mi, int(used[fi, mi]))
            if reason[fi, mi] == TARGET:
                met += 1
                assert (hi - lo) / 2 <= study.accuracy.target_ci * D
    assert met >= 2


# 40 Hz (Γ = 0.64 < 1) beside 60 Hz: the engine meets a unit where nothing moves inside a wider
# scene (a scene with nothing but such units is refused before it runs: pipeline.workflow.sanity)
STILL = (SCENE.replace("[54.0, 60.0, 72.0]", "[40.0, 60.0]").replace("max_particles = 64",
                                                                  "max_particles = 32")
         .replace('[families.launched]\ninitial = "launched"\n', ""))


def test_a_frequency_where_nothing_moves_reports_the_mover_share_bound_not_zero_width(tmp_path):
    """40 Hz from rest (Γ = 0.64 < 1): no particle ever lifts off, every D_i = 0.  The unit
    samples to the cap (4 chunks of 8) and the table says D = 0, D_hi NaN, mover share
    < 1 - 0.05^(1/32) = 8.9 %."""
    from pipeline.tables.reduce import reduce_store

    store = tmp_path / "still.zarr"
    run_study(parse_workflow(STILL, "still.toml"), store, workers=1, **QUIET)
    assert _stops(store)[0][0].tolist() == [4] and _stops(store)[1][0].tolist() == [CAP]
    row = reduce_store(store, tmp_path / "out", echo=lambda _: None)["diffusion"].iloc[0]
    assert row["n_moving"] == 0 and row["D"] == 0.0 and row["D_lo"] == 0.0
    assert math.isnan(row["D_hi"]) and math.isnan(row["D_rest_hi"])
    assert row["mover_share_hi"] == pytest.approx(1 - 0.05 ** (1 / 32))
    assert row["D_status"].startswith("no mover among 32")
    assert math.isnan(row["D_cover"])


def test_a_store_that_recorded_no_mover_as_resolved_zero_is_reopened_and_finished(tmp_path):
    """A store decided by the old rule (no mover after chunk 1: stop_reason 2, "resolved to
    ±d_resolved") is reopened by the next run and ends where a fresh run ends."""
    study = parse_workflow(STILL, "still.toml")
    fresh, old = tmp_path / "fresh.zarr", tmp_path / "old.zarr"
    run_study(study, fresh, workers=1, **QUIET)
    run_study(study, old, workers=1, **QUIET)
    g = zarr.open_group(str(old), mode="r+")
    g["done"][0, 0, 1:] = False
    g["n_chunks_used"][0, 0] = 1
    g["stop_reason"][0, 0] = ZERO
    run_study(study, old, workers=1, **QUIET)
    assert_same_store(old, fresh)


def test_a_target_without_positions_or_a_cap_without_a_target_is_refused():
    with pytest.raises(WorkflowError, match=r"accuracy\.d_resolved: only with target_ci"):
        parse_workflow(SCENE.replace("target_ci = 0.3\n", ""), "x.toml")
    with pytest.raises(WorkflowError, match="n_particles: with target_ci"):
        parse_workflow(SCENE.replace("chunk_size = 8", "chunk_size = 8\nn_particles = 64"), "x.toml")
    with pytest.raises(WorkflowError, match="observables.positions"):
        parse_workflow(SCENE.replace("[observables.positions]", "[observables.collisions]"), "x.toml")


def test_a_fixed_scene_keeps_its_fingerprint_and_layout():
    fixed = parse_workflow(SCENE.replace("target_ci = 0.3\nd_resolved = 1.0\n", "")
                           .replace("max_particles = 64", "n_particles = 64"), "x.toml")
    assert "stopping" not in fixed.data_identity() and not fixed.adaptive
    assert "target_ci" not in fixed.to_dict()["accuracy"]


# -- refinement ----------------------------------------------------------------------------------
def _peak(f_mhz, f0=60.337):
    """A synthetic D(f) with one maximum at f0 Hz and +-1 mm²/s CIs."""
    f = np.asarray(f_mhz) / 1000.0
    D = 100.0 - 400.0 * (f - f0) ** 2
    return D, D - 1.0, D + 1.0


def test_refinement_brackets_a_known_maximum_to_the_requested_resolution():
    grid = list(range(58000, 62001, 400))
    rounds = 0
    while True:
        new = refine_frequencies(grid, *_peak(grid), to=0.05)
        if not new:
            break
        assert not set(new) & set(grid)
        grid = sorted(grid + new)
        rounds += 1
    f = np.asarray(grid)
    best = int(np.argmax(_peak(f)[0]))
    assert f[best + 1] - f[best] <= 50 and f[best] - f[best - 1] <= 50
    assert abs(f[best] / 1000 - 60.337) <= 0.05
    assert rounds >= 3 and len(grid) < 11 + 4 * rounds  # a few points per round, not a sweep


def test_the_frequencies_refinement_adds_do_not_depend_on_the_order_of_the_table():
    grid = np.array(range(58000, 62001, 400))
    D, lo, hi = _peak(grid)
    perm = np.random.default_rng(0).permutation(grid.size)
    assert (refine_frequencies(grid, D, lo, hi, to=0.05)
            == refine_frequencies(grid[perm], D[perm], lo[perm], hi[perm], to=0.05))


def _chunk_files(path: Path) -> dict[str, bytes]:
    return {str(p.relative_to(path)): p.read_bytes() for p in path.rglob("*")
            if p.is_file() and "/c/" in str(p) and p.parent.name != "frequency"
            and not str(p.relative_to(path)).startswith(("frequency/", "refined/"))}


def test_growing_the_store_by_a_frequency_leaves_every_written_chunk_byte_identical(tmp_path):
    """A refine scene whose grid is already fine enough (to = 10 Hz): a frequency is added as
    refinement would, and the re-run computes only its chunks, seeded by value."""
    text = (SCENE.replace("values = [54.0, 60.0, 72.0]",
                          "values = [60.0, 66.0, 72.0]\nrefine = { to = 10.0 }")
            .replace("target_ci = 0.3\nd_resolved = 1.0\n", "")
            .replace("max_particles = 64", "n_particles = 8"))
    study = parse_workflow(text, "refine.toml")
    store = tmp_path / "refine.zarr"
    run_study(study, store, workers=1, **QUIET)
    before = _chunk_files(store)
    grown = StudyStore.open(store).add_frequencies((63.123,))
    assert grown.study.frequencies == (60.0, 66.0, 72.0, 63.123)
    run_study(study, store, workers=1, **QUIET)
    after = _chunk_files(store)
    assert {k: after[k] for k in before} == before
    assert len(after) > len(before)
    g = zarr.open_group(str(store), mode="r")
    assert g["refined"][...].tolist() == [False, False, False, True]
    # the added frequency's chunks are those of a fresh scene at that frequency alone
    alone = tmp_path / "alone.zarr"
    run_study(parse_workflow(text.replace("[60.0, 66.0, 72.0]", "[63.123, 64.0, 65.0]"), "a.toml")
              .with_frequencies((63.123,)), alone, workers=1, **QUIET)
    a = zarr.open_group(str(alone), mode="r")
    assert np.array_equal(g["positions"][3], a["positions"][0])


# -- loose ends: finished stores, table order, progress ------------------------------------------
def test_a_finished_adaptive_store_has_no_work_left_and_an_open_unit_has(scene, two_workers,
                                                                          tmp_path):
    """work_left replays the wave rule: the finished store (chunks short of the cap, every
    unit stopped) needs nothing; reopening one stopped unit with its last chunk undone does."""
    import shutil

    from pipeline.execute.cluster import work_left

    study = parse_workflow(SCENE, str(scene))
    copy = tmp_path / "copy.zarr"
    shutil.copytree(two_workers, copy)
    assert not StudyStore.open(copy).done().all()  # an adaptive store stops short of the cap
    assert work_left(study, copy) is False
    used, _ = _stops(copy)
    fi, mi = np.unravel_index(int(np.argmax(used)), used.shape)  # a unit that took > 1 wave
    g = zarr.open_group(str(copy), mode="r+")
    g["stop_reason"][fi, mi] = OPEN
    g["done"][fi, mi, int(used[fi, mi]) - 1] = False
    assert work_left(study, copy) is True


def test_the_reduced_tables_go_by_frequency_when_refinement_appended_one(tmp_path):
    from pipeline.tables.reduce import reduce_store

    text = (SCENE.replace("values = [54.0, 60.0, 72.0]",
                          "values = [60.0, 66.0, 72.0]\nrefine = { to = 10.0 }")
            .replace("target_ci = 0.3\nd_resolved = 1.0\n", "")
            .replace("max_particles = 64", "n_particles = 8")
            .replace('[families.launched]\ninitial = "launched"\n', ""))
    study = parse_workflow(text, "refine.toml")
    store = tmp_path / "refine.zarr"
    run_study(study, store, workers=1, **QUIET)
    StudyStore.open(store).add_frequencies((63.0,))  # appended: the store's axis is 60, 66, 72, 63
    run_study(study, store, workers=1, **QUIET)
    tables = reduce_store(store, tmp_path / "out", echo=lambda _: None)
    for name in ("diffusion", "counters"):
        assert tables[name]["f"].tolist() == [60.0, 63.0, 66.0, 72.0], name
    assert tables["diffusion"]["D"].notna().all()


def test_the_progress_counts_the_open_units_and_the_chunks_the_law_says_they_need():
    """Wave 1 of a unit at 40 % relative half-width with a 10 % target: the law asks for
    (0.4 / 0.1)^2 = 16 chunks in all (the wave only doubles to 2); one chunk is done, so 15
    remain.  A stopped unit needs nothing; a unit beyond its prediction needs its wave."""
    rule = StoppingRule(0.1, None, 64)
    wide = advance(rule, None, 1, lambda n: (100.0, 60.0, 140.0))  # hw = 40 % of D
    assert wide.reason == OPEN and wide.n == 2 and wide.need == 16
    met = advance(rule, None, 1, lambda n: (100.0, 95.0, 105.0))
    assert met.reason == TARGET
    capped = advance(StoppingRule(0.1, None, 4), None, 1, lambda n: (100.0, 0.0, 200.0))
    assert capped.n == 2 and capped.need == 4  # the law wants 100 chunks; the cap is 4
    assert remaining([wide, met, capped], [1, 1, 1]) == (2, 15 + 3)
