"""The digest of a chunk's values (pipeline/store/layout.py chunk_digest) and the checked read
(pipeline/store/integrity.py), without a cluster: what a task writes is what a read accepts,
also after the store grew; a chunk deleted or rewritten is not."""

from __future__ import annotations

import numpy as np
import pytest
import zarr

from pipeline.store.layout import chunk_digest
from pipeline.store.study_store import StoreDamaged, StudyStore
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY
from .test_study_store import fake_chunk

# one grid point at 54 Hz with per-period jumps; widened to 72 Hz, which has more periods
JUMPS_MAP = (TINY.replace("[54.0, 60.0]", "[54.0]") + "\n[observables.jumps]\n\n[grid]\n"
             "alpha = [0.7]\n")


def test_the_digest_of_a_period_chunk_ignores_fill_appended_along_its_last_axis():
    a = np.arange(12, dtype=np.float32).reshape(3, 4)
    a[:, 3] = np.nan  # a lower frequency's periods end early
    grown = np.concatenate([a, np.full((3, 5), np.nan, np.float32)], axis=1)
    assert chunk_digest(grown, np.nan, trim=True) == chunk_digest(a, np.nan, trim=True)
    assert chunk_digest(grown, np.nan) != chunk_digest(a, np.nan)  # untrimmed: it would change


def test_the_digest_tells_a_changed_value_and_an_all_fill_chunk_from_the_written_one():
    a = np.arange(8, dtype=np.int64)
    b = a.copy()
    b[5] = 0
    assert chunk_digest(b, 0) != chunk_digest(a, 0)
    assert chunk_digest(np.zeros_like(a), 0) != chunk_digest(a, 0)  # a deleted chunk reads 0


def test_jumps_written_before_a_map_grew_read_back_intact_after_it(tmp_path):
    """A new point at a higher frequency lengthens the period axis with NaN: the digest of a
    chunk written before still matches, and the new chunk's jumps past the old length too."""
    study = parse_workflow(JUMPS_MAP, source="m.toml")
    store = StudyStore.create_or_open(tmp_path / "m.zarr", study)
    P = store.group()["jumps"].shape[3]
    jumps = np.arange(4 * P, dtype=np.float32).reshape(4, P)
    store.write_chunk(0, 0, 0, {**fake_chunk(study, 0.5), "jumps": jumps}, 0.1)
    wider = parse_workflow(JUMPS_MAP.replace("[54.0]", "[54.0, 72.0]"), source="m.toml")
    grown = StudyStore.create_or_open(store.path, wider)
    Q = grown.group()["jumps"].shape[3]
    assert Q > P
    old = grown.read_done("jumps", 0, 0)
    assert np.array_equal(old[:, :P], jumps) and np.isnan(old[:, P:]).all()
    fi = [p.f for p in grown.study.points].index(72.0)
    more = np.arange(4 * Q, dtype=np.float32).reshape(4, Q)
    grown.write_chunk(fi, 0, 1, {**fake_chunk(study, 0.5), "jumps": more}, 0.1)
    assert np.array_equal(grown.read_done("jumps", fi, 0), more)


def test_a_chunk_file_left_by_a_torn_write_is_overwritten_whole_never_decoded(tmp_path):
    """The lyapunov-like arrays a task fills only in part: the whole chunk is written, so
    garbage left in its file by an interrupted run cannot break the rewrite."""
    study = parse_workflow(TINY, source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "t.zarr", study)
    store.write_chunk(0, 0, 0, fake_chunk(study, 0.5), 0.1, mark_done=False)
    (tmp_path / "t.zarr" / "positions" / "c" / "0" / "0" / "0" / "0").write_bytes(b"torn")
    store.write_chunk(0, 0, 0, fake_chunk(study, 0.5), 0.1)
    assert np.all(store.read_done("positions", 0, 0) == 0.5)


def test_a_deleted_chunk_of_a_store_without_a_cluster_raises_store_damaged(tmp_path):
    study = parse_workflow(TINY, source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "t.zarr", study)
    store.write_chunk(1, 1, 0, fake_chunk(study, 0.5), 0.1)
    (tmp_path / "t.zarr" / "n_sticks" / "c" / "1" / "1" / "0").unlink()
    assert np.all(zarr.open_group(str(store.path))["n_sticks"][1, 1, :4] == 0)  # reads as fill
    with pytest.raises(StoreDamaged, match=r"n_sticks\[f = 60 Hz, family launched, chunk 0\] is "
                                           r"damaged: values differ"):
        store.read_done("n_sticks", 1, 1)
    assert [(d.array, d.fi, d.mi, d.ci) for d in store.damage()] == [("n_sticks", 1, 1, 0)]
