"""pipeline.api: run_study from Python makes the CLI's store and resumes like it; open_study
names dimensions and units and masks chunks not done; reduced equals `bbb reduce`'s tables."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline import open_study, reduced, run_study
from pipeline.cli import main as cli
from pipeline.execute.run import FAIL_ENV, RunFailed
from pipeline.store.study_store import StudyStore

from .helpers import assert_same_store

FAILED = "60:rest:1"  # (f = 60 Hz, family rest, chunk 1): written, then failed, not done


@pytest.fixture(scope="module")
def cli_store(tiny_workflow, tmp_path_factory) -> Path:
    """The tiny workflow run by `bbb run` (LocalCluster of 2 workers)."""
    path = tmp_path_factory.mktemp("api_cli") / "tiny.zarr"
    assert cli(["run", str(tiny_workflow), "--store", str(path), "--workers", "2",
                "--no-progress"]) == 0
    return path


@pytest.fixture(scope="module")
def partial(tiny_workflow, tmp_path_factory) -> Path:
    """The tiny workflow run from Python with one chunk failing after writing its data."""
    path = tmp_path_factory.mktemp("api_partial") / "tiny.zarr"
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(FAIL_ENV, FAILED)
        with pytest.raises(RunFailed, match="chunk 1"):
            run_study(tiny_workflow, path, workers=1, echo=lambda s: None)
    return path


def _chunk_files(store: Path) -> dict[str, bytes]:
    """Every file of a store except the non-reproducible ones: the root attributes (creation
    time) and chunk_seconds (wall times)."""
    return {str(p.relative_to(store)): p.read_bytes() for p in sorted(store.rglob("*"))
            if p.is_file() and p.parts[len(store.parts)] != "chunk_seconds"
            and p.relative_to(store) != Path("zarr.json")}


def test_open_study_masks_the_particles_of_chunks_not_done(partial):
    raw, ds = open_study(partial, mask=False), open_study(partial)
    sel = dict(frequency=60.0, family="rest")
    failed = (ds.particle // 4 == 1).values  # chunk_size 4: particles 4..7 are chunk 1
    assert np.isfinite(raw.positions.sel(**sel).values[failed]).all()  # data were written
    assert np.isnan(ds.positions.sel(**sel).values[failed]).all()
    # every particle: finite positions iff its chunk is marked done (chunks cancelled after
    # the failure were never written either)
    done = StudyStore.open(partial).done()  # (frequency, family, chunk)
    per_particle = np.repeat(done, 4, axis=2)
    finite = np.isfinite(ds.positions.values).all(axis=-1)
    assert np.array_equal(finite, per_particle) and per_particle.sum() > 0
    assert np.array_equal(ds.particle_done.values, per_particle)


def test_run_study_resumes_with_a_distributed_client_to_the_cli_store_bit_for_bit(
        partial, cli_store, tiny_workflow, tmp_path):
    from distributed import Client, LocalCluster

    store = tmp_path / "tiny.zarr"
    shutil.copytree(partial, store)
    done = StudyStore.open(store).done()
    study = StudyStore.open(store).study
    todo = {(study.frequencies[fi], study.families[mi].name, ci)
            for fi, mi, ci in zip(*np.nonzero(~done), strict=True)}
    assert (60.0, "rest", 1) in todo

    # one worker: a LocalCluster started by run_study itself would have one per core
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        report = run_study(tiny_workflow, store, client=client, echo=lambda s: None)
    assert report.workers == 1  # the client's cluster ran it
    assert set(report.computed) == todo and report.skipped == report.n_chunks - len(todo)
    assert_same_store(store, cli_store)
    a, b = _chunk_files(store), _chunk_files(Path(cli_store))
    assert sorted(a) == sorted(b) and a == b


def test_a_missing_store_is_file_not_found_and_a_scene_is_named_as_one(tiny_workflow, tmp_path):
    """open_study, reduced and reduced_dataset of a path with no store raise what Python
    raises for a missing file; given a scene file, they say it is a scene."""
    from pipeline.api import reduced_dataset
    from pipeline.store.study_store import StoreError

    for read in (open_study, reduced, reduced_dataset):
        with pytest.raises(FileNotFoundError, match="nope.zarr: no such store"):
            read(tmp_path / "nope.zarr")
        with pytest.raises(StoreError, match="a scene, not a store") as e:
            read(tiny_workflow)
        assert not isinstance(e.value, FileNotFoundError)


def _particle_chunks(ds) -> dict[str, tuple[int, ...]]:
    """{variable: its dask chunks along particle} of every dask variable with particles."""
    return {n: v.chunks[v.dims.index("particle")] for n, v in ds.variables.items()
            if "particle" in v.dims and v.chunks is not None}


def test_open_study_keeps_the_stores_chunks_in_dask(cli_store):
    """Every variable with particles, masked or not, in dask chunks of one store chunk
    (chunk_size particles): the mask must not split them into one chunk per particle."""

    acc = StudyStore.open(cli_store).study.accuracy
    store_chunks = (acc.chunk_size,) * acc.n_chunks
    for mask in (True, False):
        chunks = _particle_chunks(open_study(cli_store, mask=mask))
        assert chunks and "positions" in chunks
        assert set(chunks.values()) == {store_chunks}, (mask, chunks)


def test_open_study_names_dimensions_and_units(cli_store):
    ds = open_study(cli_store)
    assert ds.positions.dims == ("frequency", "family", "particle", "time")
    assert ds.collisions.dims == ("frequency", "family", "particle", "collision", "field")
    units = {n: ds[n].attrs["units"] for n in ("positions", "frequency", "time")}
    assert units == {"positions": "mm", "frequency": "Hz", "time": "s"}
    assert list(ds.family.values) == ["rest", "launched"]
    assert all(isinstance(v, str | int | float) for v in ds.attrs.values())  # netCDF-safe


def test_reduced_equals_the_tables_bbb_reduce_writes(cli_store, tmp_path):
    assert cli(["reduce", str(cli_store), "--out", str(tmp_path)]) == 0
    tables = reduced(cli_store)
    for name in ("diffusion", "counters"):
        pd.testing.assert_frame_equal(tables[name], pd.read_parquet(tmp_path / f"{name}.parquet"),
                                      check_exact=True)
    ds = open_study(cli_store, reduced=True)
    d = pd.read_parquet(tmp_path / "diffusion.parquet")
    assert np.array_equal(ds.D.values, d["D"].to_numpy(), equal_nan=True)
    assert np.array_equal(ds.D_family_hi.sel(family="launched").values,
                          d["D_launched_hi"].to_numpy(), equal_nan=True)
    assert ds.D.attrs["units"] == "mm^2/s" and ds.D.dims == ("frequency",)
    c = pd.read_parquet(tmp_path / "counters.parquet").set_index(["f", "family"])
    assert ds.collisions_per_s.sel(frequency=60.0, family="launched").item() == \
        c.loc[(60.0, "launched"), "collisions_per_s"]


def test_run_study_refuses_a_client_that_is_not_one(tiny_workflow, tmp_path):
    with pytest.raises(TypeError, match="allowed: None, a distributed.Client"):
        run_study(tiny_workflow, tmp_path / "x.zarr", client=object(), echo=lambda s: None)
