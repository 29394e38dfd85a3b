"""JobKeeper on the real SLURM test cluster: a worker job cancelled while `slurm_cluster` keeps
it is replaced by a new job, whose worker joins the same scheduler.  This is the check that
fails when the SpecCluster internals replace_ended_job uses change behaviour."""

from __future__ import annotations

import subprocess
import time

import dask
import pytest

pytestmark = [pytest.mark.slow, pytest.mark.slurm]

TIMEOUT = 90.0  # seconds any one wait may take (a job starts ~3 s after sbatch, a worker ~3 s after)


def squeue(env: dict[str, str]) -> dict[str, str]:
    """job id -> state of every job in the queue."""
    out = subprocess.run(["squeue", "-h", "-o", "%i %T"], env=env, capture_output=True, text=True,
                         timeout=30, check=True).stdout.split()
    return dict(zip(out[::2], out[1::2], strict=True))


def wait_for(what: str, condition) -> None:
    deadline = time.monotonic() + TIMEOUT
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"not after {TIMEOUT:.0f} s: {what}")
        time.sleep(0.2)


def test_a_cancelled_worker_job_is_replaced_by_a_new_job_whose_worker_joins(
        slurm_env, tmp_path, monkeypatch):
    pytest.importorskip("dask_jobqueue")
    from distributed import Client

    from pipeline.execute.cluster import slurm_cluster

    monkeypatch.setenv("SLURM_CONF", slurm_env["SLURM_CONF"])  # for dask-jobqueue's sbatch, scancel
    config = {"jobqueue.slurm.cores": 1, "jobqueue.slurm.memory": "200MB",  # nodes: 1 CPU, 256 MB
              "jobqueue.slurm.queue": "debug", "jobqueue.slurm.walltime": "00:10:00",
              "jobqueue.slurm.log-directory": str(tmp_path),
              "jobqueue.slurm.scheduler-options": {"host": "127.0.0.1"},
              "jobqueue.slurm.worker-extra-args": ["--host", "127.0.0.1"]}
    said: list[str] = []
    with dask.config.set(config), slurm_cluster(1, echo=said.append) as address, \
            Client(address) as client:
        (first,) = squeue(slurm_env)  # the one job, its worker joined
        (old_worker,) = client.scheduler_info()["workers"]
        subprocess.run(["scancel", first], env=slurm_env, check=True, timeout=30)
        wait_for("a worker of a new job joins", lambda: (
            set(client.scheduler_info()["workers"]) - {old_worker}
            and list(squeue(slurm_env).values()) == ["RUNNING"]))
        (second,) = squeue(slurm_env)
        assert second != first
        assert said[-1] == "SLURM: job SLURMCluster-0 ended (all its workers left); submitting it anew"
    wait_for("every job cancelled when the cluster closes", lambda: not squeue(slurm_env))
