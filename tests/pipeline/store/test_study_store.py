"""The Zarr store: chunk-aligned writes, done-markers, attributes, refusals (the layout:
test_layout.py beside it)."""

from __future__ import annotations

import json
import os
import socket
import subprocess
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import zarr

from bbb.provenance import kernel_hash, kernel_identity
from bbb.record import COLLISION_FIELDS
from pipeline.cli import main
from pipeline.store.lock import run_lock
from pipeline.store.study_store import (
    JSON_ATTRS,
    KERNEL_ATTRS,
    StoreError,
    StudyStore,
    read_attrs,
    store_fingerprint,
)
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY


def fake_chunk(study, value: float) -> dict[str, np.ndarray]:
    """One chunk's values as a task gives them to the store (the store only writes arrays),
    recognisable: every position and collision field ``value``, every counter 3."""
    acc, obs = study.accuracy, study.observables
    n, t, k = acc.chunk_size, len(study.sample_times()), obs.collisions_record
    return {"positions": np.full((n, t), value),
            "collisions": np.full((n, k, len(COLLISION_FIELDS)), value),
            "n_recorded": np.full(n, k, dtype=np.int64),
            **{f"n_{c}": np.full(n, 3, dtype=np.int64)
               for c in ("collisions", "sticks", "liftoffs", "anomalies")}}


def test_the_documented_xarray_mask_hides_chunks_not_marked_done(store, study):
    store.write_chunk(1, 0, 1, fake_chunk(study, 5.0), 0.1)                    # done
    store.write_chunk(0, 1, 0, fake_chunk(study, 6.0), 0.1, mark_done=False)  # written, not done
    store.consolidate()
    ds = xr.open_zarr(store.path)
    done = ds.done.isel(chunk=ds.particle // (ds.sizes["particle"] // ds.sizes["chunk"]))
    x = ds.positions.where(done).values
    assert np.all(x[1, 0, 4:8] == 5.0)
    assert np.isnan(x[0, 1]).all() and np.isfinite(x).sum() == 4 * x.shape[-1]


def test_root_attrs_hold_workflow_params_numerics_version_and_kernel(store, study):
    attrs = store.attrs()
    assert attrs["workflow_toml"] == TINY
    assert attrs["params"]["alpha"] == 0.7 and "f" not in attrs["params"]
    assert attrs["numerics"] == study.accuracy.numerics().as_dict()
    assert attrs["accuracy"]["n_particles"] == 8
    assert attrs["bbb_version"] and attrs["workflow_fingerprint"] == study.fingerprint()
    assert {k: attrs[k] for k in KERNEL_ATTRS} == kernel_identity()
    assert len(attrs["kernel_hash"]) == 64 and attrs["fingerprint"] != study.fingerprint()


def test_the_store_fingerprint_changes_with_the_kernel(study):
    kernel = kernel_identity()
    fp = store_fingerprint(study.fingerprint(), kernel)
    for key in KERNEL_ATTRS:
        assert store_fingerprint(study.fingerprint(), dict(kernel, **{key: "other"})) != fp, key


def test_root_attributes_survive_to_netcdf(store, study, tmp_path):
    # netCDF attributes hold strings and numbers only: nested dicts are kept as JSON strings
    store.consolidate()
    xr.open_zarr(store.path).to_netcdf(tmp_path / "s.nc")
    back = xr.open_dataset(tmp_path / "s.nc")
    assert json.loads(back.attrs["workflow"]) == store.attrs()["workflow"]
    assert StudyStore.open(store.path).study == study
    assert back.attrs["kernel_hash"] == kernel_identity()["kernel_hash"]


def test_a_task_writes_only_its_own_chunk_files(store, study):
    before = _chunk_files(store.path)
    store.write_chunk(1, 0, 1, fake_chunk(study, 5.0), 0.1)
    new = _chunk_files(store.path) - before
    # every data array gained exactly its chunk (1, 0, 1, ...) and nothing else
    assert new and all(key.split("/c/")[1].startswith("1/0/1") for key in new)
    x = store.group()["positions"][...]
    assert np.all(x[1, 0, 4:8] == 5.0) and np.isnan(x[1, 0, :4]).all() and np.isnan(x[0]).all()


def test_done_is_marked_after_the_data_and_only_then(store, study):
    store.write_chunk(0, 1, 0, fake_chunk(study, 1.0), 0.1, mark_done=False)
    assert not store.done().any()  # data written, chunk not done: a re-run recomputes it
    store.write_chunk(0, 1, 0, fake_chunk(study, 1.0), 0.1)
    assert store.done()[0, 1, 0] and store.done().sum() == 1


def test_chunk_writes_are_idempotent(store, study):
    store.write_chunk(0, 0, 0, fake_chunk(study, 2.0), 0.1)
    first = store.group()["collisions"][...]
    store.write_chunk(0, 0, 0, fake_chunk(study, 2.0), 0.2)
    assert np.array_equal(first, store.group()["collisions"][...], equal_nan=True)


def test_reopening_with_the_same_workflow_keeps_the_data(store, study):
    store.write_chunk(0, 0, 0, fake_chunk(study, 2.0), 0.1)
    again = StudyStore.create_or_open(store.path, study)
    assert again.done()[0, 0, 0]


def test_a_different_workflow_is_refused_naming_the_difference(store):
    other = parse_workflow(TINY.replace("seed = 7", "seed = 8"), source="tiny.toml")
    with pytest.raises(StoreError, match=r"different workflow \(seed: store 7, workflow 8\)"):
        StudyStore.create_or_open(store.path, other)


def test_a_store_of_an_older_layout_is_refused(store, study):
    # layout 1 stored collisions without the floor phase: resuming it would fail in every task
    zarr.open_group(str(store.path), mode="r+").attrs["bbb_store_layout"] = 1
    with pytest.raises(StoreError, match=r"store layout 1 of an older bbb \(its collisions have "
                                         r"no floor phase\); allowed: layout 4"):
        StudyStore.create_or_open(store.path, study)


def _as_older_bbb_wrote_it(path, **kernel):
    """Rewrite a store's root attributes as an older bbb would have: layout 2 (nested dicts,
    no kernel attributes, fingerprint = the workflow's) or, with ``kernel``, layout 3 written
    by another kernel (its hash, and the fingerprint consistent with it)."""
    g = zarr.open_group(str(path), mode="r+")
    attrs = read_attrs(g)
    if kernel:
        new = {**{k: attrs[k] for k in KERNEL_ATTRS}, **kernel}
        g.attrs.update({**new, "fingerprint": store_fingerprint(attrs["workflow_fingerprint"], new)})
        return
    for key in (*KERNEL_ATTRS, "workflow_fingerprint"):
        del g.attrs[key]
    g.attrs.update({**{k: attrs[k] for k in JSON_ATTRS}, "bbb_store_layout": 2,
                    "fingerprint": attrs["workflow_fingerprint"]})


def test_a_layout_2_store_without_a_kernel_hash_is_refused(store, study):
    _as_older_bbb_wrote_it(store.path)
    with pytest.raises(StoreError, match=r"store layout 2 of an older bbb \(it records no kernel "
                                         r"hash.*allowed: layout 4"):
        StudyStore.create_or_open(store.path, study)


def test_a_store_of_another_kernel_is_refused_naming_both_hashes(store, study):
    store.write_chunk(0, 0, 0, fake_chunk(study, 2.0), 0.1)
    old = "0123456789abcdef" * 4
    _as_older_bbb_wrote_it(store.path, kernel_hash=old)
    before = store.group()["positions"][...]
    with pytest.raises(StoreError) as e:
        StudyStore.create_or_open(store.path, study)
    msg = str(e.value)
    assert f"made by another kernel (kernel_hash: store {old}, this bbb {kernel_hash()})" in msg
    assert "\n" not in msg
    assert store.done()[0, 0, 0] and np.array_equal(store.group()["positions"][...], before,
                                                     equal_nan=True)


def test_a_store_of_another_numba_is_refused(store, study):
    _as_older_bbb_wrote_it(store.path, numba_version="0.1")
    with pytest.raises(StoreError, match=r"another kernel \(numba_version: store 0\.1, this bbb "):
        StudyStore.create_or_open(store.path, study)


def test_a_store_of_layout_3_without_checksums_is_refused_for_reading_too(store):
    # bbb reduce / status / plot of a store whose chunks cannot be checked: one line, no read
    zarr.open_group(str(store.path), mode="r+").attrs["bbb_store_layout"] = 3
    with pytest.raises(StoreError) as e:
        StudyStore.open(store.path)
    assert str(e.value) == (f"{store.path}: store layout 3 of an older bbb (its chunks carry no "
                            "checksums, so a damaged chunk cannot be told from data); allowed: "
                            "layout 4 (delete it or use another --store)")


def test_different_params_are_refused(store):
    other = parse_workflow(TINY.replace('preset = "klages2004"', 'preset = "matyas2004"'),
                           source="tiny.toml")
    with pytest.raises(StoreError, match=r"params\.(R|alpha)"):
        StudyStore.create_or_open(store.path, other)


def test_new_reduce_settings_are_accepted_and_recorded(store):
    other = parse_workflow(TINY + "[analysis]\nci = 0.9\n", source="tiny.toml")
    StudyStore.create_or_open(store.path, other)
    assert StudyStore.open(store.path).study.analysis.ci == 0.9


def test_open_returns_the_study_it_was_made_by(store, study):
    assert StudyStore.open(store.path).study == study


def test_a_directory_that_is_not_a_store_is_refused(tmp_path, study):
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "a.txt").write_text("x")
    with pytest.raises(StoreError, match="not a Zarr store"):
        StudyStore.create_or_open(tmp_path / "notes", study)


def test_another_zarr_group_is_refused(tmp_path, study):
    zarr.open_group(str(tmp_path / "other.zarr"), mode="w")
    with pytest.raises(StoreError, match="not a bbb study store"):
        StudyStore.create_or_open(tmp_path / "other.zarr", study)


def test_interrupted_layout_creation_is_redone(tmp_path, study):
    zarr.open_group(str(tmp_path / "s.zarr"), mode="w", attributes={"bbb_creating": True})
    store = StudyStore.create_or_open(tmp_path / "s.zarr", study)
    assert store.attrs()["workflow_fingerprint"] == study.fingerprint()


def test_unwritable_path_is_refused(tmp_path, study):
    (tmp_path / "file").write_text("a file cannot hold a store")  # refused even for root
    with pytest.raises(StoreError, match="cannot create"):
        StudyStore.create_or_open(tmp_path / "file" / "s.zarr", study)


def _chunk_files(path) -> set[str]:
    out = set()
    for root, _, files in os.walk(path):
        for f in files:
            rel = os.path.relpath(os.path.join(root, f), path)
            if "/c/" in rel:
                out.add(rel)
    return out


def test_a_held_store_is_refused_naming_the_holder(tmp_path):
    path = str(tmp_path / "s.zarr")
    with run_lock(path):
        with pytest.raises(StoreError, match=rf"in use by another bbb run .*pid {os.getpid()}"):
            with run_lock(path):
                pass
    assert not os.path.exists(path + ".lock")  # released


@pytest.mark.parametrize("linked", ["the store", "its folder"])
def test_a_run_reaching_a_held_store_through_a_symlink_is_refused(linked, tiny_workflow,
                                                                  tmp_path, capsys):
    """One run holds the store by its real path; `bbb run` on a symlink to the store (or to
    a folder above it) takes the same lock, so it is refused, not let in beside the first."""
    (tmp_path / "real").mkdir()
    real = tmp_path / "real" / "s.zarr"
    if linked == "the store":
        real.mkdir()
        (tmp_path / "link.zarr").symlink_to(real)
        via = tmp_path / "link.zarr"
    else:
        (tmp_path / "link").symlink_to(tmp_path / "real")
        via = tmp_path / "link" / "s.zarr"
    with run_lock(str(real)):
        assert main(["run", str(tiny_workflow), "--store", str(via), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert f"in use by another bbb run (host {socket.gethostname()}, pid {os.getpid()}" in err
    assert f"delete {real}.lock" in err and err.count("\n") == 1
    assert not (real / "zarr.json").exists()  # the refused run wrote nothing


def test_a_stale_lock_of_a_dead_process_is_taken_over(tmp_path):
    path = str(tmp_path / "s.zarr")
    dead = _dead_pid()
    Path(path + ".lock").write_text(json.dumps({"host": socket.gethostname(), "pid": dead}))
    with run_lock(path):
        assert json.loads(Path(path + ".lock").read_text())["pid"] == os.getpid()


def _dead_pid() -> int:
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def test_fsspec_urls_are_stores_too(study, tmp_path):
    # memory:// goes through zarr's FsspecStore like s3:// would; file:// is a local path.
    from pipeline.execute.task import compute_chunk

    for url in ("memory://bbb-test/s.zarr", f"file://{tmp_path}/s.zarr"):
        store = StudyStore.create_or_open(url, study)
        compute_chunk(store, 1, 1, 0)
        again = StudyStore.open(url)
        assert again.study == study and again.done().sum() == 1
        assert np.isfinite(again.group()["positions"][1, 1, :4]).all()
    assert (tmp_path / "s.zarr" / "zarr.json").exists()


def test_read_done_reads_runs_of_done_chunks_and_skips_the_gaps(tmp_path):
    study = parse_workflow(TINY.replace("n_particles = 8", "n_particles = 20"), source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "g.zarr", study)
    for ci in (0, 1, 3, 4):  # two runs of done chunks around chunk 2, written but not done
        store.write_chunk(0, 1, ci, fake_chunk(study, 10.0 + ci), 0.1)
    store.write_chunk(0, 1, 2, fake_chunk(study, 99.0), 0.1, mark_done=False)
    x = store.read_done("positions", 0, 1)
    assert x[:, 0].tolist() == [v for ci in (0, 1, 3, 4) for v in [10.0 + ci] * 4]
    assert store.read_done("positions", 1, 1).shape == (0, x.shape[1])  # nothing done there
