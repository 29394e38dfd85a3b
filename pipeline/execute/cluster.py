"""Clusters beyond one machine: ``bbb run --cluster slurm --jobs N`` through dask-jobqueue.

The batch system's settings (cores and memory per job, partition, account, walltime, ...) come
from dask's configuration, the ``jobqueue.slurm`` section of a YAML file in ``~/.config/dask/``
(or ``$DASK_CONFIG``, or ``/etc/dask/``); see docs/cluster.md.  bbb adds its own defaults
where that section leaves a value unset:

- ``processes`` = ``cores``: one single-threaded worker process per core, like the
  LocalCluster (the kernel holds the GIL; threads would only queue behind it);
- ``NUMBA_NUM_THREADS=1`` in every job (numba would start one thread per core per process);
- the dashboard on a free port (``:0``), not 8787, which another user of the login node may hold.

``--jobs N`` submits N jobs once the store is known to need work (a store held by another
run, made by another workflow, or already complete submits nothing); the run starts when the
first worker joins, later ones join as their jobs start; a job that ends early (walltime,
node failure) is replaced, its unfinished chunks go to the other workers meanwhile; and every
job is cancelled when the run ends, however it ends.  Every worker loads the numba kernel as
it joins, before its first task, one process per host at a time (numba issue #4807).

``python -m pipeline.execute.cluster`` prints the resolved settings and the job script, submitting
nothing: the way to check a configuration on a login node.

Size: just over 400 lines, one idea (a run's SLURM jobs from submission to cancellation);
the check that a damaged store still has work left added the last lines.
"""

from __future__ import annotations

import fcntl
import functools
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import Any

from distributed.diagnostics.plugin import SchedulerPlugin, WorkerPlugin

__all__ = ["CLUSTERS", "ClusterConfigError", "slurm_settings", "check_slurm", "job_script",
           "make_slurm_cluster", "work_left", "slurm_cluster", "replace_ended_job", "JobKeeper",
           "WarmNumba"]

CLUSTERS = ("slurm",)
SECTION = "jobqueue.slurm"
# SLURM's --time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S
_WALLTIME = re.compile(r"^(\d+-)?\d+(:\d{1,2}){0,2}$")


class ClusterConfigError(ValueError):
    """A cluster that cannot be built as configured: one line naming the setting."""


def config_files() -> str:
    """Where dask looks for configuration files, for error messages."""
    import dask.config

    return ", ".join(dict.fromkeys([*dask.config.paths, dask.config.PATH]))


def _jobqueue():
    first = "dask_jobqueue" not in sys.modules
    before = signal.getsignal(signal.SIGINT)
    try:
        import dask_jobqueue
    except ImportError:
        raise ClusterConfigError("--cluster slurm needs dask-jobqueue; allowed: install it with "
                                 "pip install 'bbb[slurm]' (or pip install dask-jobqueue)") from None
    if first and threading.current_thread() is threading.main_thread():
        # dask-jobqueue 0.9.0 sets SIGINT's handler to sys.exit() when imported (its issue
        # #696, fixed after 0.9.0): Ctrl-C would end `bbb run` with status 0 and no message,
        # and leave its jobs running.  Put the handler back.
        signal.signal(signal.SIGINT, before)
    import dask.config

    if dask.config.get(f"{SECTION}.python", "missing") == "missing":
        # its defaults are registered once, on import; a dask.config.set() block around that
        # first import takes them away again when it ends
        dask_jobqueue.config.reconfigure()
    return dask_jobqueue


def _fail(key: str, problem: str, allowed: str) -> ClusterConfigError:
    return ClusterConfigError(f"dask config {SECTION}.{key}: {problem}; allowed: {allowed} "
                              f"(set it in a YAML file in {config_files()})")


def slurm_settings() -> dict[str, Any]:
    """Validate the ``jobqueue.slurm`` configuration; returns SLURMCluster keyword arguments
    for bbb's own defaults (the rest SLURMCluster reads from the configuration itself)."""
    _jobqueue()  # registers jobqueue's defaults, so every key below exists
    import dask.config
    from dask.utils import parse_bytes

    def get(key):
        return dask.config.get(f"{SECTION}.{key}", None)

    cores = get("cores")
    if cores is None:
        raise _fail("cores", "not set", "the cores of one job, an integer >= 1, e.g. cores: 32")
    if isinstance(cores, bool) or not isinstance(cores, int) or cores < 1:
        raise _fail("cores", f"{cores!r}", "an integer >= 1")
    memory = get("memory")
    if memory is None:
        raise _fail("memory", "not set", "the memory of one job, e.g. memory: 64GB")
    try:
        if parse_bytes(memory) <= 0:
            raise ValueError
    except (ValueError, TypeError):
        raise _fail("memory", f"{memory!r}", "a size such as 64GB or 500MiB") from None
    processes = get("processes")
    if processes is None:
        processes = cores  # one single-threaded worker per core
    if isinstance(processes, bool) or not isinstance(processes, int) or processes < 1:
        raise _fail("processes", f"{processes!r}", "an integer >= 1 (default: cores)")
    if cores % processes:
        raise _fail("processes", f"{processes} does not divide cores = {cores}",
                    "a divisor of cores (each process gets cores / processes threads)")
    walltime = get("walltime")
    if walltime is not None and not _WALLTIME.match(str(walltime)):
        raise _fail("walltime", f"{walltime!r}", "SLURM's --time, e.g. '04:00:00' or '1-00:00:00'")
    prologue = get("job-script-prologue") or []
    if not isinstance(prologue, list) or not all(isinstance(x, str) for x in prologue):
        raise _fail("job-script-prologue", f"{prologue!r}", "a list of shell lines")
    scheduler = get("scheduler-options") or {}
    if not isinstance(scheduler, dict):
        raise _fail("scheduler-options", f"{scheduler!r}", "a mapping, e.g. {host: login1}")
    return {
        "processes": processes,
        "job_script_prologue": [*prologue, "export NUMBA_NUM_THREADS=1"],
        "scheduler_options": {"dashboard_address": ":0", **scheduler},
    }


def make_slurm_cluster(**overrides: Any):
    """A SLURMCluster from the configuration (validated), with no job submitted yet."""
    kwargs = {**slurm_settings(), **overrides}
    try:
        return _jobqueue().SLURMCluster(**kwargs)
    except (ValueError, TypeError) as e:  # jobqueue's own checks of the configuration
        raise ClusterConfigError(f"dask config {SECTION}: {' '.join(str(e).split())} "
                                 f"(configuration files: {config_files()})") from None


def job_script(scheduler: str = "tcp://SCHEDULER:8786") -> str:
    """The job script a SLURM job of this configuration runs (starts and submits nothing)."""
    settings = slurm_settings()
    del settings["scheduler_options"]  # the scheduler's, not the job's
    try:
        job = _jobqueue().slurm.SLURMJob(scheduler=scheduler, name="bbb-worker", **settings)
    except (ValueError, TypeError) as e:
        raise ClusterConfigError(f"dask config {SECTION}: {' '.join(str(e).split())} "
                                 f"(configuration files: {config_files()})") from None
    return job.job_script()


def check_slurm(timeout: float = 120.0) -> None:
    """Validate the configuration, then let SLURM judge the job it gives: ``sbatch --test-only``
    on its job script (nothing is submitted).  Raises ClusterConfigError in one line."""
    script = job_script()
    sbatch = shutil.which("sbatch")
    if sbatch is None:
        raise ClusterConfigError("--cluster slurm: sbatch not found on PATH; allowed: a machine "
                                 "that submits SLURM jobs (python -m pipeline.execute.cluster shows the "
                                 "job script anywhere)")
    with tempfile.NamedTemporaryFile("w", suffix=".sh", prefix="bbb-check-") as fh:
        fh.write(script)
        fh.flush()
        try:
            res = subprocess.run([sbatch, "--test-only", fh.name], capture_output=True, text=True,
                                 timeout=timeout)
        except (OSError, subprocess.TimeoutExpired) as e:
            raise ClusterConfigError(f"--cluster slurm: sbatch --test-only failed ({e})") from None
    if res.returncode != 0:
        said = (res.stderr.strip() or res.stdout.strip() or f"exit status {res.returncode}")
        raise ClusterConfigError(f"--cluster slurm: SLURM rejects the job ({said.splitlines()[0]}); "
                                 f"allowed: a job SLURM accepts, set in dask config {SECTION} "
                                 "(queue, account, walltime, cores, memory, job-extra-directives)")


def work_left(study, store_path) -> bool:
    """Whether ``bbb run`` has chunks to compute in this store, found before any job is
    submitted; refuses, as the run would, a store held by another run or made by another
    workflow (StoreError).  Lays the store out if it is new, as the run would.

    An adaptive store never has every chunk done (a (frequency, family) stops short of the
    cap): it is finished when the wave rule, replayed as the run would (recorded stops are
    read, not recomputed, except a "resolved to ±d_resolved" where nothing moved, which reopens),
    leaves no (frequency, family) open and refinement adds nothing.  A store with damaged
    chunks has work left: their recomputation."""
    from ..store.lock import run_lock
    from ..store.study_store import StudyStore, normalize_path
    from ..workflow.sanity import refuse_nothing_moves
    from .repair import repair_metadata
    from .waves import Waves

    refuse_nothing_moves(study)  # pipeline.workflow.sanity: no job for a scene that cannot move
    path = normalize_path(store_path)
    with run_lock(path):
        repair_metadata(study, path)  # as the run would: damaged zarr.json files rebuilt
        store = StudyStore.create_or_open(path, study)
        if store.damage():  # damaged chunks: the run recomputes them
            return True
        if not store.study.adaptive:
            return not store.done().all()
        return bool(Waves(store, echo=lambda _: None).prepare())


@contextmanager
def slurm_cluster(jobs: int | tuple[int, int], study=None, echo: Callable[[str], None] = print,
                  store: str | None = None) -> Iterator[str]:
    """A Dask cluster of SLURM jobs; yields its scheduler address once the first worker has
    joined (so the run sees a worker to check the store with), and cancels every job on exit,
    whatever happened.

    jobs  -- N: keep N jobs while it runs (a job that ends, e.g. at its walltime, is
             replaced: JobKeeper); (MIN, MAX): elastic, as many single-threaded workers as the
             run has chunks queued, between MIN and MAX jobs (pipeline.execute.elastic),
             a job that ends early replaced too
    study -- if given, every worker loads its numba kernel as it joins (WarmNumba)
    store -- if given, the jobs are recorded beside it while they run, for ``bbb status``
             (pipeline.store.jobs): every job of the run is named ``bbb-`` + 8 hex digits
    """
    import datetime
    import socket
    import uuid

    import dask.config
    from distributed import Client

    from ..store.jobs import clear_jobs, record_jobs
    from .elastic import WaveAdaptive

    processes = slurm_settings()["processes"]  # what make_slurm_cluster passes to SLURMCluster
    job_name = f"bbb-{uuid.uuid4().hex[:8]}"
    cluster = make_slurm_cluster(job_name=job_name)
    elastic = isinstance(jobs, tuple)
    try:
        retiring: set[str] = set()  # workers elastic scaling retires: their jobs stay ended
        cluster.scheduler.add_plugin(JobKeeper(cluster, None if elastic else jobs, echo,
                                               retiring))
        if store is not None:
            record_jobs(store, {
                "cluster": "slurm", "job_name": job_name, "host": socket.gethostname(),
                "pid": os.getpid(), "jobs": f"{jobs[0]}-{jobs[1]} (elastic)" if elastic else jobs,
                "started": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")})
        with Client(cluster) as client:
            if study is not None:
                client.register_plugin(WarmNumba(study), name=WarmNumba.name)
            cores = dask.config.get(f"{SECTION}.cores")
            if elastic:
                cluster.adapt(Adaptive=functools.partial(WaveAdaptive, retiring=retiring),
                              minimum_jobs=jobs[0], maximum_jobs=jobs[1])
                what = (f"elastic: {jobs[0]} to {jobs[1]} jobs of {cores} cores ({processes} "
                        "workers each), one worker per chunk queued")
            else:
                cluster.scale(jobs=jobs)
                what = f"{jobs} jobs of {cores} cores ({processes} workers each) submitted"
            echo(f"SLURM: {what}; job name {job_name}; scheduler {cluster.scheduler_address}, "
                 f"dashboard {_dashboard(cluster)}"
                 + ("; waiting for the first to start (squeue --me)"
                    if not elastic or jobs[0] else ""))
            if not elastic or jobs[0]:
                client.wait_for_workers(1)
        yield cluster.scheduler_address
    finally:
        cluster.close()  # cancels every job still queued or running (scancel)
        if store is not None:
            clear_jobs(store)


def replace_ended_job(cluster, left: str, present: Iterable[str], jobs: int | None) -> str | None:
    """The worker named ``left`` has left the cluster: if it was the last of its job's workers
    (none of them is among the worker names ``present``), forget that job and submit a new one
    in its place (then ``jobs`` jobs in all; None: as many as before, for elastic scaling, whose
    own scale-down removes a job from ``worker_spec`` before its workers leave, so that job is
    not replaced).  Returns the ended job's name, or None if nothing was done.

    The one function of bbb that touches a cluster's internal state.  dask-jobqueue has no API
    to replace a job whose workers all left (its issues #122 and #611; the documented answer,
    worker ``--lifetime`` with ``adapt()``, covers walltimes only, and adapt() too keeps an ended
    job in its plan, its issue #691): the job stays in ``worker_spec``, so neither ``scale()``
    nor ``adapt()`` submits another.  Internals used, all of ``distributed.deploy.SpecCluster``
    (described in its docstring, not in the API documentation):

    - ``worker_spec``: dict job name -> spec, the jobs the cluster keeps submitted; a spec's
      ``"group"`` lists the suffixes of its workers' names (``-0``, ``-1``, ... when a job runs
      several worker processes; none when it runs one, whose worker is named as the job);
    - ``new_worker_spec()``: ``{name: spec}`` of one more job, under a name not in ``worker_spec``
      (taken before the ended job leaves it, so the new job never reuses that name: SpecCluster
      cancels a single-process job whose name no worker holds ``lost-worker-timeout`` after
      such a worker left -- the new job, while still queued, if it had the same name).

    Then the public ``scale(jobs=N)`` brings the running jobs in line with ``worker_spec``: it
    closes the ended job (``scancel``, harmless for an ended job) and submits the new one.
    Checked with distributed 2024.8.0 and 2026.8.0, dask-jobqueue 0.9.0 (pyproject.toml bounds
    distributed to these): tests/pipeline/execute/test_cluster.py checks these attributes,
    tests/cluster/test_job_keeper.py the replacement on a real SLURM cluster.
    """
    spec = cluster.worker_spec

    def workers_of(job) -> set[str]:
        return {f"{job}{suffix}" for suffix in spec[job].get("group", [""])}

    job = next((j for j in spec if left in workers_of(j)), None)
    if job is None or workers_of(job) & set(present):
        return None  # not a job of this cluster (any more), or some of its workers remain
    replacement = cluster.new_worker_spec()
    del spec[job]
    spec.update(replacement)
    cluster.scale(jobs=len(spec) if jobs is None else jobs)
    return job


class JobKeeper(SchedulerPlugin):
    """Scheduler plugin: when every worker of a job has left (walltime, node failure, scancel
    by hand), submit a job anew, so that ``jobs`` jobs stay requested (replace_ended_job).

    Runs in the scheduler, which dask-jobqueue starts in this process, on the cluster's event
    loop; it only tracks worker names (the scheduler's public ``workers``).
    """

    name = "bbb-job-keeper"

    def __init__(self, cluster, jobs: int | None, echo: Callable[[str], None] = print,
                 retiring: set[str] | None = None):
        self.cluster, self.jobs, self.echo = cluster, jobs, echo
        self.retiring = set() if retiring is None else retiring  # left on purpose: not replaced
        self.names: dict[str, str] = {}  # worker address -> worker name

    def add_worker(self, scheduler=None, worker=None, **kwargs) -> None:
        self.names[worker] = str(scheduler.workers[worker].name)

    def remove_worker(self, scheduler=None, worker=None, **kwargs) -> None:
        from distributed.core import Status

        name = self.names.pop(worker, None)
        if name is None or self.cluster.status in (Status.closing, Status.closed):
            return
        if name in self.retiring:  # elastic scaling retired it
            self.retiring.discard(name)
            return
        job = replace_ended_job(self.cluster, name, self.names.values(), self.jobs)
        if job is not None:
            self.echo(f"SLURM: job {job} ended (all its workers left); submitting it anew")


#: what a run prints for the dashboard's link without bokeh (not in the default install)
NO_DASHBOARD = "unavailable without bokeh: pip install 'bbb[dashboard]'"


def has_bokeh() -> bool:
    """Whether bokeh, which serves the Dask dashboard, is installed (not imported here)."""
    import importlib.util

    return importlib.util.find_spec("bokeh") is not None


def _dashboard(cluster) -> str:
    if not has_bokeh():
        return NO_DASHBOARD
    try:
        return cluster.dashboard_link
    except Exception:
        return "unavailable"


class WarmNumba(WorkerPlugin):
    """Worker plugin: load (or compile) the kernel when a worker starts, before any task.

    The processes of one host take turns (an exclusive lock on a file in the host's temporary
    directory): the first compiles and writes numba's cache if it must, the others only read
    it, so no two processes on a host write the same cache entry at once (numba issue #4807).
    """

    name = "bbb-warm-numba"

    def __init__(self, study):
        self.study = study

    def setup(self, worker=None) -> None:
        from .task import warm_numba

        path = os.path.join(tempfile.gettempdir(), f"bbb-numba-warm-{os.getuid()}.lock")
        with open(path, "a") as fh:
            fcntl.flock(fh, fcntl.LOCK_EX)
            try:
                warm_numba(self.study)
            finally:
                fcntl.flock(fh, fcntl.LOCK_UN)


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.execute.cluster [slurm]``: the resolved settings and the job script."""
    argv = sys.argv[1:] if argv is None else argv
    if argv not in ([], ["slurm"]):
        print(f"usage: python -m pipeline.execute.cluster [{'|'.join(CLUSTERS)}]", file=sys.stderr)
        return 2
    try:
        settings = slurm_settings()
        script = job_script()
    except ClusterConfigError as e:
        print(f"bbb: error: {e}", file=sys.stderr)
        return 2
    print(f"# bbb additions to {SECTION}: {settings}")
    print(f"# configuration files: {config_files()}")
    print("# (the scheduler address is filled in by `bbb run --cluster slurm`)")
    print(script)
    return 0


if __name__ == "__main__":
    sys.exit(main())
