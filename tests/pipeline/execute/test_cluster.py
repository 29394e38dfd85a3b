"""`bbb run --cluster slurm`: configuration from dask's config files, validated without SLURM,
and a whole run through dask-jobqueue with stand-ins for `sbatch` and `scancel`."""

from __future__ import annotations

import importlib.util
import inspect
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import dask
import pytest
import zarr

from pipeline.execute.cluster import (
    ClusterConfigError,
    check_slurm,
    job_script,
    make_slurm_cluster,
    replace_ended_job,
    slurm_settings,
)

from ..helpers import TINY, assert_same_store

# the slurm extra; without it only the tests that need no dask-jobqueue run
jobqueue = pytest.mark.skipif(importlib.util.find_spec("dask_jobqueue") is None,
                              reason="the slurm extra: pip install -e '.[slurm]'")

BBB = Path(sys.executable).with_name("bbb")
SLURM = {"jobqueue.slurm.cores": 2, "jobqueue.slurm.memory": "2GB"}

# sbatch: runs the job script in the background in a session of its own (its pid is the job
# id), or with --test-only accepts or, if FAKE_SLURM_REJECT is set, rejects it like SLURM.
SBATCH = """\
#!/bin/sh
if [ "$1" = "--test-only" ]; then
    if [ -n "$FAKE_SLURM_REJECT" ]; then
        echo "sbatch: error: invalid partition specified: $FAKE_SLURM_REJECT" >&2; exit 1
    fi
    echo "sbatch: Job 1 to start at now using 2 processors on nodes n1 in partition debug" >&2
    exit 0
fi
cp "$1" "$FAKE_SLURM_DIR/job-$$.sh"   # jobqueue deletes its script once submitted
setsid sh "$FAKE_SLURM_DIR/job-$$.sh" > "$FAKE_SLURM_DIR/job-$$.log" 2>&1 < /dev/null &
echo "$!" >> "$FAKE_SLURM_DIR/jobs"
echo "Submitted batch job $!"
"""
SCANCEL = """\
#!/bin/sh
for job in "$@"; do kill -TERM -- "-$job" 2>/dev/null; done
exit 0
"""


@pytest.fixture
def fake_slurm(tmp_path, monkeypatch):
    """sbatch/scancel stand-ins first on PATH; yields their directory.  Every job still alive
    at the end is killed by its process group id (which is its job id)."""
    bin_dir = tmp_path / "fake-slurm"
    bin_dir.mkdir()
    for name, text in (("sbatch", SBATCH), ("scancel", SCANCEL)):
        (bin_dir / name).write_text(text)
        (bin_dir / name).chmod(0o755)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("FAKE_SLURM_DIR", str(bin_dir))
    yield bin_dir
    jobs = bin_dir / "jobs"
    for job in (jobs.read_text().split() if jobs.exists() else []):
        try:
            os.killpg(int(job), signal.SIGKILL)
        except ProcessLookupError:
            pass


@jobqueue
def test_settings_default_to_one_single_threaded_worker_per_core():
    """processes = cores when the config leaves it unset; numba limited to 1 thread per job."""
    with dask.config.set(SLURM):
        s = slurm_settings()
        script = job_script()
    assert s["processes"] == 2 and "export NUMBA_NUM_THREADS=1" in s["job_script_prologue"]
    assert "--cpus-per-task=2" in script and "--mem=" in script
    assert "--nthreads 1" in script and "--nworkers 2" in script and sys.executable in script


@jobqueue
def test_queue_account_and_walltime_come_from_the_dask_config():
    with dask.config.set({**SLURM, "jobqueue.slurm.queue": "short",
                          "jobqueue.slurm.account": "physics",
                          "jobqueue.slurm.walltime": "1-00:00:00",
                          "jobqueue.slurm.job-script-prologue": ["module load python"]}):
        script = job_script()
    for line in ("#SBATCH -p short", "#SBATCH -A physics", "#SBATCH -t 1-00:00:00",
                 "module load python\nexport NUMBA_NUM_THREADS=1"):
        assert line in script


@jobqueue
@pytest.mark.parametrize("setting, needle", [
    ({"jobqueue.slurm.cores": None}, "jobqueue.slurm.cores: not set; allowed: the cores of one job"),
    ({"jobqueue.slurm.cores": 0}, "jobqueue.slurm.cores: 0; allowed: an integer >= 1"),
    ({"jobqueue.slurm.cores": "many"}, "jobqueue.slurm.cores: 'many'; allowed: an integer >= 1"),
    ({"jobqueue.slurm.memory": None}, "jobqueue.slurm.memory: not set; allowed: the memory"),
    ({"jobqueue.slurm.memory": "lots"}, "jobqueue.slurm.memory: 'lots'; allowed: a size"),
    ({"jobqueue.slurm.processes": 3}, "jobqueue.slurm.processes: 3 does not divide cores = 2"),
    ({"jobqueue.slurm.walltime": "2 hours"}, "jobqueue.slurm.walltime: '2 hours'; allowed: SLURM"),
    ({"jobqueue.slurm.job-script-prologue": "module load x"}, "job-script-prologue: 'module load x'"),
])
def test_a_bad_setting_is_named_with_what_is_allowed_and_where_to_set_it(setting, needle):
    with dask.config.set({**SLURM, **setting}):
        with pytest.raises(ClusterConfigError) as e:
            slurm_settings()
    msg = str(e.value)
    assert needle in msg and "\n" not in msg and "(set it in a YAML file in " in msg


def test_without_dask_jobqueue_the_extra_to_install_is_named(monkeypatch):
    monkeypatch.setitem(sys.modules, "dask_jobqueue", None)  # import fails as if absent
    with pytest.raises(ClusterConfigError, match=r"pip install 'bbb\[slurm\]'"):
        slurm_settings()


@jobqueue
def test_importing_dask_jobqueue_leaves_ctrl_c_alone():
    """dask-jobqueue 0.9.0 sets SIGINT's handler to sys.exit() on import (its issue #696):
    Ctrl-C would end `bbb run` with status 0, no message, jobs left running.  Checked in a
    fresh interpreter, where the import really happens."""
    code = ("import signal; from pipeline.execute.cluster import _jobqueue; _jobqueue(); "
            "print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.stdout.strip() == "True", res.stderr


@jobqueue
def test_without_sbatch_the_check_says_so(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))  # no sbatch anywhere
    with dask.config.set(SLURM), pytest.raises(ClusterConfigError, match="sbatch not found"):
        check_slurm()


@jobqueue
def test_a_job_slurm_rejects_is_refused_before_anything_runs(fake_slurm, monkeypatch):
    monkeypatch.setenv("FAKE_SLURM_REJECT", "nope")
    with dask.config.set(SLURM), pytest.raises(ClusterConfigError) as e:
        check_slurm()
    assert "SLURM rejects the job (sbatch: error: invalid partition specified: nope)" in str(e.value)
    assert not (fake_slurm / "jobs").exists()  # nothing submitted


@pytest.fixture
def unsubmitted_cluster():
    """A SLURMCluster of two worker processes per job (cores 2) with no job submitted: its
    scheduler runs, its ``scale`` only records the calls (nothing reaches sbatch)."""
    with dask.config.set(SLURM):
        cluster = make_slurm_cluster()
        calls = []
        cluster.scale = lambda **kw: calls.append(kw)
        cluster.scale_calls = calls
        try:
            yield cluster
        finally:
            cluster.worker_spec.clear()
            del cluster.scale
            cluster.close()


@jobqueue
def test_the_spec_cluster_internals_replace_ended_job_uses_are_there(unsubmitted_cluster):
    """replace_ended_job relies on SpecCluster's worker_spec (job name -> spec whose "group"
    holds its workers' name suffixes) and new_worker_spec() (one more job under a name not in
    worker_spec), and on scale(jobs=...): a new distributed or dask-jobqueue that changes
    them fails here first (the behaviour: tests/cluster/test_job_keeper.py)."""
    from dask_jobqueue import SLURMCluster

    spec = unsubmitted_cluster.worker_spec
    assert isinstance(spec, dict) and spec == {}
    new = unsubmitted_cluster.new_worker_spec()
    assert isinstance(new, dict) and len(new) == 1
    ((name, job),) = new.items()
    assert isinstance(name, str) and job["group"] == ["-0", "-1"]
    spec.update(new)
    assert set(unsubmitted_cluster.new_worker_spec()) != {name}  # a name not yet in worker_spec
    assert "jobs" in inspect.signature(SLURMCluster.scale).parameters


@jobqueue
def test_a_job_with_a_worker_left_is_not_replaced(unsubmitted_cluster):
    spec = unsubmitted_cluster.worker_spec
    spec.update(unsubmitted_cluster.new_worker_spec())
    (job,) = spec
    assert replace_ended_job(unsubmitted_cluster, f"{job}-0", [f"{job}-1"], jobs=1) is None
    assert list(spec) == [job] and unsubmitted_cluster.scale_calls == []


@jobqueue
def test_a_job_whose_last_worker_left_is_replaced_under_a_new_name(unsubmitted_cluster):
    spec = unsubmitted_cluster.worker_spec
    spec.update(unsubmitted_cluster.new_worker_spec())
    (job,) = spec
    assert replace_ended_job(unsubmitted_cluster, f"{job}-1", ["other-0"], jobs=1) == job
    (new,) = spec
    assert new != job and spec[new]["group"] == ["-0", "-1"]
    assert unsubmitted_cluster.scale_calls == [{"jobs": 1}]
    assert replace_ended_job(unsubmitted_cluster, f"{job}-0", [], jobs=1) is None  # once only


@jobqueue
def test_a_run_on_slurm_jobs_survives_a_job_ending_mid_sweep(fake_slurm, fault_workflow,
                                                             fault_reference, tmp_path):
    """`bbb run --cluster slurm --jobs 1`, configured by a file in $DASK_CONFIG: the job is
    submitted through sbatch and its 2 workers start the sweep; the job is then killed (as at
    its walltime) once >= 1 chunk is done; a new job is submitted, the run completes, every job
    is cancelled at the end, and the store equals the LocalCluster's bit for bit."""
    conf = tmp_path / "dask"
    conf.mkdir()
    (conf / "jobqueue.yaml").write_text(textwrap.dedent("""\
        jobqueue:
          slurm:
            cores: 2
            memory: 2GB
            walltime: "00:10:00"
            scheduler-options:
              host: 127.0.0.1
            worker-extra-args: ["--host", "127.0.0.1"]
        """))
    store = tmp_path / "slurm.zarr"
    run = subprocess.Popen([str(BBB), "run", str(fault_workflow), "--store", str(store),
                            "--cluster", "slurm", "--jobs", "1", "--no-progress"],
                           env=dict(os.environ, DASK_CONFIG=str(conf)), stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 300
        while (done := _done(store)) is None or not done.any():
            assert run.poll() is None and time.monotonic() < deadline, "no chunk done"
            time.sleep(0.02)
        first = (fake_slurm / "jobs").read_text().split()
        os.killpg(int(first[0]), signal.SIGKILL)  # the job ends: its workers vanish mid-task
        assert not done.all(), "the sweep ended before the job did; make FAULT longer"
        out, err = run.communicate(timeout=300)
    finally:
        if run.poll() is None:
            run.kill()
            run.wait()
    assert run.returncode == 0, err
    assert "SLURM: 1 jobs of 2 cores (2 workers each) submitted" in out
    assert "SLURM: job SLURMCluster-0 ended (all its workers left); submitting it anew" in out
    assert "fault: 16/16 chunks done (16 computed" in out
    jobs = (fake_slurm / "jobs").read_text().split()
    assert len(first) == 1 and len(jobs) == 2
    deadline = time.monotonic() + 30
    while not _gone(int(jobs[1])):  # scancel ended the replacement
        assert time.monotonic() < deadline, "the SLURM job outlived the run"
        time.sleep(0.1)
    assert_same_store(fault_reference, store)


def _done(store):
    try:
        return zarr.open_group(str(store), mode="r")["done"][...]
    except Exception:  # not laid out yet
        return None


@jobqueue
def test_a_finished_store_submits_no_job(fake_slurm, reference, tiny_workflow, tmp_path, capsys):
    from pipeline.cli import main

    store = copy_store(reference[0], tmp_path / "done.zarr")
    with dask.config.set(SLURM):
        assert main(["run", str(tiny_workflow), "--store", str(store), "--cluster", "slurm",
                     "--no-progress"]) == 0
    assert "all 8 chunks already done" in capsys.readouterr().out
    assert not (fake_slurm / "jobs").exists()


@jobqueue
def test_a_store_of_another_workflow_is_refused_before_any_job_is_submitted(
        fake_slurm, reference, tmp_path, capsys):
    from pipeline.cli import main

    other = tmp_path / "other.toml"
    other.write_text(TINY.replace("seed = 7", "seed = 8"))
    with dask.config.set(SLURM):
        assert main(["run", str(other), "--store", str(reference[0]), "--cluster", "slurm"]) == 2
    assert "different workflow (seed: store 7, workflow 8)" in capsys.readouterr().err
    assert not (fake_slurm / "jobs").exists()


def _can_hide_directories() -> bool:
    try:
        res = subprocess.run(["unshare", "--mount", "--propagation", "private", "sh", "-c",
                              "mount -t tmpfs none /mnt"], capture_output=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return res.returncode == 0


@pytest.mark.skipif(not _can_hide_directories(), reason="needs unshare and mount (root)")
def test_a_store_path_a_worker_cannot_see_is_refused_before_any_task(tiny_workflow, tmp_path):
    """A `dask worker` whose view of the store's directory is an empty tmpfs (a node without
    the shared filesystem): `bbb run --scheduler` exits 1 naming the worker and the rule, and
    no chunk is done."""
    shared = tmp_path / "shared"
    shared.mkdir()
    sched_file = tmp_path / "scheduler.json"
    env = dict(os.environ, NUMBA_NUM_THREADS="1")
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host",
                               "127.0.0.1", "--port", "0", "--no-dashboard", "--scheduler-file",
                               str(sched_file)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    try:
        deadline = time.monotonic() + 60
        while not (sched_file.exists() and sched_file.read_text().strip()):
            assert time.monotonic() < deadline and procs[0].poll() is None
            time.sleep(0.1)
        time.sleep(0.1)
        address = json.loads(sched_file.read_text())["address"]
        worker = (f"mount -t tmpfs none {shared} && exec {sys.executable} -m "
                  f"distributed.cli.dask_worker {address} --nthreads 1 --no-nanny --no-dashboard "
                  "--host 127.0.0.1 --name blind")
        procs.append(subprocess.Popen(["unshare", "--mount", "--propagation", "private", "sh",
                                       "-c", worker], env=env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL))
        from distributed import Client

        with Client(address, timeout="30s") as c:
            c.wait_for_workers(1, timeout=60)
        store = shared / "s.zarr"
        res = subprocess.run([str(BBB), "run", str(tiny_workflow), "--store", str(store),
                              "--scheduler", address, "--no-progress"], capture_output=True,
                             text=True, timeout=300)
    finally:
        for proc in reversed(procs):
            proc.terminate()
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
    assert res.returncode == 1 and "Traceback" not in res.stderr
    assert f"--store {store}: not visible to 1 of 1 workers" in res.stderr
    assert "must be on a shared filesystem or an fsspec URL" in res.stderr
    assert not _done(store).any()


def copy_store(src, dst) -> Path:
    shutil.copytree(src, dst)
    return Path(dst)


def _gone(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return True
    return False
