"""The one-machine SLURM test cluster (tests/cluster/slurm.sh): how long `up` takes from nothing
(packages installed, no run directory), how long `down` takes, and the latency of a trivial
batch job from `sbatch` to its output file: the first job after `up` and the ones submitted
right after the previous one's output appeared (slurmctld schedules batch jobs at most every
batch_sched_delay = 3 s, SLURM's default, which the cluster keeps).

    python3 -m benchmarks.perf.slurm_fixture [--repeats 5] [--jobs 5]

Needs root and slurm-wlm + munge (`slurm.sh up` installs them).  Runs its own cluster in
bbb-slurm-bench in the temporary directory on ports 16837-16839; leaves nothing running.
Standard library only.
Commit the output under benchmarks/results/."""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import shutil
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from benchmarks.common import ROOT

SCRIPT = ROOT / "tests" / "cluster" / "slurm.sh"
RUN_DIR = Path(tempfile.gettempdir()) / "bbb-slurm-bench"
ENV = {**os.environ, "BBB_SLURM_DIR": str(RUN_DIR), "BBB_SLURM_PORT": "16837"}


def timed(*cmd: str, env: dict[str, str] = ENV) -> float:
    start = time.perf_counter()
    subprocess.run(cmd, env=env, check=True, capture_output=True, text=True)
    return time.perf_counter() - start


def job_latency(env: dict[str, str], out: Path) -> float:
    """Seconds from just before `sbatch` to the job's output file holding its line."""
    out.unlink(missing_ok=True)
    start = time.perf_counter()
    subprocess.run(["sbatch", "--output=/dev/null", "--wrap", f"echo done > {out}"], env=env,
                   check=True, capture_output=True)
    while not (out.exists() and out.read_text() == "done\n"):
        if time.perf_counter() - start > 60:
            raise RuntimeError(f"no {out} 60 s after sbatch")
        time.sleep(0.01)
    return time.perf_counter() - start


def line(name: str, values: list[float]) -> str:
    return (f"{name:<34} {statistics.median(values):7.2f} {min(values):7.2f} {max(values):7.2f}"
            f"   n={len(values)}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="up/down cycles")
    ap.add_argument("--jobs", type=int, default=5, help="trivial batch jobs per cycle, one at a time")
    args = ap.parse_args()

    cpu = next((ln.split(":", 1)[1].strip() for ln in subprocess.run(
        ["lscpu"], capture_output=True, text=True).stdout.splitlines() if ln.startswith("Model name")), "?")
    version = subprocess.run(["slurmctld", "-V"], capture_output=True, text=True).stdout.strip()
    print(f"# SLURM test cluster (tests/cluster/slurm.sh)  {datetime.datetime.now():%Y-%m-%dT%H:%M:%S}")
    print(f"# CPU: {cpu}  ({os.cpu_count()} cores)  {version}  {platform.system()} {platform.release()}")
    print(f"# run dir {RUN_DIR}; {args.repeats} cycles of: remove the run dir, up, {args.jobs} trivial "
          "jobs one after another (sbatch --wrap 'echo done > FILE'), down")
    ups, downs, first, later = [], [], [], []
    env = {**ENV, "SLURM_CONF": str(RUN_DIR / "slurm.conf")}
    out = Path(tempfile.gettempdir()) / "bbb-slurm-bench-out.txt"
    try:
        for _ in range(args.repeats):
            timed(str(SCRIPT), "down")
            shutil.rmtree(RUN_DIR, ignore_errors=True)
            ups.append(timed(str(SCRIPT), "up"))
            first.append(job_latency(env, out))
            later += [job_latency(env, out) for _ in range(args.jobs - 1)]
            downs.append(timed(str(SCRIPT), "down"))
    finally:
        timed(str(SCRIPT), "down")
        out.unlink(missing_ok=True)
    print(f"{'seconds':<34} {'median':>7} {'min':>7} {'max':>7}")
    print(line("up from nothing", ups))
    print(line("down (idle cluster)", downs))
    print(line("sbatch -> output file, 1st job", first))
    if later:
        print(line("sbatch -> output file, next jobs", later))


if __name__ == "__main__":
    main()
