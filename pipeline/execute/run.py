"""Run a study: one Dask task per (frequency, family, chunk), each writing its own store chunk.

The cluster is a ``LocalCluster`` (processes, one thread each, ``workers`` of them; default:
the number of cores) or an existing scheduler given by address.  Every chunk's result depends
only on (parameters, frequency, family, chunk) through its SeedSequence, so the store is the
same bit for bit whatever the worker count or task order.  Chunks already marked done are
skipped, so re-running the same workflow on the same store resumes it; first, every done
chunk is read and checked (:meth:`pipeline.store.study_store.StudyStore.damage`), and the
damaged ones (a chunk file deleted, cut or altered, a done-marker unreadable) recomputed:
exactly their bytes.  Client side; a task on a worker is :mod:`pipeline.execute.task`.

Fault injection (for tests): the environment variable ``BBB_FAIL_CHUNKS`` lists chunks, as
``F:FAMILY:CHUNK`` separated by commas (F in Hz), whose task writes its data and then fails
before marking the chunk done.  It is read by the client, not the workers.
"""

from __future__ import annotations

import logging
import os
import sys
import time
import traceback
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field

from ..store.lock import run_lock
from ..store.study_store import StudyStore, is_local, normalize_path
from ..workflow.identity import f_key
from ..workflow.sanity import check_scene
from ..workflow.study import Study
from .cluster import NO_DASHBOARD, has_bokeh
from .elastic import QueueGauge
from .repair import repair_metadata
from .task import (  # the task and what it reports, importable from here as before the split
    FAIL_ENV,
    ChunkKey,
    ChunkResult,
    KernelMismatch,
    compute_chunk,
    is_failing,
    point_arg,
    store_argument,
    task_key,
    warm_numba,
)
from .waves import Waves

__all__ = [
    "RunFailed",
    "RunReport",
    "ChunkResult",
    "compute_chunk",
    "warm_numba",
    "run_study",
    "parse_fail_chunks",
    "FAIL_ENV",
    "KernelMismatch",
]

class RunFailed(RuntimeError):
    """A task failed; the message names the frequency, family, chunk and cause."""


class SchedulerUnreachable(ValueError):
    """--scheduler names no reachable Dask scheduler (a usage error: nothing ran)."""


@dataclass
class RunReport:
    """The outcome of :func:`run_study`; ``summary()`` is the one-line report.

    wall: the whole run, s; compute_wall: from the first task submitted to the last result, s
    (wall minus cluster start-up and numba warm-up); task_seconds: summed simulation times of
    the tasks, s; write_seconds: summed time the tasks spent writing to the store, s;
    submit_seconds: from the start of computing until the first wave's tasks were all
    submitted (the task graph built: every chunk of a fixed-N scene), s.
    """

    name: str
    store: str
    n_chunks: int
    skipped: int
    computed: list[ChunkKey] = field(default_factory=list)
    collisions: int = 0
    task_seconds: float = 0.0
    write_seconds: float = 0.0
    wall: float = 0.0
    compute_wall: float = 0.0
    workers: int = 0
    dashboard: str | None = None
    adaptive: bool = False  # n_chunks is then the store's capacity, not a plan
    submit_seconds: float = 0.0
    repaired: list[ChunkKey] = field(default_factory=list)  # damaged chunks recomputed
    check_seconds: float = 0.0  # reading and checking every done chunk, s

    @property
    def collisions_per_s(self) -> float:
        return self.collisions / self.wall if self.wall > 0 else 0.0

    def summary(self) -> str:
        done = self.skipped + len(self.computed)
        # an adaptive store's chunk axis is a cap: most of it is never meant to be computed
        count = (f"{done} chunks used (of {self.n_chunks} the cap allows)" if self.adaptive
                 else f"{done}/{self.n_chunks} chunks done")
        repaired = f", {len(self.repaired)} of them repaired" if self.repaired else ""
        return (f"{self.name}: {count} ({len(self.computed)} computed{repaired}, "
                f"{self.skipped} already done), {self.collisions:.3g} collisions in "
                f"{self.wall:.1f} s wall ({self.compute_wall:.1f} s computing, "
                f"{self.task_seconds:.1f} s in tasks) on {self.workers} workers = "
                f"{self.collisions_per_s:.3g} collisions/s -> {self.store}")


def parse_fail_chunks(spec: str | None) -> set[tuple[int, str, int]]:
    """``"60:rest:1,54.5:launched:0"`` -> {(60000, "rest", 1), (54500, "launched", 0)}."""
    out = set()
    for item in (spec or "").split(","):
        if not item.strip():
            continue
        try:
            f, fam, ci = item.strip().split(":")
            out.add((f_key(float(f)), fam, int(ci)))
        except ValueError:
            raise ValueError(f"{FAIL_ENV}: bad item {item!r}; allowed: F:FAMILY:CHUNK") from None
    return out


# -------------------------------------------------------------------------------------------
def run_study(
    study: Study,
    store_path: str | os.PathLike,
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool = True,
    fail_chunks: str | None = None,
    dashboard: bool = True,
    echo: Callable[[str], None] = print,
) -> RunReport:
    """Compute every chunk of ``study`` not yet done in the store at ``store_path``.

    scheduler -- address of an existing Dask scheduler (``tcp://host:port``); None starts a
                 LocalCluster with ``workers`` processes (default: the number of cores)
    fail_chunks -- fault injection, as BBB_FAIL_CHUNKS (default: read from the environment)
    dashboard -- serve the Dask dashboard of a LocalCluster and print its link (needs bokeh:
                 pip install 'bbb[dashboard]'; without it the line says so)

    Before anything runs, warns (stderr) about and refuses a scene in which nothing can move
    (:mod:`pipeline.workflow.sanity`).

    Raises RunFailed naming the chunk if a task fails; finished chunks stay done.
    """
    check_scene(study)
    t_start = time.perf_counter()
    store_path = normalize_path(store_path)
    fails = parse_fail_chunks(os.environ.get(FAIL_ENV) if fail_chunks is None else fail_chunks)
    with run_lock(store_path):
        return _run_locked(study, store_path, scheduler, workers, progress, fails, dashboard,
                           echo, t_start)


def _run_locked(study, store_path, scheduler, workers, progress, fails, dashboard, echo,
                t_start) -> RunReport:
    # An existing scheduler is reached first, so that a wrong address leaves no store behind;
    # a LocalCluster starts only once the store is known to need work.
    client, cluster = connect(scheduler, None, dashboard) if scheduler else (None, None)
    waves = None
    t_compute = None
    report = RunReport(study.name, store_path, 0, 0, adaptive=study.adaptive)

    def start(n_tasks: int) -> None:
        """The cluster, the kernel warmed in it, before the first of ``n_tasks`` tasks."""
        nonlocal client, cluster, t_compute
        if t_compute is not None:
            return
        warm = warm_numba(study)  # compile here first: workers then only load the cache
        if client is None:
            client, cluster = connect(None, workers, dashboard)
        report.workers = len(client.scheduler_info(n_workers=-1)["workers"])
        report.dashboard = _dashboard(client, cluster, dashboard)
        link = report.dashboard or ("off" if not dashboard else NO_DASHBOARD)
        echo(f"{study.name}: {n_tasks} chunks on {report.workers} workers; numba warm-up "
             f"{warm:.1f} s; dashboard: {link}")
        if cluster is None:
            _check_workers_see_store(client, store_path)
        _warm_workers(client, study)
        t_compute = time.perf_counter()

    try:
        repair_metadata(study, store_path, echo)  # damaged zarr.json files, chunks kept
        store = StudyStore.create_or_open(store_path, study)
        store.consolidate()  # readable by xarray.open_zarr even if the run is interrupted
        study = store.study  # a grid store's points, in its order
        damaged = _repair(store, report, start, lambda todo: _execute(
            client, store, todo, fails, report, progress), echo)
        done = store.done()
        report.n_chunks, report.skipped = done.size, int(done.sum()) - len(report.repaired)
        if study.adaptive:
            # waves and refinement: the chunks to compute follow from the done ones
            waves = Waves(store, echo)
            todo = waves.prepare()
            store, study = waves.store, waves.store.study
        else:
            todo = [(fi, mi, ci)
                    for fi in range(len(study.points))
                    for mi in range(len(study.families))
                    for ci in range(study.accuracy.n_chunks)
                    if not done[fi, mi, ci]]
        if not todo and not damaged:
            if waves is None:
                echo(f"{study.name}: all {done.size} chunks already done in {store_path} "
                     f"(every one read and checked in {report.check_seconds:.1f} s: intact)")
            else:
                store.consolidate()
                echo(f"{study.name}: nothing left to compute in {store_path} "
                     f"({int(store.done().sum())} chunks used; {waves.summary()})")
            report.wall = time.perf_counter() - t_start
            return report
        if report.skipped and todo:
            echo(f"{study.name}: resuming, {report.skipped} of {done.size} chunks already done")
        if todo:
            start(len(todo))
        try:
            if waves is None and todo:
                _execute(client, store, todo, fails, report, progress)
            elif todo:
                waves.execute(client, fails, report, progress, compute_chunk, _failed)
                store = waves.store
                report.n_chunks = store.done().size  # refinement may have grown the store
                echo(f"{study.name}: {waves.summary()}"
                     + (f"; {waves.rounds} refinement rounds, {len(store.study.refined)} "
                        "frequencies added" if store.study.refine else "")
                     + (f"; {waves.rounds} refinement rounds, {len(store.study.points)} points"
                        if store.study.grid_refine else ""))
        finally:
            report.compute_wall = time.perf_counter() - (t_compute or time.perf_counter())
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    store.consolidate()
    report.wall = time.perf_counter() - t_start
    echo(report.summary())
    return report


def _repair(store: StudyStore, report: RunReport, start, execute, echo) -> bool:
    """Read and check every done chunk; recompute the damaged ones (``start(n)`` readies the
    cluster, ``execute(todo)`` runs the tasks) and say so in one line.  True if any."""
    t0 = time.perf_counter()
    damage = store.damage()
    report.check_seconds = time.perf_counter() - t0
    if not damage:
        return False
    study = store.study
    todo = sorted({(d.fi, d.mi, d.ci) for d in damage})
    start(len(todo))
    execute(todo)
    report.repaired = [(study.points[fi].f, study.families[mi].name, ci) for fi, mi, ci in todo]
    named = [f"{d.array}[{study.points[d.fi].label()}, family {study.families[d.mi].name}, "
             f"chunk {d.ci}]" for d in damage]
    echo(f"{study.name}: repaired {len(todo)} damaged chunks: {'; '.join(named[:6])}"
         + (f" and {len(named) - 6} more" if len(named) > 6 else ""))
    return True


def connect(scheduler: str | None, workers: int | None, dashboard: bool):
    """(client, cluster): a client of the running scheduler at ``scheduler`` (cluster None), or
    of a new LocalCluster of ``workers`` processes (None: one per core)."""
    from distributed import Client, LocalCluster
    from distributed.comm.addressing import parse_address, parse_host_port

    if scheduler:
        try:  # no host:port: refused before a Client (one failed with an AssertionError)
            scheme, loc = parse_address(scheduler)
            _ = parse_host_port(loc) if scheme in ("tcp", "tls") else None
            return Client(scheduler, timeout="20s"), None
        except (OSError, ValueError, TypeError) as e:
            raise SchedulerUnreachable(f"--scheduler {scheduler}: cannot reach a Dask scheduler "
                                       f"({e}); allowed: the address of a running scheduler, "
                                       "e.g. tcp://host:8786") from None
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(
        n_workers=n, threads_per_worker=1, processes=True,
        # ":0": a free port (None would still bind the fixed :8787 for the scheduler's http
        # server, clashing with any other cluster on this machine)
        dashboard_address=":0",
        scheduler_kwargs={"dashboard": dashboard and has_bokeh()},
        # numba would otherwise start one thread per core in every worker for prange loops
        env={"NUMBA_NUM_THREADS": "1"},
        # A failed task is reported once, by the client (RunFailed names the chunk, the cause
        # and where it was raised); the workers' own log tracebacks would bury that line.
        silence_logs=logging.CRITICAL,
    )
    return Client(cluster), cluster


def _dashboard(client, cluster, wanted: bool) -> str | None:
    if cluster is not None and not (wanted and has_bokeh()):
        return None
    try:
        return client.dashboard_link
    except Exception:  # no dashboard on this scheduler
        return None


def _check_workers_see_store(client, store_path: str) -> None:
    """With a remote scheduler the store must be on storage every worker sees."""
    if not is_local(store_path):
        return  # an fsspec URL: the workers open it themselves
    seen = client.run(os.path.exists, os.path.join(store_path, "zarr.json"))
    blind = sorted(w for w, ok in seen.items() if not ok)
    if blind:
        raise RunFailed(f"--store {store_path}: not visible to {len(blind)} of {len(seen)} "
                        f"workers (e.g. {blind[0]}); with --scheduler the store must be on a "
                        "shared filesystem or an fsspec URL (s3://, gs://, ...)")


def _warm_workers(client, study: Study) -> None:
    """Load the kernel in every worker: one worker per host first, then the rest at once.

    The first worker on a host finds the client's cache (or, on another machine, compiles and
    writes it alone); the others only read it, so no two processes write the same cache.
    """
    by_host: dict[str, list[str]] = {}
    for addr, info in client.scheduler_info(n_workers=-1)["workers"].items():
        by_host.setdefault(info.get("host", addr), []).append(addr)
    firsts = [addrs[0] for addrs in by_host.values()]
    rest = [a for addrs in by_host.values() for a in addrs[1:]]
    for addr in firsts:
        client.run(warm_numba, study, workers=[addr])
    if rest:
        client.run(warm_numba, study, workers=rest)


def _execute(client, store: StudyStore, todo, fails, report: RunReport, progress: bool) -> None:
    from distributed import as_completed
    from tqdm import tqdm

    study = store.study
    token = uuid.uuid4().hex[:8]
    futures = {}
    t0 = time.perf_counter()
    handle = store_argument(store)
    for i, (fi, mi, ci) in enumerate(todo):
        fut = client.submit(compute_chunk, handle, fi, mi, ci, is_failing(study, fi, mi, ci, fails),
                            point_arg(study, fi), key=task_key(study, fi, mi, ci, token),
                            priority=len(todo) - i, retries=0, pure=False)
        futures[fut] = (fi, mi, ci)
    report.submit_seconds = time.perf_counter() - t0
    gauge = QueueGauge(client)  # the queue's length, which elastic workers follow
    gauge.publish(len(futures), force=True)
    bar = tqdm(total=len(todo), unit="chunk", disable=not progress, file=sys.stderr,
               desc=study.name, smoothing=0.1)
    try:
        for fut in as_completed(futures):
            fi, mi, ci = futures[fut]
            try:
                res: ChunkResult = fut.result()
            except Exception as e:
                _failed(fut, study, fi, mi, ci, e, lambda: client.cancel(list(futures)))
            report.computed.append(res.key)
            report.collisions += res.collisions
            report.task_seconds += res.seconds
            report.write_seconds += res.write_seconds
            bar.update(1)
            gauge.publish(len(futures) - len(report.computed))
    finally:
        gauge.publish(len(futures) - len(report.computed), force=True)
        bar.close()


def _failed(fut, study: Study, fi: int, mi: int, ci: int, e: Exception, cancel) -> None:
    """Cancel the other tasks (``cancel()``) and raise RunFailed naming the chunk of a failed
    task, its cause and where it was raised (read first: cancelling drops the traceback)."""
    where = _where(fut)
    cancel()
    fam = study.families[mi].name
    raise RunFailed(f"chunk {study.points[fi].label()}, family {fam}, chunk {ci} failed: "
                    f"{type(e).__name__}: {e}{where}") from e


def _where(fut) -> str:
    """' (at file:line in function)' of the innermost frame of a failed task, if known."""
    try:
        frames = traceback.extract_tb(fut.traceback())
    except Exception:  # no traceback available from this scheduler
        return ""
    if not frames:
        return ""
    fr = frames[-1]
    return f" (at {os.path.basename(fr.filename)}:{fr.lineno} in {fr.name})"
