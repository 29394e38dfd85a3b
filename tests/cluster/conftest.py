"""A real SLURM cluster on this machine for the tests of this folder: `slurm.sh up` once per
session (munged, slurmctld, two slurmd: nodes n1 and n2 of one CPU each, partition `debug`),
`slurm.sh down` at its end.  Tests that use it are marked ``slow`` and ``slurm``: `make test`
never starts SLURM, `make test-slow` or ``pytest -m slurm tests/cluster`` does.

The cluster runs in a directory and on ports of its own (`RUN_DIR`, `PORT`), so a test cluster
started by hand with `slurm.sh up` (default bbb-slurm in the temporary directory, port 16817)
is left alone.  It needs
root (slurmd, and apt-get if slurm-wlm is missing): as another user the tests are skipped, or
fail if BBB_REQUIRE_SLURM is set (as .ci/run sets it)."""

from __future__ import annotations

import os
import shlex
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

SCRIPT = Path(__file__).with_name("slurm.sh")
RUN_DIR = str(Path(tempfile.gettempdir()) / "bbb-slurm-pytest")
PORT = 16827  # slurmctld; the nodes listen on the next two
#: set (e.g. by .ci/run) to fail, not skip, where the cluster cannot be started (not root)
REQUIRE = "BBB_REQUIRE_SLURM"


def read_env_file(path: Path) -> dict[str, str]:
    """The variables of the `export NAME=value` lines `slurm.sh up` writes for clients."""
    env = {}
    for line in path.read_text().splitlines():
        words = shlex.split(line)
        if len(words) == 2 and words[0] == "export" and "=" in words[1]:
            name, value = words[1].split("=", 1)
            env[name] = value
    return env


@pytest.fixture(scope="session")
def slurm_env() -> Iterator[dict[str, str]]:
    """The environment for SLURM's clients (`sinfo`, `sbatch`, ...) to reach the test cluster:
    this process's environment plus SLURM_CONF; pass it as ``env=`` to subprocess."""
    if os.geteuid() != 0:
        if os.environ.get(REQUIRE):  # CI (.ci/run): these tests must run, not be skipped
            pytest.fail(f"{REQUIRE} is set but the real SLURM cluster needs root "
                        "(tests/cluster/slurm.sh)", pytrace=False)
        pytest.skip("a real SLURM cluster needs root (tests/cluster/slurm.sh)")
    script_env = {**os.environ, "BBB_SLURM_DIR": RUN_DIR, "BBB_SLURM_PORT": str(PORT)}
    up = subprocess.run([str(SCRIPT), "up"], env=script_env, capture_output=True, text=True,
                        timeout=900)  # apt-get may install the packages first
    if up.returncode != 0:
        pytest.fail(f"slurm.sh up failed (exit {up.returncode}):\n{up.stderr}", pytrace=False)
    try:
        yield {**os.environ, **read_env_file(Path(RUN_DIR) / "env")}
    finally:
        down = subprocess.run([str(SCRIPT), "down"], env=script_env, capture_output=True,
                              text=True, timeout=120)
        if down.returncode != 0:
            pytest.fail(f"slurm.sh down failed (exit {down.returncode}):\n{down.stderr}",
                        pytrace=False)
