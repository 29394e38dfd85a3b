"""Fixtures: the tiny workflow as a file and as a parsed study with an empty store on disk,
a real dask scheduler with two workers, and bbb installed from a wheel into a fresh venv."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

import pytest

from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import parse_workflow

from .helpers import FAULT, QUIET, TINY

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def study():
    return parse_workflow(TINY, source="tiny.toml")


@pytest.fixture
def store(tmp_path, study):
    return StudyStore.create_or_open(tmp_path / "s.zarr", study)


@pytest.fixture(scope="session")
def tiny_workflow(tmp_path_factory) -> Path:
    """The tiny workflow as a file (one file for the whole session, so its path is stable)."""
    path = tmp_path_factory.mktemp("wf") / "tiny.toml"
    path.write_text(TINY)
    return path


@pytest.fixture(scope="session")
def reference(tiny_workflow, tmp_path_factory):
    """The tiny workflow run through a real LocalCluster with 2 workers: (store path, report).

    Shared by every test that needs a finished store, so the suite runs it once.
    """
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import load_workflow

    path = tmp_path_factory.mktemp("ref") / "tiny.zarr"
    report = run_study(load_workflow(tiny_workflow), path, workers=2, **QUIET)
    return path, report


@pytest.fixture(scope="session")
def fault_workflow(tmp_path_factory) -> Path:
    """helpers.FAULT as a file: a sweep of seconds, for killing things mid-sweep."""
    path = tmp_path_factory.mktemp("fault") / "fault.toml"
    path.write_text(FAULT)
    return path


@pytest.fixture(scope="session")
def fault_reference(fault_workflow, tmp_path_factory) -> Path:
    """The FAULT workflow run undisturbed on a 2-worker LocalCluster: the store every
    disturbed run must equal bit for bit."""
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import load_workflow

    path = tmp_path_factory.mktemp("fault_ref") / "fault.zarr"
    run_study(load_workflow(fault_workflow), path, workers=2, **QUIET)
    return path


@pytest.fixture
def dask_cluster(tmp_path):
    """A real `dask scheduler` and two `dask worker` processes on 127.0.0.1 (random port).

    Yields the scheduler address; every process started here is stopped by its pid.
    """
    with dask_processes(tmp_path) as (address, _):
        yield address


@pytest.fixture
def dask_cluster_workers(tmp_path):
    """As dask_cluster, but yields (address, [worker Popen, ...]) so a test can kill a worker."""
    with dask_processes(tmp_path) as (address, workers):
        yield address, workers


@contextmanager
def dask_processes(tmp_path, n_workers: int = 2):
    """Start `dask scheduler` + n_workers `dask worker` (1 thread, no nanny) on 127.0.0.1."""
    sched_file = tmp_path / "scheduler.json"
    env = dict(os.environ, NUMBA_NUM_THREADS="1")
    procs = []

    def start(args):
        p = subprocess.Popen([sys.executable, "-m", *args], env=env, cwd=tmp_path,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs.append(p)
        return p

    try:
        start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
               "--no-dashboard", "--scheduler-file", str(sched_file)])
        deadline = time.monotonic() + 60
        while not sched_file.exists() or not sched_file.read_text().strip():
            assert time.monotonic() < deadline, "dask scheduler did not start"
            assert procs[0].poll() is None, "dask scheduler exited"
            time.sleep(0.1)
        time.sleep(0.1)  # let the scheduler finish writing the file
        address = json.loads(sched_file.read_text())["address"]
        workers = [start(["distributed.cli.dask_worker", address, "--nthreads", "1", "--no-nanny",
                          "--no-dashboard", "--host", "127.0.0.1", "--name", f"w{i}"])
                   for i in range(n_workers)]
        from distributed import Client

        with Client(address, timeout="30s") as c:
            c.wait_for_workers(n_workers, timeout=60)
        yield address, workers
    finally:
        # Workers first (they say goodbye to the scheduler), then the scheduler.
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


@pytest.fixture(scope="session")
def installed(tmp_path_factory) -> Path:
    """The python of a fresh venv holding bbb installed from a wheel (`pip install .`, not
    editable); the dependencies come from this test's environment through a .pth file.  One
    wheel per session (4 s in `make test` here, 25 s on a loaded machine), used by
    studies/klages2004/test_make_figures.py, studies/contact/test_scenes.py and
    test_installed_cli.py."""
    base = tmp_path_factory.mktemp("installed")
    # built from a copy without build/ and egg-info: setuptools would reuse a stale build/lib
    src = base / "src"
    shutil.copytree(ROOT, src, ignore=shutil.ignore_patterns(
        ".git", ".venv", "build", "*.egg-info", "runs", "figures", "__pycache__", ".*_cache",
        ".hypothesis", "dask-worker-space"))
    wheels = base / "wheels"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels),
                    str(src)], check=True, capture_output=True, cwd=base)
    venv = base / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    py = venv / "bin" / "python"
    site = Path(subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()"
                                "['purelib'])"], check=True, capture_output=True, text=True
                               ).stdout.strip())
    # the wheel into the new venv's site-packages (pip, run from this environment, targets it)
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target",
                    str(site), str(next(wheels.glob("bbb-*.whl")))], check=True,
                   capture_output=True)
    # the dependencies: this environment's site-packages, after the new venv's own; .pth files
    # there (this checkout's editable install) are not read, so `pipeline` is the wheel's
    deps = [p for p in sys.path if p.endswith("site-packages")]
    (site / "zz_deps.pth").write_text("\n".join(deps) + "\n")
    return py
