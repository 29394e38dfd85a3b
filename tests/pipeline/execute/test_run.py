"""Running a study on real Dask clusters: reproducibility, resume, fault reporting."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.execute.run import RunFailed, run_study
from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import load_workflow, parse_workflow

from ..helpers import QUIET as quiet
from ..helpers import TINY, assert_same_store, store_arrays


def test_local_cluster_run_completes_every_chunk(reference):
    path, report = reference
    store = StudyStore.open(path)
    assert store.done().all() and len(report.computed) == report.n_chunks == 8
    assert report.workers == 2 and report.collisions > 0
    x = store_arrays(path)
    assert np.isfinite(x["positions"]).all()
    assert x["n_collisions"].sum() == report.collisions
    assert (x["n_recorded"] > 0).any()


def test_one_worker_gives_bit_identical_arrays(reference, tiny_workflow, tmp_path):
    run_study(load_workflow(tiny_workflow), tmp_path / "one.zarr", workers=1, **quiet)
    assert_same_store(reference[0], tmp_path / "one.zarr")


def test_scheduler_and_worker_processes_give_the_local_cluster_store(
        reference, tiny_workflow, tmp_path, dask_cluster):
    report = run_study(load_workflow(tiny_workflow), tmp_path / "remote.zarr",
                       scheduler=dask_cluster, **quiet)
    assert report.workers == 2
    assert_same_store(reference[0], tmp_path / "remote.zarr")


def test_resume_recomputes_only_unfinished_chunks(reference, tiny_workflow, tmp_path):
    study = load_workflow(tiny_workflow)
    path = tmp_path / "resumed.zarr"
    # The last-submitted chunk writes its data, then fails before being marked done.
    with pytest.raises(RunFailed, match=r"f = 60 Hz, family launched, chunk 1 failed"):
        run_study(study, path, workers=2, fail_chunks="60:launched:1", **quiet)
    done = StudyStore.open(path).done()
    assert 0 < done.sum() < done.size and not done[1, 1, 1]
    unfinished = {(study.frequencies[fi], study.families[mi].name, ci)
                  for fi, mi, ci in zip(*np.nonzero(~done), strict=True)}
    report = run_study(study, path, workers=2, fail_chunks="", **quiet)
    assert set(report.computed) == unfinished and report.skipped == done.sum()
    assert_same_store(reference[0], path)


def test_rerunning_a_finished_store_computes_nothing(reference, tiny_workflow):
    report = run_study(load_workflow(tiny_workflow), reference[0], workers=2, **quiet)
    assert report.computed == [] and report.skipped == report.n_chunks


def test_adding_frequencies_and_families_leaves_old_results_unchanged(reference, tmp_path):
    bigger = parse_workflow(
        TINY.replace("[54.0, 60.0]", "[60.0, 66.0, 54.0]")
        .replace("[families.rest]", '[families.dropped]\ninitial = "dropped"\n\n[families.rest]'),
        source="bigger.toml")
    run_study(bigger, tmp_path / "bigger.zarr", workers=2, **quiet)
    a, b = store_arrays(reference[0]), store_arrays(tmp_path / "bigger.zarr")
    # reference order: f (54, 60) x (rest, launched); bigger: f (60, 66, 54) x (dropped, rest,
    # launched)
    for fa, fb in ((0, 2), (1, 0)):
        for ma, mb in ((0, 1), (1, 2)):
            assert np.array_equal(a["positions"][fa, ma], b["positions"][fb, mb])


def test_bbb_run_with_an_edited_kernel_refuses_to_resume_the_store(reference, tiny_workflow, tmp_path):
    """A copy of bbb whose kernel (its first hashed source) was edited runs `bbb run` on a
    partial store of this kernel: exit 2, one line naming both kernel hashes, and the store is
    left as it was (the chunk not done stays not done: no chunk of the other kernel is mixed
    in)."""
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    import zarr

    import bbb
    import pipeline
    from bbb.provenance import KERNEL_SOURCES, kernel_hash

    store = tmp_path / "tiny.zarr"
    shutil.copytree(reference[0], store)
    zarr.open_group(str(store), mode="r+")["done"][1, 1, 1] = False
    before = store_arrays(store)
    code = tmp_path / "code"
    for pkg in (bbb, pipeline):
        src = Path(pkg.__file__).parent
        shutil.copytree(src, code / src.name, ignore=shutil.ignore_patterns("__pycache__"))
    kernel = code / "bbb" / sorted(KERNEL_SOURCES)[0]
    kernel.write_text(kernel.read_text() + "\n_EDITED = 1  # a code edit: another kernel\n")
    new = subprocess.run([sys.executable, "-c", "from bbb.provenance import kernel_hash; "
                          "print(kernel_hash())"], cwd=code, capture_output=True, text=True,
                         check=True).stdout.strip()
    assert new != kernel_hash()
    out = subprocess.run([sys.executable, "-m", "pipeline", "run", str(tiny_workflow), "--store",
                          str(store), "--workers", "1", "--no-progress"], cwd=code,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr
    assert f"made by another kernel (kernel_hash: store {kernel_hash()}, this bbb {new})" in out.stderr
    after = store_arrays(store)
    assert sorted(after) == sorted(before)
    for name in before:
        assert np.array_equal(before[name], after[name], equal_nan=before[name].dtype.kind == "f")


def test_a_worker_running_another_kernel_fails_its_task_before_writing(
        tiny_workflow, tmp_path, monkeypatch):
    """Workers of a remote cluster importing an edited copy of bbb: every task refuses to
    compute into the store made by this kernel, naming both hashes, and nothing is written."""
    import shutil
    from pathlib import Path

    import bbb
    from bbb.provenance import kernel_hash

    from ..conftest import dask_processes

    code = tmp_path / "code"
    # with numba's cache (its index keys on the sources' mtimes, which copytree keeps): the
    # edit goes to a hashed source that holds no jitted function, so no worker compiles
    shutil.copytree(Path(bbb.__file__).parent, code / "bbb")
    edited = code / "bbb" / "numerics.py"
    edited.write_text(edited.read_text() + "\n_EDITED = 1  # a code edit: another kernel\n")
    monkeypatch.setenv("PYTHONPATH", str(code))  # the workers' environment, not this process's
    (tmp_path / "cluster").mkdir()
    store = tmp_path / "s.zarr"
    with dask_processes(tmp_path / "cluster") as (address, _):
        with pytest.raises(RunFailed, match=r"failed: KernelMismatch: worker \S+ runs another "
                           rf"kernel \(kernel_hash: worker [0-9a-f]{{64}}, store {kernel_hash()}\)"):
            run_study(load_workflow(tiny_workflow), store, scheduler=address, **quiet)
    x = store_arrays(store)
    assert not x["done"].any() and np.isnan(x["positions"]).all()
