"""The scaling model of `bbb plan --workers` (pipeline/execute/scaling.py) against measured runs,
and its predictions for the D(f, alpha) map (issue 27).  On a quiet machine only (refuses a
1-minute load average above --max-load, default 1.5):

    python -m benchmarks.studies.scaling_check local [--workers 1,2,8]   # LocalCluster runs
    python -m benchmarks.studies.scaling_check slurm [--jobs 1,2]        # real SLURM (root; slurm.sh)
    python -m benchmarks.studies.scaling_check predict                   # the dissipation map

``local`` and ``slurm`` run the same small adaptive map (MAP: 24 points, waves of 32-particle
chunks, ~45 CPU-s) from an empty store at each worker count and compare the measured wall
time of the whole run with two predictions:

* plan: what `bbb plan --workers` says -- task costs from the pilot (pipeline/execute/pilot.py),
  the overheads of pipeline/execute/scale_plan.py's MEASURED;
* replay: the same simulation fed the run's own tasks -- each (point, family)'s waves replayed
  from the store with the stopping rule, its mean chunk_seconds plus the run's write time per
  task -- so that it checks the simulation of the schedule alone, not the pilot's costs.  Task
  times are taken from the 2-worker run for more workers (workers that share cores measure
  stretched times; the simulation does the sharing).

``predict`` prints `bbb plan`'s scaling table of the dissipation map at 2, 8, 64, 256 workers
(SLURM jobs of 32 workers, numba's cache on the shared filesystem, and cold) and its chunk
size sweep at 256, from the pilot cache in runs/plan-cache (or a new pilot, ~1-2 min).
Commit each output as benchmarks/results/scaling-{validation,slurm,dissipation}-DATE.txt.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.common import ROOT, cpu_name

MAP = """\
[study]
name = "scalemap"
seed = 27

[params]
preset = "klages2004"

[frequencies]
values = [54.0, 56.0, 60.0, 66.0, 74.0, 86.0]

[grid]
alpha = [0.5, 0.6, 0.7, 0.9]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
chunk_size = 32
t_max = 100.0
sample_dt = 0.5
target_ci = 0.1
d_resolved = 9.0
max_particles = 512

[observables.positions]
"""

DASK_CONFIG = """\
jobqueue:
  slurm:
    cores: 1
    memory: 250MB
    queue: debug
    walltime: "00:20:00"
    log-directory: {logs}
    local-directory: {scratch}
    scheduler-options: {{host: 127.0.0.1}}
    worker-extra-args: ["--host", "127.0.0.1"]
distributed:
  worker:
    memory: {{target: false, spill: false, pause: false, terminate: false}}
"""


def header(what: str, command: str) -> list[str]:
    return [f"# {what}, {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC, {cpu_name()}, "
            f"{os.cpu_count()} cores, Python {platform.python_version()}, load average "
            f"{os.getloadavg()[0]:.2f} at start", f"# command: python -m benchmarks.studies.scaling_check "
            f"{command}"]


def replay_units(store_path: Path, write_per_task: float):
    """The units of a finished adaptive store: each (point, family)'s waves replayed with the
    stopping rule from its chunks, its task time the mean chunk_seconds + the write time."""
    import numpy as np
    import zarr

    from pipeline.execute.adaptive import advance
    from pipeline.execute.intervals import unit_ci
    from pipeline.execute.scaling import Unit
    from pipeline.execute.waves import rule_of
    from pipeline.store.study_store import StudyStore

    store = StudyStore.open(str(store_path))
    study = store.study
    secs = np.asarray(zarr.open_group(str(store_path), mode="r")["chunk_seconds"][...])
    done = store.done()
    units = []
    for fi in range(len(study.points)):
        for mi in range(len(study.families)):
            n = int(done[fi, mi].sum())
            state = advance(rule_of(study), None, n,
                            lambda k, fi=fi, mi=mi: unit_ci(store, fi, mi, k))
            assert state.n == n, (fi, mi, state, n)
            ends = state.waves
            waves = tuple(b - a for a, b in zip([0, *ends[:-1]], ends, strict=True))
            units.append(Unit(fi, float(secs[fi, mi, :n].mean()) + write_per_task, waves))
    return units


def plan_units(study, cache: Path):
    from pipeline.execute.pilot import pilot_rates
    from pipeline.execute.scale_plan import units_of

    return units_of(study, pilot_rates(study, cache_dir=cache, echo=None))


def predicted(units, kind: str, n: int, cold: bool = False) -> float:
    from pipeline.execute.scale_plan import MEASURED
    from pipeline.execute.scaling import Deployment, simulate

    # local: this machine's cores; slurm: the test cluster's single-CPU jobs, one worker each
    dep = Deployment(kind, n, (os.cpu_count() or 1) if kind == "local" else 1, per_host=1,
                     cold=cold)
    return simulate(units, dep, MEASURED).wall


def table(rows, kind: str) -> list[str]:
    out = ["| workers | measured wall (s) | plan (s) | plan / measured | replay (s) | "
           "replay / measured | measured start-up + end (s) | tasks | CPU-s in tasks |",
           "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for n, wall, startup, tasks, cpu, plan_s, replay_s in rows:
        out.append(f"| {n} | {wall:.1f} | {plan_s:.1f} | {plan_s / wall:.2f} | {replay_s:.1f} | "
                   f"{replay_s / wall:.2f} | {startup:.1f} | {tasks} | {cpu:.1f} |")
    return out


def local(args) -> list[str]:
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import parse_workflow

    lines = header("the scaling model against LocalCluster runs", f"local --workers "
                   f"{args.workers}")
    study = parse_workflow(MAP, source="scalemap.toml")
    ns = [int(x) for x in args.workers.split(",")]
    with tempfile.TemporaryDirectory(prefix="bbb-scaling-") as tmp:
        work = Path(tmp)
        units = plan_units(study, work / "cache")
        reports, stores = {}, {}
        for n in ns:
            stores[n] = work / f"w{n}.zarr"
            t = time.perf_counter()
            reports[n] = run_study(study, stores[n], workers=n, progress=False, dashboard=False,
                                   echo=lambda s: None)
            reports[n].wall = time.perf_counter() - t
        rows = []
        for n in ns:
            r = reports[n]
            src = n if n <= 2 else min(ns, key=lambda m: abs(m - 2))
            rs = reports[src]
            replay = replay_units(stores[src], rs.write_seconds / len(rs.computed))
            rows.append((n, r.wall, r.wall - r.compute_wall, len(r.computed), r.task_seconds,
                         predicted(units, "local", n), predicted(replay, "local", n)))
    lines += ["", f"map: {len(study.points)} points, adaptive (waves of "
              f"{study.accuracy.chunk_size}-particle chunks); a fresh store per run; "
              "replay task times from the run itself (1, 2 workers) or the 2-worker run (more)",
              ""] + table(rows, "local")
    lines.append(f"\n# load average at the end {os.getloadavg()[0]:.2f}")
    return lines


def slurm(args) -> list[str]:
    from pipeline.workflow.load import parse_workflow

    script = ROOT / "tests" / "cluster" / "slurm.sh"
    lines = header("the scaling model against runs on the real SLURM test cluster",
                   f"slurm --jobs {args.jobs}")
    study = parse_workflow(MAP, source="scalemap.toml")
    run_dir = Path(tempfile.gettempdir()) / "bbb-slurm-scaling"
    env = {**os.environ, "BBB_SLURM_DIR": str(run_dir), "BBB_SLURM_PORT": "16847"}
    subprocess.run([str(script), "up"], env=env, check=True, capture_output=True, text=True)
    rows = []
    try:
        for k, v in re.findall(r"export (\w+)=(\S+)", (run_dir / "env").read_text()):
            env[k] = v.strip("'\"")
        with tempfile.TemporaryDirectory(prefix="bbb-scaling-") as tmp:
            work = Path(tmp)
            (work / "dask").mkdir()
            (work / "dask" / "jobqueue.yaml").write_text(
                DASK_CONFIG.format(logs=work / "logs", scratch=work / "scratch"))
            (work / "map.toml").write_text(MAP)
            env["DASK_CONFIG"] = str(work / "dask")
            units = plan_units(study, work / "cache")
            for n in (int(x) for x in args.jobs.split(",")):
                store = work / f"j{n}.zarr"
                t = time.perf_counter()
                out = subprocess.run([str(Path(sys.executable).with_name("bbb")), "run",
                                      str(work / "map.toml"), "--store", str(store), "--cluster",
                                      "slurm", "--jobs", str(n), "--no-progress"], env=env,
                                     capture_output=True, text=True, check=True).stdout
                wall = time.perf_counter() - t
                m = re.search(r"in ([\d.]+) s wall \(([\d.]+) s computing, ([\d.]+) s in tasks\)",
                              out)
                tasks = int(re.search(r"\((\d+) computed", out).group(1))
                # write time per task is not printed by bbb run: the local runs' (~0.01 s)
                replay = replay_units(store, 0.01)
                rows.append((n, wall, wall - float(m.group(2)), tasks, float(m.group(3)),
                             predicted(units, "slurm", n), predicted(replay, "slurm", n)))
    finally:
        subprocess.run([str(script), "down"], env=env, check=False, capture_output=True)
    lines += ["", f"map: {len(study.points)} points, adaptive; `bbb run --cluster slurm --jobs "
              "N` as a subprocess (its wall includes the interpreter's start and SLURM's), one "
              "single-CPU job per node (n1, n2 share this machine's cores)", ""]
    lines += table(rows, "slurm")
    lines.append(f"\n# load average at the end {os.getloadavg()[0]:.2f}")
    return lines


def predict(args) -> list[str]:
    from pipeline.execute.pilot import pilot_rates
    from pipeline.execute.scale_plan import (
        chunk_size_sweep,
        scaling_table,
        sweep_table,
        units_of,
    )
    from pipeline.workflow.load import load_workflow

    scene = "pipeline/studies/dissipation/scenes/dissipation.toml"
    study = load_workflow(ROOT / scene)
    rates = pilot_rates(study, cache_dir=ROOT / "runs" / "plan-cache", echo=None)
    units = units_of(study, rates)
    lines = header(f"bbb plan's scaling table of {scene}", "predict")
    lines += ["", f"cost model: {rates.source}", ""]
    for cold in (False, True):
        lines += [scaling_table(units, [1, 2, 8, 64, 256], kind="slurm", per_job=32, cold=cold),
                  ""]
    lines.append(sweep_table(chunk_size_sweep(study, rates, 256, [16, 32, 64, 128, 256, 512],
                                              kind="slurm", per_job=32), 256))
    return lines


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("local", "slurm", "predict"))
    ap.add_argument("--workers", default="1,2,8")
    ap.add_argument("--jobs", default="1,2")
    ap.add_argument("--max-load", type=float, default=1.5)
    args = ap.parse_args()
    if args.what != "predict" and os.getloadavg()[0] > args.max_load:
        print(f"load average {os.getloadavg()[0]:.2f} > {args.max_load}: not a quiet machine",
              file=sys.stderr)
        return 1
    print("\n".join({"local": local, "slurm": slurm, "predict": predict}[args.what](args)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
