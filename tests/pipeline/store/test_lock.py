"""The run lock of a store at an fsspec URL (pipeline/store/lock.py): the object `<url>.lock`,
created exclusively, renewed by a heartbeat, taken over once abandoned.  memory:// stores for
the lock's rules; a local:// store (fsspec on local disk, as s3:// would be, but seen by worker
processes) for whole `bbb run`s.  The local-path lock: tests/pipeline/store/test_study_store.py."""

from __future__ import annotations

import datetime as dt
import json
import os
import socket
import subprocess
import time
import uuid

import fsspec
import numpy as np
import pytest

from pipeline.cli import main
from pipeline.execute.task import compute_chunk
from pipeline.store import lock as lock_module
from pipeline.store.lock import run_lock
from pipeline.store.study_store import StoreError, StudyStore

from ..helpers import assert_same_store


@pytest.fixture
def url():
    """A memory:// store path of its own; its objects are removed afterwards."""
    path = f"memory://bbb-lock-{uuid.uuid4().hex}/s.zarr"
    yield path
    fs, root = fsspec.core.url_to_fs(path.rsplit("/", 1)[0])
    if fs.exists(root):
        fs.rm(root, recursive=True)


def lock_of(url: str) -> dict | None:
    fs, path = fsspec.core.url_to_fs(url + ".lock")
    return json.loads(fs.cat_file(path)) if fs.exists(path) else None


def write_lock(url: str, **holder) -> None:
    fs, path = fsspec.core.url_to_fs(url + ".lock")
    fs.pipe_file(path, json.dumps(holder).encode())


def ago(seconds: float) -> str:
    return (dt.datetime.now(dt.UTC) - dt.timedelta(seconds=seconds)).isoformat()


def test_a_second_run_on_a_held_url_store_is_refused_in_one_line_and_changes_nothing(
        url, study, tiny_workflow, capsys):
    store = StudyStore.create_or_open(url, study)
    compute_chunk(store, 0, 0, 0)
    before = {name: np.asarray(arr[...]) for name, arr in store.group().arrays()}
    with run_lock(url):
        held = lock_of(url)
        assert main(["run", str(tiny_workflow), "--store", url, "--workers", "1",
                     "--no-progress"]) == 2
        err = capsys.readouterr().err
        assert lock_of(url) == held  # the first run's lock untouched
    assert err.count("\n") == 1 and err.startswith(f"bbb: error: {url}: in use by another bbb run")
    assert f"(host {socket.gethostname()}, pid {os.getpid()}, since " in err
    after = {name: np.asarray(arr[...]) for name, arr in StudyStore.open(url).group().arrays()}
    assert sorted(after) == sorted(before)
    for name in before:
        assert np.array_equal(after[name], before[name], equal_nan=before[name].dtype.kind == "f")


def test_once_the_holder_releases_a_url_store_the_run_completes_it(
        reference, tiny_workflow, tmp_path, monkeypatch, capsys):
    """local:// is fsspec's local filesystem: the store goes through zarr's FsspecStore like an
    s3:// one, while the LocalCluster's worker processes see it (FSSPEC_LOCAL lets fsspec create
    its folders, as object stores need none)."""
    monkeypatch.setenv("FSSPEC_LOCAL", json.dumps({"auto_mkdir": True}))  # for the workers
    monkeypatch.setitem(fsspec.config.conf, "local", {"auto_mkdir": True})  # for this process
    path = tmp_path / "s.zarr"
    url = f"local://{path}"
    args = ["run", str(tiny_workflow), "--store", url, "--workers", "1", "--no-progress"]
    with run_lock(url):
        assert main(args) == 2
    assert "in use by another bbb run" in capsys.readouterr().err
    assert main(args) == 0
    assert lock_of(url) is None
    assert_same_store(reference[0], path)


def test_a_url_lock_created_between_a_look_and_the_create_is_not_overwritten(url, monkeypatch):
    """Two runs that both see no lock: the filesystem's exclusive create lets one through."""
    write_lock(url, host="other-host", pid=1, started="then", heartbeat=ago(0), token="theirs")
    real = lock_module._read_url_lock
    looks = []

    def sees_no_lock_at_first(fs, path):
        looks.append(path)
        return None if len(looks) == 1 else real(fs, path)

    monkeypatch.setattr(lock_module, "_read_url_lock", sees_no_lock_at_first)
    with pytest.raises(StoreError, match=r"in use by another bbb run \(host other-host, pid 1"):
        with run_lock(url):
            pass
    assert lock_of(url)["token"] == "theirs"


def test_a_url_lock_with_a_recent_heartbeat_from_another_host_is_refused(url):
    write_lock(url, host="other-host", pid=1, started="then", heartbeat=ago(60), token="theirs")
    with pytest.raises(StoreError) as e:
        with run_lock(url):
            pass
    assert f"delete {url}.lock if no run is active" in str(e.value)
    assert "last heartbeat 60 s ago); a run whose heartbeat stops is taken over after 300 s" \
        in str(e.value)
    assert lock_of(url)["token"] == "theirs"


def test_a_url_lock_whose_heartbeat_is_older_than_the_stale_limit_is_taken_over(url):
    stale = lock_module.STALE_SECONDS + 5
    write_lock(url, host="other-host", pid=1, started="then", heartbeat=ago(stale), token="theirs")
    with run_lock(url):
        assert lock_of(url)["pid"] == os.getpid()


def test_a_url_lock_of_a_dead_process_on_this_host_is_taken_over_at_once(url):
    dead = subprocess.Popen(["true"])
    dead.wait()
    write_lock(url, host=socket.gethostname(), pid=dead.pid, started="then", heartbeat=ago(0),
               token="theirs")
    with run_lock(url):
        assert lock_of(url)["pid"] == os.getpid()


def test_the_holder_of_a_url_lock_renews_its_heartbeat(url, monkeypatch):
    monkeypatch.setattr(lock_module, "HEARTBEAT_SECONDS", 0.05)
    with run_lock(url):
        first = lock_of(url)["heartbeat"]
        deadline = time.monotonic() + 10
        while lock_of(url)["heartbeat"] == first:
            assert time.monotonic() < deadline, "the heartbeat was not renewed"
            time.sleep(0.02)
        assert lock_of(url)["pid"] == os.getpid()


def test_a_url_lock_is_removed_when_its_run_ends_even_by_an_error(url):
    with pytest.raises(RuntimeError), run_lock(url):
        assert lock_of(url) is not None
        raise RuntimeError("the run failed")
    assert lock_of(url) is None
