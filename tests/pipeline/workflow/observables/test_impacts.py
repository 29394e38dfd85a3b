"""The impacts observable (floor phase at the collisions, vx correlation across them): its sums
against independent computations, and a real store's table against the stored collisions."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.catalog import table_names, tables
from pipeline.tables.units import UNKNOWN, column_unit
from pipeline.workflow.load import WorkflowError, parse_workflow
from pipeline.workflow.observables.impacts import (
    BINS,
    centred,
    impact_row,
    pair_moments,
    pearson,
    phase_counts,
    within,
)

from ...execute.store_bits import _BASE

SCENE = _BASE.format(name="impacts", params="", more="""
[observables.collisions]
record = 60

[observables.impacts]
collisions = 60
lags = 3
""")


def test_phase_counts_are_numpy_histograms_of_each_particles_valid_phases():
    rng = np.random.default_rng(1)
    phase = rng.random((5, 40))
    n = np.array([40, 0, 7, 39, 1])
    got = phase_counts(phase, n)
    for p in range(5):
        want, _ = np.histogram(phase[p, : n[p]], bins=BINS, range=(0.0, 1.0))
        assert np.array_equal(got[p], want)


def test_pooled_pair_sums_give_numpy_s_correlation_of_the_pooled_pairs():
    rng = np.random.default_rng(2)
    vx = rng.normal(size=(4, 30)).cumsum(axis=1)  # correlated from one collision to the next
    n = np.array([30, 12, 3, 25])
    m = pair_moments(np.where(np.arange(30) < n[:, None], vx, np.nan), n, 4).sum(axis=0)
    for lag in range(1, 5):
        a = np.concatenate([vx[p, : n[p] - lag] for p in range(4) if n[p] > lag])
        b = np.concatenate([vx[p, lag: n[p]] for p in range(4) if n[p] > lag])
        assert pearson(m[lag - 1]) == pytest.approx(np.corrcoef(a, b)[0, 1], rel=1e-12)


def test_an_ar1_velocity_series_gives_the_correlation_rho_to_the_lag():
    # analytic: vx_{i+1} = rho vx_i + noise has correlation rho**lag at lag
    rng = np.random.default_rng(3)
    rho, P, R = -0.5, 200, 400
    vx = np.empty((P, R))
    vx[:, 0] = rng.normal(size=P) / np.sqrt(1 - rho**2)
    for i in range(1, R):
        vx[:, i] = rho * vx[:, i - 1] + rng.normal(size=P)
    m = pair_moments(vx, np.full(P, R), 3).sum(axis=0)
    assert pearson(m) == pytest.approx([rho, rho**2, rho**3], abs=0.01)


def test_within_particle_correlation_sees_rho_where_particle_offsets_make_the_pooled_one_near_1():
    # analytic: AR(1) noise (rho at lag 1) about a mean vx of its own per particle, far apart
    rng = np.random.default_rng(4)
    rho, P, R = -0.4, 100, 300
    noise = np.empty((P, R))
    noise[:, 0] = rng.normal(size=P) / np.sqrt(1 - rho**2)
    for i in range(1, R):
        noise[:, i] = rho * noise[:, i - 1] + rng.normal(size=P)
    vx = noise + rng.normal(scale=50.0, size=(P, 1))
    m = pair_moments(vx, np.full(P, R), 1)
    assert pearson(m.sum(axis=0))[0] > 0.99
    assert within(centred(m).sum(axis=1))[0] == pytest.approx(rho, abs=0.02)
    # and it is the correlation of the pairs centred on each particle's own pair means
    a, b = vx[:, :-1], vx[:, 1:]
    a, b = a - a.mean(axis=1, keepdims=True), b - b.mean(axis=1, keepdims=True)
    want = (a * b).sum() / np.sqrt((a * a).sum() * (b * b).sum())
    assert within(centred(m).sum(axis=1))[0] == pytest.approx(want, rel=1e-9)


def test_a_particle_set_without_impacts_leaves_every_statistic_blank_and_says_why():
    row = impact_row(np.zeros((3, BINS), np.int64), np.zeros((3, 2, 6)),
                     np.random.default_rng(0), 50, 0.95)
    assert row["n_impacts"] == 0 and np.isnan(row["up_share"]) and np.isnan(row["vx_corr_1"])
    assert "no impacts" in row["impacts_status"] and "vx_corr_2" in row["impacts_status"]


def test_a_scene_s_impacts_table_is_read_off_its_stored_collisions(tmp_path):
    study = parse_workflow(SCENE, "impacts.toml")
    store = StudyStore.create_or_open(tmp_path / "i.zarr", study)
    for fi in range(2):
        for mi in range(2):
            for ci in range(2):
                compute_chunk(store, fi, mi, ci)
    assert "impacts" in table_names(study)
    table = tables(store, ["impacts"])["impacts"]
    assert all(column_unit(c) != UNKNOWN for c in table.columns)
    done = store.done()
    for (fi, mi), row in zip([(f, m) for f in range(2) for m in range(2)], table.itertuples(),
                         strict=True):
        coll = store.read_done("collisions", fi, mi, done[fi, mi])
        n = store.read_done("n_recorded", fi, mi, done[fi, mi])
        valid = np.arange(coll.shape[1]) < n[:, None]
        phase = coll[..., 5][valid]
        assert row.n_impacts == phase.size > 0
        up = np.mean((phase >= 0.25) & (phase < 0.75))  # the floor moves up
        assert row.up_share == pytest.approx(up, rel=1e-12)
        if np.isnan(row.up_share_lo):  # every resample the same share: no interval, said
            assert "up_share: interval of zero width" in row.impacts_status
        else:
            assert row.up_share_lo <= row.up_share <= row.up_share_hi
        a = np.concatenate([coll[p, : n[p] - 1, 3] for p in range(len(n)) if n[p] > 1])
        b = np.concatenate([coll[p, 1: n[p], 3] for p in range(len(n)) if n[p] > 1])
        assert row.vx_corr_1 == pytest.approx(np.corrcoef(a, b)[0, 1], rel=1e-9)
        pairs = [(coll[p, : n[p] - 1, 3], coll[p, 1: n[p], 3]) for p in range(len(n)) if n[p] > 1]
        a = np.concatenate([x - x.mean() for x, _ in pairs])
        b = np.concatenate([y - y.mean() for _, y in pairs])
        assert row.vx_within_1 == pytest.approx((a * b).sum() / np.sqrt((a * a).sum() * (b * b).sum()),
                                                rel=1e-9)


def test_a_scene_with_lags_zero_is_refused_naming_the_key():
    with pytest.raises(WorkflowError, match=r"observables\.impacts\.lags.*out of range"):
        parse_workflow(SCENE.replace("lags = 3", "lags = 0"), "impacts.toml")
