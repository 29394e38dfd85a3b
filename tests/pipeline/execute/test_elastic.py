"""Elastic workers (pipeline/execute/elastic.py) on a real LocalCluster: Dask's Adaptive driven by
the chunks a run has queued, as `bbb run --cluster slurm --jobs MIN:MAX` drives it on SLURM."""

from __future__ import annotations

import threading
import time

import pytest

from pipeline.execute.elastic import QUEUED_KEY, QueueGauge, WaveAdaptive
from pipeline.execute.run import run_study
from pipeline.workflow.load import parse_workflow

from ..helpers import QUIET, TINY, assert_same_store


def wait_until(what: str, condition, timeout: float = 60.0) -> None:
    start = time.monotonic()
    while not condition():
        if time.monotonic() - start > timeout:
            pytest.fail(f"not after {timeout:.0f} s: {what}")
        time.sleep(0.05)


@pytest.fixture
def elastic_cluster():
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=0, threads_per_worker=1, processes=True, dashboard_address=":0",
                      env={"NUMBA_NUM_THREADS": "1"}) as cluster, Client(cluster) as client:
        retiring: set[str] = set()
        cluster.adapt(Adaptive=lambda c, **kw: WaveAdaptive(c, retiring=retiring, **kw),
                      minimum=0, maximum=2, interval="100ms", wait_count=3)
        yield cluster, client, retiring


def test_the_workers_follow_the_queued_chunks_between_minimum_and_maximum(elastic_cluster):
    """No chunk queued: no worker.  5 queued: the maximum, 2.  1 queued: 1 (after 3 lower
    targets in a row, the idle one retired and named to the job keeper).  0: none."""
    cluster, client, retiring = elastic_cluster

    def n_workers() -> int:
        return len(client.scheduler_info(n_workers=-1)["workers"])

    time.sleep(0.5)
    assert n_workers() == 0
    client.set_metadata(QUEUED_KEY, 5)
    wait_until("2 workers for 5 queued chunks", lambda: n_workers() == 2)
    time.sleep(0.5)
    assert n_workers() == 2  # never above the maximum
    client.set_metadata(QUEUED_KEY, 1)
    wait_until("1 worker for 1 queued chunk", lambda: n_workers() == 1)
    assert len(retiring) == 1  # the retired worker's name, so that its job is not replaced
    client.set_metadata(QUEUED_KEY, 0)
    wait_until("no worker for no queued chunk", lambda: n_workers() == 0)


def test_a_run_on_elastic_workers_starts_them_and_ends_bit_identical(elastic_cluster, tmp_path):
    """A run on a cluster that starts with no worker: the run's queue brings workers up (at
    most 2), the run completes, the store is a 2-worker LocalCluster run's bit for bit, and
    the queue it leaves published is 0."""
    cluster, client, _ = elastic_cluster
    study = parse_workflow(TINY.replace("t_max = 10.0", "t_max = 40.0"))
    seen: list[int] = []
    stop = threading.Event()

    def watch():
        while not stop.is_set():
            seen.append(len(cluster.scheduler.workers))
            time.sleep(0.05)

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    reports = []
    run = threading.Thread(target=lambda: reports.append(run_study(
        study, tmp_path / "elastic.zarr", scheduler=cluster.scheduler_address, **QUIET)),
        daemon=True)
    run.start()
    run.join(timeout=120)  # a run whose queue brings up no worker would wait forever
    stop.set()
    watcher.join()
    assert reports, "the run did not end within 120 s (no worker came up?)"
    report = reports[0]
    assert report.workers == 0 and len(report.computed) == 8
    assert 1 <= max(seen) <= 2
    assert client.get_metadata(QUEUED_KEY) == 0
    reference = tmp_path / "reference.zarr"
    run_study(study, reference, workers=2, **QUIET)
    assert_same_store(reference, tmp_path / "elastic.zarr")


def test_the_gauge_publishes_changes_at_most_every_period_unless_forced(elastic_cluster):
    _, client, _ = elastic_cluster
    gauge = QueueGauge(client)
    gauge.publish(7)
    assert client.get_metadata(QUEUED_KEY) == 7
    gauge.publish(6)  # within PERIOD_S of the last: not sent
    assert client.get_metadata(QUEUED_KEY) == 7
    gauge.publish(5, force=True)
    assert client.get_metadata(QUEUED_KEY) == 5
