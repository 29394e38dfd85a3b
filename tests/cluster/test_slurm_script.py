"""tests/cluster/slurm.sh without a cluster (fast, part of `make test`: starts no daemon):
`down` of a directory where nothing runs is a no-op, `status` and a wrong command fail."""

from __future__ import annotations

import subprocess

from .conftest import SCRIPT


def slurm_sh(tmp_path, *args: str) -> subprocess.CompletedProcess:
    env = {"PATH": "/usr/sbin:/usr/bin:/sbin:/bin", "BBB_SLURM_DIR": str(tmp_path / "slurm")}
    return subprocess.run([str(SCRIPT), *args], env=env, capture_output=True, text=True, timeout=60)


def test_down_with_nothing_running_succeeds_twice(tmp_path):
    for _ in range(2):
        down = slurm_sh(tmp_path, "down")
        assert (down.returncode, down.stderr) == (0, "")


def test_status_without_a_cluster_names_the_directory(tmp_path):
    status = slurm_sh(tmp_path, "status")
    assert status.returncode == 1
    assert f"no slurmctld running for {tmp_path / 'slurm'}" in status.stderr


def test_an_unknown_command_prints_the_usage(tmp_path):
    for args in ((), ("start",)):
        wrong = slurm_sh(tmp_path, *args)
        assert wrong.returncode == 1
        assert "usage:" in wrong.stderr and "up|down|status" in wrong.stderr
