"""The real SLURM test cluster (conftest.py, slurm.sh) does what later tests will rely on: two
idle nodes, batch jobs that run and finish, steps across both nodes, and scancel."""

from __future__ import annotations

import re
import socket
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

import pytest

pytestmark = [pytest.mark.slow, pytest.mark.slurm]

TIMEOUT = 60.0  # seconds any one wait may take (a batch job starts ~3 s after submission)


def run(env: dict[str, str], *cmd: str) -> str:
    """stdout of a SLURM client; its stderr in the failure if it exits non-zero."""
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=TIMEOUT)
    assert proc.returncode == 0, f"{' '.join(cmd)}: exit {proc.returncode}\n{proc.stderr}"
    return proc.stdout


def wait_for(what: str, condition: Callable[[], bool], timeout: float = TIMEOUT) -> float:
    """Poll ``condition`` until true; seconds it took.  Fails naming ``what`` after timeout."""
    start = time.monotonic()
    while not condition():
        if time.monotonic() - start > timeout:
            pytest.fail(f"not after {timeout:.0f} s: {what}")
        time.sleep(0.1)
    return time.monotonic() - start


def queued(env: dict[str, str]) -> dict[str, str]:
    """job id -> state (PENDING, RUNNING, ...) of every job in squeue."""
    lines = run(env, "squeue", "-h", "-o", "%i %T").split()
    return dict(zip(lines[::2], lines[1::2], strict=True))


def job_state(env: dict[str, str], job: str) -> str:
    """JobState of a job slurmctld still knows (for MinJobAge, 300 s, after it ended)."""
    match = re.search(r"\bJobState=(\S+)", run(env, "scontrol", "show", "job", job))
    assert match, f"no JobState for job {job}"
    return match.group(1)


def sbatch(env: dict[str, str], workdir: Path, script: str) -> str:
    """Submit ``script`` (sbatch --wrap) to run in ``workdir``; the job id."""
    out = run(env, "sbatch", "--parsable", f"--chdir={workdir}", f"--output={workdir}/slurm-%j.out",
              "--wrap", script)
    return out.strip().split(";")[0]


def test_sinfo_lists_exactly_n1_and_n2_idle(slurm_env):
    def nodes():
        return sorted(run(slurm_env, "sinfo", "-h", "-N", "-o", "%N %t %P %c").splitlines())

    # idle again within the timeout if an earlier test's job is still completing
    wait_for("both nodes idle", lambda: all(" idle " in line for line in nodes()))
    assert nodes() == ["n1 idle debug* 1", "n2 idle debug* 1"]


def test_sbatch_job_writes_its_file_and_leaves_the_queue(slurm_env, tmp_path):
    out = tmp_path / "out.txt"
    job = sbatch(slurm_env, tmp_path, f'echo "job $SLURM_JOB_ID on $SLURMD_NODENAME" > {out}')
    wait_for(f"job {job} writes {out}", lambda: out.exists() and out.read_text().endswith("\n"))
    assert re.fullmatch(rf"job {job} on n[12]\n", out.read_text())
    wait_for(f"job {job} leaves squeue", lambda: job not in queued(slurm_env))
    assert job_state(slurm_env, job) == "COMPLETED"


def test_srun_runs_one_task_on_each_of_two_nodes(slurm_env):
    out = run(slurm_env, "srun", "-N2", "-l", "sh", "-c", 'echo "$SLURMD_NODENAME $(hostname)"')
    assert sorted(out.splitlines()) == [f"0: n1 {socket.gethostname()}",
                                        f"1: n2 {socket.gethostname()}"]


def test_scancel_ends_a_running_job(slurm_env, tmp_path):
    pid_file = tmp_path / "pid"
    job = sbatch(slurm_env, tmp_path, f"echo $$ > {pid_file}; exec sleep 300")
    wait_for(f"job {job} running", lambda: queued(slurm_env).get(job) == "RUNNING"
             and pid_file.exists() and pid_file.read_text().endswith("\n"))
    pid = int(pid_file.read_text())
    assert Path(f"/proc/{pid}/comm").read_text() == "sleep\n"
    run(slurm_env, "scancel", job)
    took = wait_for(f"job {job} leaves squeue after scancel", lambda: job not in queued(slurm_env))
    assert took < 30, f"job {job} left squeue {took:.0f} s after scancel"
    assert job_state(slurm_env, job) == "CANCELLED"
    wait_for(f"the job's sleep (pid {pid}) ends", lambda: not _is_sleep(pid), timeout=10)


def _is_sleep(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/comm").read_text() == "sleep\n"
    except FileNotFoundError:
        return False

