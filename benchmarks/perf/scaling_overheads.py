"""The overheads of a distributed run, measured: what pipeline/execute/scale_plan.py's MEASURED
holds (issue 27).  Run it on a quiet machine (it refuses a 1-minute load average above
--max-load, default 1.5):

    python -m benchmarks.perf.scaling_overheads [--tasks 10000] [--map 100]

1. A fresh worker's first task: a LocalCluster of one worker started, a chunk of a tiny scene
   submitted at once, its result back -- with numba's cache as bbb keeps it (beside the
   sources, on the shared filesystem of a cluster) and cold (NUMBA_CACHE_DIR an empty
   temporary directory, so nothing is cleared anywhere); and the kernel load alone
   (warm_numba) in a fresh process, cached and cold.
2. LocalCluster start-up for 1, 2 and 8 workers (the model's worker_start: CPU-s per worker
   process, the processes sharing the cores).
3. The serial timeline of client and scheduler: --tasks no-op tasks submitted one by one (as
   waves.py does) to 2 workers, results handled as they complete: submit s per task, and
   the tasks per second the run sustains (1 / (sched + submit + result)).
4. The first wave of a map of --map x --map points (one tiny chunk each, fixed N, so its only
   wave): tasks per second bbb's own tasks reach on 2 workers (store writes included).
5. The client's wave decision: D's bootstrap CI (interval_of, the dissipation map's paper
   settings: 2000 resamples, 101 samples) from n = 1 ... 32 chunks of 128 particles; a
   least-squares line decide_fixed + decide x n.

Prints a table; commit it as benchmarks/results/scaling-overheads-DATE.txt.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.common import ROOT, cpu_name

TINY = """\
[study]
name = "latency"
seed = 3

[params]
preset = "klages2004"

[frequencies]
values = [60.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 5.0
sample_dt = 0.5

[observables.positions]
"""

WARM = ("import time, sys; t = time.perf_counter(); "
        "from pipeline.workflow.load import parse_workflow; from pipeline.execute.task import "
        "warm_numba; s = parse_workflow(sys.stdin.read()); t1 = time.perf_counter(); "
        "w = warm_numba(s); print(t1 - t, w)")


def load_average() -> float:
    return os.getloadavg()[0]


def warm_in_fresh_process(env: dict) -> tuple[float, float]:
    """(imports, kernel load) seconds in a new interpreter."""
    out = subprocess.run([sys.executable, "-c", WARM], input=TINY, env=env, cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), float(out[1])


def first_task(study, store_path: Path, env: dict) -> tuple[float, float]:
    """(cluster up with its worker, first result) seconds from asking for the cluster."""
    from distributed import Client, LocalCluster

    from pipeline.execute.task import compute_chunk, point_arg, store_argument
    from pipeline.store.study_store import StudyStore

    store = StudyStore.create_or_open(store_path, study)
    # in this process's environment, not LocalCluster(env=...): a spawned worker re-imports
    # this script (and numba, reading NUMBA_CACHE_DIR) before the Nanny applies its env
    saved = {k: os.environ.get(k) for k in env}
    os.environ.update(env)
    try:
        t = time.perf_counter()
        with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                          dashboard_address=":0", env={"NUMBA_NUM_THREADS": "1"}) as cluster, \
                Client(cluster) as c:
            up = time.perf_counter() - t
            seen = c.run(os.environ.get, "NUMBA_CACHE_DIR")
            assert list(seen.values()) == [env.get("NUMBA_CACHE_DIR")], seen
            c.submit(compute_chunk, store_argument(store), 0, 0, 0, False, point_arg(study, 0),
                     pure=False).result()
            return up, time.perf_counter() - t
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def cluster_start(n: int) -> tuple[float, float]:
    """(LocalCluster of n workers up, closed) seconds."""
    from distributed import Client, LocalCluster

    t = time.perf_counter()
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                           dashboard_address=":0", env={"NUMBA_NUM_THREADS": "1"})
    client = Client(cluster)
    client.wait_for_workers(n)
    up = time.perf_counter() - t
    t = time.perf_counter()
    client.close()
    cluster.close()
    return up, time.perf_counter() - t


def noop(i):
    return i


def no_op_tasks(n: int) -> tuple[float, float]:
    """(submit s per task, tasks per second to the last result) on 2 workers."""
    from distributed import Client, LocalCluster, as_completed

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        client.submit(noop, -1, pure=False).result()
        t = time.perf_counter()
        ac = as_completed()
        for i in range(n):
            ac.add(client.submit(noop, i, key=f"noop-{i}", priority=-i, pure=False))
        submit = time.perf_counter() - t
        for fut in ac:
            fut.result()
        return submit / n, n / (time.perf_counter() - t)


def map_first_wave(side: int, work: Path):
    from benchmarks.perf.maps_scale import scene
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import parse_workflow

    alphas = [0.3 + 0.6 * i / max(1, side - 1) for i in range(side)]
    freqs = [50.0 + 0.5 * i for i in range(side)]
    study = parse_workflow(scene(alphas, freqs, 2, 0.2), source="scale.toml")
    return run_study(study, work / "map.zarr", workers=2, progress=False, dashboard=False,
                     echo=lambda s: None)


def decisions(repeats: int = 3) -> list[tuple[int, float]]:
    import numpy as np

    from pipeline.execute.intervals import interval_of, pair_units
    from pipeline.workflow.identity import stop_seed
    from pipeline.workflow.load import load_workflow

    study = load_workflow(ROOT / "pipeline/studies/dissipation/scenes/dissipation.toml")
    fam, point = study.families[0], study.points[len(study.points) // 2]
    rng = np.random.default_rng(0)
    t = study.sample_times()
    out = []
    for n in (1, 2, 4, 8, 16, 32):
        m = n * study.accuracy.chunk_size
        x = np.cumsum(rng.normal(scale=3.0, size=(m, t.size)), axis=1)
        best = np.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            interval_of(study, x, stop_seed(study, point.f, fam, n),
                        pair_units(study, [(fam, m)], point))
            best = min(best, time.perf_counter() - t0)
        out.append((n, best))
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tasks", type=int, default=10_000)
    ap.add_argument("--map", type=int, default=100, help="the map's side: MAP x MAP points")
    ap.add_argument("--max-load", type=float, default=1.5)
    args = ap.parse_args()
    import numpy as np

    from pipeline.execute.task import warm_numba
    from pipeline.workflow.load import parse_workflow

    before = load_average()
    if before > args.max_load:
        print(f"load average {before:.2f} > {args.max_load}: not a quiet machine", file=sys.stderr)
        return 1
    study = parse_workflow(TINY, source="latency.toml")
    warm_numba(study)  # the cache beside the sources is populated
    lines = [f"# scaling overheads, {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC, "
             f"{cpu_name()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
             f"load average {before:.2f} at start",
             f"# command: python -m benchmarks.perf.scaling_overheads --tasks {args.tasks} "
             f"--map {args.map}", ""]
    with tempfile.TemporaryDirectory(prefix="bbb-overheads-") as tmp:
        work = Path(tmp)
        env = {**os.environ, "NUMBA_NUM_THREADS": "1"}
        imp_c, warm_c = warm_in_fresh_process(env)
        imp_x, warm_x = warm_in_fresh_process({**env, "NUMBA_CACHE_DIR": str(work / "cold1")})
        up_c, first_c = first_task(study, work / "a.zarr", {})
        up_x, first_x = first_task(study, work / "b.zarr", {"NUMBA_CACHE_DIR": str(work / "cold2")})
        lines += ["## 1. a fresh worker (s)", "",
                  "| | numba cache (beside the sources) | cold (empty NUMBA_CACHE_DIR) |",
                  "| --- | --- | --- |",
                  f"| fresh process: imports | {imp_c:.2f} | {imp_x:.2f} |",
                  f"| fresh process: kernel load (warm_numba) | {warm_c:.2f} | {warm_x:.2f} |",
                  f"| LocalCluster of 1 worker up | {up_c:.2f} | {up_x:.2f} |",
                  f"| first task's result, from asking for the cluster | {first_c:.2f} | "
                  f"{first_x:.2f} |",
                  f"| first task's latency after the worker is up | {first_c - up_c:.2f} | "
                  f"{first_x - up_x:.2f} |", ""]
        times = {n: cluster_start(n) for n in (1, 2, 8)}
        starts = {n: up for n, (up, _) in times.items()}
        per_worker = (starts[8] - starts[2]) / (8 / 2 - 1)  # CPU-s per process on 2 cores
        lines += ["## 2. LocalCluster start-up (s; processes share the cores)", "",
                  "| workers | 1 | 2 | 8 |", "| --- | --- | --- | --- |",
                  "| up, every worker joined | " + " | ".join(f"{starts[n]:.2f}" for n in (1, 2, 8))
                  + " |",
                  "| closed | " + " | ".join(f"{times[n][1]:.2f}" for n in (1, 2, 8)) + " |", "",
                  f"worker_start = (t8 - t2) / (8/2 - 1) = {per_worker:.2f} CPU-s per worker "
                  f"process; the rest of t2: {starts[2] - per_worker:.2f} s", ""]
        submit, rate = no_op_tasks(args.tasks)
        lines += [f"## 3. {args.tasks} no-op tasks, submitted one by one, on 2 workers", "",
                  f"submit: {1e3 * submit:.3f} ms per task (client)",
                  f"sustained: {rate:.0f} tasks/s = {1e3 / rate:.3f} ms per task on the serial "
                  "timeline of client and scheduler (sched + submit + result)", ""]
        report = map_first_wave(args.map, work)
        n = len(report.computed)
        lines += [f"## 4. the first (only) wave of a {args.map} x {args.map}-point map, "
                  "one chunk of 2 particles x 0.2 s per point, 2 workers", "",
                  f"{n} tasks in {report.compute_wall:.1f} s computing = "
                  f"{n / report.compute_wall:.0f} tasks/s; submitted in "
                  f"{report.submit_seconds:.2f} s ({1e3 * report.submit_seconds / n:.3f} ms per "
                  f"task); in tasks {report.task_seconds:.1f} s simulating, "
                  f"{report.write_seconds:.1f} s writing ({1e3 * report.write_seconds / n:.1f} ms "
                  "per task)", ""]
    d = decisions()
    ns = np.array([n for n, _ in d], dtype=float)
    ts = np.array([s for _, s in d])
    slope, intercept = np.polyfit(ns, ts, 1)
    lines += ["## 5. a wave decision: D's bootstrap CI from n chunks of 128 particles (s, best of 3)",
              "", "| n | " + " | ".join(str(n) for n, _ in d) + " |",
              "| --- |" + " --- |" * len(d),
              "| s | " + " | ".join(f"{s:.4f}" for _, s in d) + " |", "",
              f"fit: decide_fixed = {max(intercept, 0.0):.4f} s, decide = {slope:.5f} s per chunk",
              "", f"# load average at the end {load_average():.2f}"]
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
