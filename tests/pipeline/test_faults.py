"""Faults a cluster inflicts, survived with real processes and real stores (issue 6).

A worker killed mid-sweep, the whole `bbb run` killed mid-sweep, a chunk torn mid-write, a
second run on a held store, a task that raises; then `bbb status` of a partial store and
`bbb verify` of sound and corrupted stores.  Every "the same store" below is bit for bit
(helpers.assert_same_store).
"""

from __future__ import annotations

import dataclasses
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import zarr

from bbb.provenance import kernel_hash
from pipeline.cli import main
from pipeline.execute.run import run_study
from pipeline.store.study_store import KERNEL_ATTRS, StoreError, store_fingerprint
from pipeline.workflow.load import load_workflow
from pipeline.workflow.observables.counters import COUNTERS

from .helpers import QUIET, assert_same_store, write_as_a_run

BBB = Path(sys.executable).with_name("bbb")

# Arrays with one chunk per (frequency, family, ensemble chunk) whose bytes are reproducible.
CHUNK_ARRAYS = ("positions", "collisions", "n_recorded", *(f"n_{c}" for c in COUNTERS))
TIMEOUT = 300  # s, only ever reached when something hangs


# -- helpers ------------------------------------------------------------------------------------
def done_now(store) -> np.ndarray | None:
    """The store's done array, or None while the store is not yet laid out."""
    try:
        return np.asarray(zarr.open_group(str(store), mode="r")["done"][...], dtype=bool)
    except Exception:  # not created yet, or the layout is being written
        return None


def wait_for_first_done(store, proc: subprocess.Popen) -> np.ndarray:
    """Poll (every 20 ms) until >= 1 chunk is done; returns done at that moment."""
    deadline = time.monotonic() + TIMEOUT
    while True:
        done = done_now(store)
        if done is not None and done.any():
            return done
        assert proc.poll() is None, f"the run exited ({proc.returncode}) before any chunk was done"
        assert time.monotonic() < deadline, "no chunk done in time"
        time.sleep(0.02)


def chunk_of(store, fi: int, mi: int, ci: int, chunk_size: int) -> dict[str, np.ndarray]:
    g = zarr.open_group(str(store), mode="r")
    sl = slice(ci * chunk_size, (ci + 1) * chunk_size)
    return {name: np.asarray(g[name][fi, mi, sl]) for name in CHUNK_ARRAYS}


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and a.tobytes() == b.tobytes()  # NaN payloads included


def copy_store(src, dst) -> Path:
    shutil.copytree(src, dst)
    return Path(dst)


def group_gone(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return True
    return False


# -- a worker killed ----------------------------------------------------------------------------
def test_a_worker_killed_mid_sweep_leaves_the_store_bit_identical(
        fault_workflow, fault_reference, dask_cluster_workers, tmp_path):
    """SIGKILL one of two `dask worker` processes once >= 1 chunk is done: Dask reschedules its
    tasks on the other worker, the run exits 0 and the store equals an undisturbed run's."""
    address, workers = dask_cluster_workers
    store = tmp_path / "fault.zarr"
    run = subprocess.Popen([str(BBB), "run", str(fault_workflow), "--store", str(store),
                            "--scheduler", address, "--no-progress"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        at_kill = wait_for_first_done(store, run)
        workers[0].send_signal(signal.SIGKILL)
        workers[0].wait()
        assert not at_kill.all(), "the sweep ended before the kill; make FAULT longer"
        out, err = run.communicate(timeout=TIMEOUT)
    finally:
        if run.poll() is None:
            run.kill()
            run.wait()
    assert run.returncode == 0, err
    assert "fault: 16/16 chunks done (16 computed" in out
    assert workers[1].poll() is None  # the survivor did the rest
    assert_same_store(fault_reference, store)


# -- the whole run killed -----------------------------------------------------------------------
@pytest.fixture(scope="module")
def killed_run(fault_workflow, tmp_path_factory):
    """`bbb run` (client and its LocalCluster workers, one process group) SIGKILLed once >= 1
    chunk is done.  Returns (store, done at the kill, pid of the killed `bbb run`)."""
    store = tmp_path_factory.mktemp("killed") / "fault.zarr"
    # a session of its own: the kill takes the client and every worker at once, like a job
    # scheduler ending the job or a machine going down
    run = subprocess.Popen([str(BBB), "run", str(fault_workflow), "--store", str(store),
                            "--workers", "2", "--no-progress"], start_new_session=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_first_done(store, run)
    finally:
        os.killpg(run.pid, signal.SIGKILL)
        run.wait()
    deadline = time.monotonic() + 30
    while not group_gone(run.pid):  # nothing of the run may write after this point
        assert time.monotonic() < deadline, "processes of the killed run survived SIGKILL"
        time.sleep(0.05)
    done = done_now(store)
    assert done is not None and 0 < done.sum() < done.size, "the kill did not land mid-sweep"
    return store, done, run.pid


def test_every_chunk_marked_done_when_the_run_is_killed_holds_its_data(killed_run, fault_reference):
    """Each chunk done at the SIGKILL holds exactly the bytes of an undisturbed run's chunk
    (positions, collisions, n_recorded and counters): done is never written before the data."""
    store, done, _ = killed_run
    cs = 4  # FAULT's chunk_size
    for fi, mi, ci in zip(*np.nonzero(done), strict=True):
        got, want = chunk_of(store, fi, mi, ci, cs), chunk_of(fault_reference, fi, mi, ci, cs)
        for name in CHUNK_ARRAYS:
            assert same_bits(got[name], want[name]), (name, fi, mi, ci)


def test_rerun_after_a_kill_computes_only_chunks_not_done_and_matches_an_undisturbed_run(
        killed_run, fault_workflow, fault_reference, tmp_path):
    """Re-running takes over the killed run's stale lock (its pid is dead on this host),
    recomputes exactly the chunks not done at the kill, and ends bit-identical."""
    src, done, pid = killed_run
    store = copy_store(src, tmp_path / "fault.zarr")
    lock = Path(f"{store}.lock")
    shutil.copy(f"{src}.lock", lock)  # left behind by the killed run
    assert json.loads(lock.read_text())["pid"] == pid
    study = load_workflow(fault_workflow)
    report = run_study(study, store, workers=2, **QUIET)
    not_done = {(study.frequencies[fi], study.families[mi].name, int(ci))
                for fi, mi, ci in zip(*np.nonzero(~done), strict=True)}
    assert set(report.computed) == not_done and len(report.computed) == len(not_done)
    assert report.skipped == done.sum()
    assert not lock.exists()
    assert_same_store(fault_reference, store)


def test_a_torn_chunk_not_marked_done_is_recomputed(reference, tiny_workflow, tmp_path):
    """Garbage bytes in a chunk's positions and collisions files and a lost counter file,
    without its done marker (a write cut short): the re-run recomputes that chunk alone, the
    torn bytes are overwritten, never decoded, and the store equals the reference."""
    store = copy_store(reference[0], tmp_path / "torn.zarr")
    zarr.open_group(str(store), mode="r+")["done"][1, 0, 1] = False  # f = 60 Hz, rest, chunk 1
    (store / "positions/c/1/0/1/0").write_bytes(b"torn")
    (store / "collisions/c/1/0/1/0/0").write_bytes(b"\x28\xb5\x2f\xfd half a zstd frame")
    (store / "n_collisions/c/1/0/1").unlink()
    report = run_study(load_workflow(tiny_workflow), store, workers=1, **QUIET)
    assert report.computed == [(60.0, "rest", 1)] and report.skipped == 7
    assert_same_store(reference[0], store)


# -- concurrent runs --------------------------------------------------------------------------
def test_a_second_bbb_run_on_a_held_store_exits_2_naming_the_holder(
        reference, tiny_workflow, tmp_path, capsys):
    """While one `bbb run` holds the store, a second is refused in one line with the holder's
    host and pid and how to clear a stale lock; the holder finishes undisturbed."""
    store = tmp_path / "tiny.zarr"
    lock = Path(f"{store}.lock")
    first = subprocess.Popen([str(BBB), "run", str(tiny_workflow), "--store", str(store),
                              "--workers", "1", "--no-progress"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + TIMEOUT
        while not (lock.exists() and lock.read_text().strip()):
            assert first.poll() is None and time.monotonic() < deadline, "no lock taken"
            time.sleep(0.02)
        assert main(["run", str(tiny_workflow), "--store", str(store)]) == 2
        assert first.poll() is None  # the refusal happened while the first run held the lock
        assert json.loads(lock.read_text())["pid"] == first.pid  # the lock was left alone
        _, err = first.communicate(timeout=TIMEOUT)
    finally:
        if first.poll() is None:
            first.kill()
            first.wait()
    refusal = capsys.readouterr().err
    assert refusal.count("\n") == 1 and "Traceback" not in refusal
    assert f"in use by another bbb run (host {socket.gethostname()}, pid {first.pid}" in refusal
    assert f"if no run is active, delete {lock}" in refusal
    assert first.returncode == 0, err
    assert_same_store(reference[0], store)


def test_two_runs_taking_over_one_stale_lock_do_not_both_get_it(tmp_path, monkeypatch):
    """The interleaving that let two runs in: run B reads a stale lock (dead pid, this host);
    before B removes it, run A removes it too and writes its own; B must now see A's lock and
    be refused, not remove A's lock believing it the stale one."""
    from pipeline.store import lock as store_module

    path = str(tmp_path / "s.zarr")
    lock = Path(f"{path}.lock")
    dead = subprocess.Popen(["true"])
    dead.wait()
    lock.write_text(json.dumps({"host": socket.gethostname(), "pid": dead.pid}))
    run_a = subprocess.Popen(["sleep", "60"])  # stands in for run A: a live process
    real_read = store_module._read_lock
    reads = []

    def b_reads_then_a_takes_over(p):
        holder = real_read(p)
        if not reads:  # B's first look: the stale holder; then A takes over
            lock.unlink()
            lock.write_text(json.dumps({"host": socket.gethostname(), "pid": run_a.pid}))
        reads.append(holder)
        return holder

    monkeypatch.setattr(store_module, "_read_lock", b_reads_then_a_takes_over)
    try:
        with pytest.raises(StoreError, match=rf"in use by another bbb run .*pid {run_a.pid}"):
            with store_module.run_lock(path):
                pass
        assert json.loads(lock.read_text())["pid"] == run_a.pid  # A's lock untouched
    finally:
        run_a.kill()
        run_a.wait()


# -- a task that raises ---------------------------------------------------------------------------
def test_invalid_parameters_stop_the_run_before_anything_is_written(tiny_workflow, tmp_path):
    """A Study that slipped past validation (f = -60 Hz, impossible from a workflow file):
    every point's bbb.Params is made before the store is, so the run stops on the client,
    naming the cause, and leaves no store behind."""
    study = dataclasses.replace(load_workflow(tiny_workflow), frequencies=(54.0, -60.0))
    store = tmp_path / "bad.zarr"
    with pytest.raises(ValueError,
                       match=r"Params\.f = -60\.0 is out of range; allowed: 0\.001 ≤ f ≤ 100000 \(Hz\)"):
        run_study(study, store, workers=1, **QUIET)
    assert not store.exists()


# -- bbb status ----------------------------------------------------------------------------------
def test_status_counts_done_chunks_per_frequency_and_family_of_a_partial_store(
        reference, tmp_path, capsys):
    store = copy_store(reference[0], tmp_path / "partial.zarr")
    g = zarr.open_group(str(store), mode="r+")
    g["done"][0, 0, 1] = False  # 54 Hz, rest, chunk 1
    g["done"][1, 1, 0] = False  # 60 Hz, launched, chunk 0
    assert main(["status", str(store)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith(f"tiny: 6/8 chunks done in {store}")
    assert [line.split() for line in out[2:]] == [["54", "1/2", "2/2"], ["60", "2/2", "1/2"]]


# -- bbb verify ----------------------------------------------------------------------------------
def test_verify_passes_a_sound_store(reference, capsys):
    assert main(["verify", str(reference[0])]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert out == [f"tiny: verified 8 done of 8 chunks in {reference[0]}: OK"]


def _set(name, index, value):
    """A value a faulty run could have written: set, and its chunk's digest recorded."""
    def corrupt(store: Path):
        write_as_a_run(store, name, index, value)
    return corrupt


def _shift(name, index, delta):
    def corrupt(store: Path):
        write_as_a_run(store, name, index, lambda v: v + delta)
    return corrupt


def _file(rel, data: bytes | None):
    def corrupt(store: Path):
        if data is None:
            (store / rel).unlink()
        else:
            (store / rel).write_bytes(data)
    return corrupt


def _attr(key, value):
    def corrupt(store: Path):
        g = zarr.open_group(str(store), mode="r+")
        g.attrs[key] = value(dict(g.attrs)[key]) if callable(value) else value
    return corrupt


def _other_kernel(kernel_hash: str):
    """The attributes a store made by another kernel has: its kernel hash, and a fingerprint
    consistent with it (bbb run wrote both)."""
    def corrupt(store: Path):
        g = zarr.open_group(str(store), mode="r+")
        kernel = {**{k: g.attrs[k] for k in KERNEL_ATTRS}, "kernel_hash": kernel_hash}
        g.attrs.update({"kernel_hash": kernel_hash, "fingerprint": store_fingerprint(
            g.attrs["workflow_fingerprint"], kernel)})
    return corrupt


def _drop_array(name):
    def corrupt(store: Path):
        shutil.rmtree(store / name)
    return corrupt


# corruption of a copy of the reference store: (how, the start of each line verify must print)
# Indices: [frequency 0 = 54 Hz, 1 = 60 Hz; family 0 = rest, 1 = launched; particle, ...];
# particles 4-7 are chunk 1.  Collision fields: t x y vx vy phase (y is 2).
CORRUPTIONS = {
    "NaN in a position": (
        _set("positions", (1, 1, 6, 5), np.nan),
        "positions[f = 60 Hz, family launched, chunk 1]: 1 non-finite values"),
    "collision 0.5 mm below the surface": (
        _shift("collisions", (0, 0, 1, 3, 2), -0.5),
        "collisions[f = 54 Hz, family rest, chunk 0]: 1 collisions off the floor surface"),
    "collision 0.01 mm above the surface": (
        _shift("collisions", (1, 0, 7, 0, 2), 0.01),
        "collisions[f = 60 Hz, family rest, chunk 1]: 1 collisions off the floor surface"),
    "done chunk whose positions file is gone": (
        _file("positions/c/0/1/1/0", None),
        "positions[f = 54 Hz, family launched, chunk 1]: values differ from those its task wrote"),
    "done chunk whose collisions file is garbage": (
        _file("collisions/c/1/0/0/0/0", b"garbage"),
        "collisions[f = 60 Hz, family rest, chunk 0]: unreadable: its bytes fail their CRC-32C"),
    "n_recorded beyond the record length": (
        _set("n_recorded", (0, 1, 0), 41),
        "n_recorded[f = 54 Hz, family launched, chunk 0]: 1 out of range"),
    "n_recorded below the rows written": (
        _shift("n_recorded", (1, 0, 2), -1),
        "collisions[f = 60 Hz, family rest, chunk 0]: 1 rows beyond n_recorded are not NaN"),
    "start outside the first cell": (
        _shift("positions", (0, 0, 0, 0), 2.0),
        "positions[f = 54 Hz, family rest, chunk 0]: 1 particles start outside the first cell"),
    "negative counter": (
        _set("n_sticks", (1, 1, 5), -1),
        "n_sticks[f = 60 Hz, family launched, chunk 1]: 1 negative counts"),
    "repaired velocity counted": (
        _set("n_anomalies", (0, 0, 3), 2),
        "n_anomalies[f = 54 Hz, family rest, chunk 0]: 1 particles with repaired velocities"),
    "fingerprint of another workflow": (
        _attr("fingerprint", "0" * 64),
        "attribute fingerprint: 000000000000 does not match the stored workflow and kernel"),
    "workflow fingerprint of another workflow": (
        _attr("workflow_fingerprint", "0" * 64),
        "attribute workflow_fingerprint: 000000000000 does not match the stored workflow"),
    "made by another kernel": (
        _other_kernel("ab" * 32),
        f"attribute kernel_hash: store {'ab' * 32}, this bbb {kernel_hash()}: made by another "
        "kernel"),
    "params attribute edited": (
        _attr("params", lambda p: json.dumps(dict(json.loads(p), alpha=0.5))),
        "attribute params: alpha: 0.5, expected 0.7"),
    "params attribute not JSON": (
        _attr("params", "{alpha: 0.5"),
        "attribute params: not a JSON object string",
        "attribute params: '{alpha: 0.5', expected {"),
    "array removed": (
        _drop_array("chunk_seconds"),
        "chunk_seconds: missing",
        "consolidated metadata: differs from the arrays (chunk_seconds)"),
}


@pytest.mark.parametrize("case", list(CORRUPTIONS))
def test_verify_exits_1_naming_each_corruption(case, reference, tmp_path, capsys):
    """A copy of the sound store with one corruption: `bbb verify` exits 1, lists it on a line
    naming the array (or attribute) and the frequency, family and chunk, and sums up in one
    `bbb: error:` line."""
    corrupt, *lines = CORRUPTIONS[case]
    store = copy_store(reference[0], tmp_path / "s.zarr")
    corrupt(store)
    assert main(["verify", str(store)]) == 1
    cap = capsys.readouterr()
    problems = cap.out.strip().splitlines()[:-1]
    assert len(problems) == len(lines), problems
    assert all(p.startswith(line) for p, line in zip(problems, lines, strict=True)), problems
    assert cap.err == f"bbb: error: {store}: {len(lines)} inconsistencies (listed above)\n"
