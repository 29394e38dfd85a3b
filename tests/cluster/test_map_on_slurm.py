"""`bbb run MAP.toml --cluster slurm --jobs 2` on the real SLURM test cluster (conftest.py):
a small parameter map (TINY with ``[grid] alpha = [0.5, 0.7]``: 4 points x 2 families x 4
chunks = 32 chunks of ~1.5 s) run through dask-jobqueue by the public command, disturbed
mid-run, must end bit-identical to an undisturbed local 2-worker run of the same workflow.

Each test runs `bbb run` as a subprocess with a dask configuration of its own (DASK_CONFIG):
one single-CPU job per node, and Dask's memory management off (a worker with the kernel
loaded, ~205 MiB, is over the 80 % of the job's memory at which Dask pauses it; docs/cluster.md).
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import zarr

from ..pipeline.helpers import QUIET, TINY, assert_same_store

pytestmark = [pytest.mark.slow, pytest.mark.slurm]

BBB = Path(sys.executable).with_name("bbb")
TIMEOUT = 300.0  # seconds any one wait may take; only reached when something hangs
N_CHUNKS = 32

# TINY as a map, each chunk long enough (t_max = 800 s of simulated time, ~1.5 s of CPU) that
# the SLURM run lasts ~20-40 s on two single-CPU jobs and a disturbance lands mid-run
MAP = (TINY.replace('name = "tiny"', 'name = "slurm_map"')
       .replace("[frequencies]", "[grid]\nalpha = [0.5, 0.7]\n\n[frequencies]")
       .replace("n_particles = 8", "n_particles = 16")
       .replace("t_max = 10.0", "t_max = 800.0"))

DASK_CONFIG = """\
jobqueue:
  slurm:
    cores: 1
    memory: 250MB
    queue: debug
    walltime: "00:10:00"
    log-directory: {logs}
    local-directory: {scratch}
    scheduler-options: {{host: 127.0.0.1}}
    worker-extra-args: ["--host", "127.0.0.1"]
distributed:
  worker:
    memory: {{target: false, spill: false, pause: false, terminate: false}}
"""


# -- helpers ------------------------------------------------------------------------------------
def squeue(env: dict[str, str]) -> dict[str, str]:
    """job id -> state of every job in the queue."""
    out = subprocess.run(["squeue", "-h", "-o", "%i %T"], env=env, capture_output=True, text=True,
                         timeout=30, check=True).stdout.split()
    return dict(zip(out[::2], out[1::2], strict=True))


def wait_for(what: str, condition, proc: subprocess.Popen | None = None,
             timeout: float = TIMEOUT) -> float:
    """Poll ``condition`` until true (failing if ``proc`` exits first); seconds it took."""
    start = time.monotonic()
    while not condition():
        if proc is not None and proc.poll() is not None:
            out, err = proc.communicate()
            pytest.fail(f"bbb run exited ({proc.returncode}) before: {what}\n{out}\n{err}")
        if time.monotonic() - start > timeout:
            pytest.fail(f"not after {timeout:.0f} s: {what}")
        time.sleep(0.1)
    return time.monotonic() - start


def done_now(store: Path) -> np.ndarray | None:
    """The store's done array, or None while the store is not yet laid out."""
    try:
        return np.asarray(zarr.open_group(str(store), mode="r")["done"][...], dtype=bool)
    except Exception:  # not created yet, or the layout is being written
        return None


def mid_run(store: Path) -> bool:
    """Some chunks done and some not (a quarter done, so both workers are busy by then)."""
    done = done_now(store)
    return done is not None and N_CHUNKS // 4 <= done.sum() < done.size


def cancel_all(env: dict[str, str]) -> None:
    jobs = list(squeue(env))
    if jobs:
        subprocess.run(["scancel", *jobs], env=env, timeout=30, check=False)


@pytest.fixture(scope="module")
def map_workflow(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("map") / "slurm_map.toml"
    path.write_text(MAP)
    return path


@pytest.fixture(scope="module")
def local_reference(map_workflow, tmp_path_factory) -> Path:
    """The same map run undisturbed on a local 2-worker cluster."""
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import load_workflow

    store = tmp_path_factory.mktemp("reference") / "slurm_map.zarr"
    run_study(load_workflow(map_workflow), store, workers=2, **QUIET)
    return store


@pytest.fixture
def run_env(slurm_env, tmp_path) -> dict[str, str]:
    """The environment of `bbb run --cluster slurm` on the test cluster (and of its jobs, which
    inherit it): SLURM_CONF, and DASK_CONFIG pointing at a configuration for 1-CPU nodes."""
    config = tmp_path / "dask"
    config.mkdir()
    (config / "jobqueue.yaml").write_text(DASK_CONFIG.format(logs=tmp_path / "logs",
                                                             scratch=tmp_path / "scratch"))
    assert not squeue(slurm_env), "jobs left in the test cluster's queue by an earlier test"
    yield {**slurm_env, "DASK_CONFIG": str(config)}
    cancel_all(slurm_env)  # whatever a failed test left


def bbb_run(workflow: Path, store: Path, env: dict[str, str], jobs: str = "2"
            ) -> subprocess.Popen:
    return subprocess.Popen([str(BBB), "run", str(workflow), "--store", str(store),
                             "--cluster", "slurm", "--jobs", jobs, "--no-progress"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def bbb_status(store: Path, env: dict[str, str]) -> str:
    return subprocess.run([str(BBB), "status", str(store)], env=env, capture_output=True,
                          text=True, timeout=60, check=True).stdout


def finish(proc: subprocess.Popen) -> tuple[str, str]:
    try:
        return proc.communicate(timeout=TIMEOUT)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


# -- the tests ----------------------------------------------------------------------------------
def test_a_map_with_a_worker_job_cancelled_mid_run_finishes_bit_identical_to_a_local_run(
        map_workflow, local_reference, run_env, tmp_path):
    """scancel one of the two running worker jobs once some chunks are done and some not: its
    chunks re-run on the other worker, a new job replaces it, the run exits 0 and the store is
    the local run's bit for bit; every job is gone when the run ends."""
    store = tmp_path / "slurm_map.zarr"
    run = bbb_run(map_workflow, store, run_env)
    try:
        wait_for("both jobs running", lambda: list(squeue(run_env).values()) == ["RUNNING"] * 2,
                 run)
        status = bbb_status(store, run_env)  # bbb status lists the run's jobs, as squeue does
        rows = {ln.split()[0]: ln.split()[1] for ln in status.splitlines() if ln.split()[:2]}
        assert {job: rows.get(job) for job in squeue(run_env)} == dict.fromkeys(
            squeue(run_env), "RUNNING"), status
        assert "jobs of the run" in status and "2 jobs requested" in status
        wait_for("a quarter of the chunks done, not all", lambda: mid_run(store), run)
        victim = sorted(squeue(run_env))[0]
        subprocess.run(["scancel", victim], env=run_env, check=True, timeout=30)
        at_cancel = done_now(store)
        out, err = finish(run)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode == 0, err
    assert not at_cancel.all(), "the run ended before the scancel; make MAP longer"
    assert f"slurm_map: {N_CHUNKS}/{N_CHUNKS} chunks done ({N_CHUNKS} computed" in out
    assert "ended (all its workers left); submitting it anew" in out + err
    assert_same_store(local_reference, store)
    wait_for("every job cancelled after the run", lambda: not squeue(run_env), timeout=30)
    assert not Path(f"{store}.jobs").exists()  # the record of the run's jobs is gone with them


def test_a_map_on_elastic_workers_uses_both_nodes_and_ends_bit_identical(
        map_workflow, local_reference, run_env, tmp_path):
    """`--jobs 0:2`: no job before a chunk is queued; the map's 32 queued chunks bring up two
    jobs (the most asked for, and the nodes' limit); the run exits 0, bit-identical to the
    local run, and no job is left."""
    store = tmp_path / "slurm_map.zarr"
    run = bbb_run(map_workflow, store, run_env, jobs="0:2")
    try:
        wait_for("two jobs running", lambda: list(squeue(run_env).values()) == ["RUNNING"] * 2,
                 run)
        out, err = finish(run)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode == 0, err
    assert "elastic: 0 to 2 jobs" in out + err
    assert f"slurm_map: {N_CHUNKS}/{N_CHUNKS} chunks done ({N_CHUNKS} computed" in out
    assert_same_store(local_reference, store)
    wait_for("every job cancelled after the run", lambda: not squeue(run_env), timeout=30)


def test_a_map_whose_client_was_killed_mid_run_resumes_to_the_same_store(
        map_workflow, local_reference, run_env, tmp_path):
    """SIGKILL `bbb run` (the client, and the scheduler inside it) mid-run: its jobs outlive it
    (nothing could cancel them), so cancel them as a user would; then the same `bbb run` again
    takes over the stale lock, computes only the chunks not done and ends bit-identical."""
    store = tmp_path / "slurm_map.zarr"
    run = bbb_run(map_workflow, store, run_env)
    try:
        wait_for("a quarter of the chunks done, not all", lambda: mid_run(store), run)
    finally:
        run.kill()
        run.wait()
    left = squeue(run_env)
    assert left, "no job of the killed run left in the queue"
    subprocess.run(["scancel", *left], env=run_env, check=True, timeout=30)
    wait_for("the killed run's jobs gone", lambda: not squeue(run_env), timeout=60)
    done = done_now(store)  # final: no worker of the killed run is left to mark a chunk done
    assert 0 < done.sum() < done.size, "the kill did not land mid-run; make MAP longer"

    again = bbb_run(map_workflow, store, run_env)
    out, err = finish(again)
    assert again.returncode == 0, err
    assert (f"slurm_map: {N_CHUNKS}/{N_CHUNKS} chunks done ({N_CHUNKS - done.sum()} computed, "
            f"{done.sum()} already done)") in out
    assert_same_store(local_reference, store)


def test_sigterm_to_bbb_run_cancels_its_slurm_jobs_before_it_exits(map_workflow, run_env, tmp_path):
    """SIGTERM to `bbb run --cluster slurm` mid-run ends it as Ctrl-C does: exit 143, and when it
    has exited none of its jobs is still running or pending (they are cancelled, not left to
    end by themselves once their workers lose the scheduler, ~3.5 s later here), and the queue
    is empty within a few seconds."""
    store = tmp_path / "slurm_map.zarr"
    run = bbb_run(map_workflow, store, run_env)
    try:
        wait_for("both jobs running", lambda: list(squeue(run_env).values()) == ["RUNNING"] * 2,
                 run)
        wait_for("a chunk done", lambda: (d := done_now(store)) is not None and d.any(), run)
        run.send_signal(signal.SIGTERM)
        out, err = finish(run)
        at_exit = squeue(run_env)
        wait_for("every job gone from the queue", lambda: not squeue(run_env), timeout=10)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode == 143, err
    assert "terminated (SIGTERM)" in err
    assert not {job: state for job, state in at_exit.items() if state in ("RUNNING", "PENDING")}
