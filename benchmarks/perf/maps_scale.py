"""How a parameter map scales: a map of 10^4 points (alpha x f) from workflow to first wave and
back into xarray, and what a map costs per point over the same points run as separate 1-D
scenes.

    python -m benchmarks.perf.maps_scale [--alphas 100 --freqs 100] [--lines 8 --line-freqs 8]

Section 1 (the big map; tiny tasks, so the run measures the engine, not the kernel): parse
the workflow (every point's bbb.Params checked), lay out the store, run it on a LocalCluster
of 2 workers -- ``submit_seconds`` is the task graph built and the first wave submitted
(RunReport) -- and open it with ``open_study`` (unstacked, lazily) and ``xarray.open_zarr``.
Section 2 (per-point overhead): ``--lines`` grid lines of ``--line-freqs`` frequencies as one
map and as one 1-D scene per line (Study.line: the same chunks, bit for bit), all on one
LocalCluster so that no run pays a cluster start-up; compared by the run's compute wall time
(first task submitted to last result) summed over the scenes.  Prints tables; commit the
output under benchmarks/results/ with the date and the CPU."""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import shutil
import tempfile
import time
from pathlib import Path

from benchmarks.common import cpu_name

MAP = """\
[study]
name = "scale"
seed = 11

[params]
preset = "klages2004"

[frequencies]
values = {freqs}

[grid]
alpha = {alphas}

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = {n}
chunk_size = {n}
t_max = {t_max}
sample_dt = {dt}

[observables.positions]
"""


def scene(alphas, freqs, n: int, t_max: float) -> str:
    return MAP.format(alphas=[round(a, 6) for a in alphas], freqs=list(freqs), n=n,
                      t_max=t_max, dt=t_max / 4)


def big_map(n_alpha: int, n_f: int, work: Path, echo) -> list[str]:
    from xarray import open_zarr

    from pipeline.api import open_study
    from pipeline.execute.run import run_study
    from pipeline.store.study_store import StudyStore
    from pipeline.workflow.load import parse_workflow

    alphas = [0.3 + 0.6 * i / max(1, n_alpha - 1) for i in range(n_alpha)]
    freqs = [50.0 + 0.5 * i for i in range(n_f)]
    text = scene(alphas, freqs, 2, 0.2)
    t = time.perf_counter()
    study = parse_workflow(text, source="scale.toml")
    parse_s = time.perf_counter() - t
    path = work / "scale.zarr"
    t = time.perf_counter()
    StudyStore.create_or_open(path, study)
    layout_s = time.perf_counter() - t
    report = run_study(study, path, workers=2, progress=False, dashboard=False, echo=echo)
    t = time.perf_counter()
    ds = open_study(path)
    open_s = time.perf_counter() - t
    t = time.perf_counter()
    open_zarr(str(path), consolidated=None)
    raw_s = time.perf_counter() - t
    n = len(study.points)
    return [
        f"## 1. a map of {n} points ({n_alpha} alpha x {n_f} f), 1 family, 1 chunk of 2 "
        "particles x 0.2 s each",
        "",
        "| step | seconds | target |",
        "| --- | --- | --- |",
        f"| parse + check every point's Params | {parse_s:.2f} | |",
        f"| lay out the store | {layout_s:.2f} | |",
        f"| task graph built and first wave submitted ({len(report.computed)} tasks) | "
        f"{report.submit_seconds:.2f} | < 10 |",
        f"| the whole run (2 workers; {report.task_seconds:.0f} s in tasks) | {report.wall:.1f} | |",
        f"| open_study (unstacked {dict(ds.sizes)['frequency']} f x "
        f"{dict(ds.sizes)['alpha']} alpha, lazy) | {open_s:.2f} | < 2 |",
        f"| xarray.open_zarr of the store | {raw_s:.2f} | |",
        "",
    ]


def overhead(n_lines: int, n_f: int, work: Path, echo) -> list[str]:
    from distributed import Client, LocalCluster

    from pipeline.execute.run import run_study
    from pipeline.workflow.load import parse_workflow

    alphas = [0.5 + 0.4 * i / max(1, n_lines - 1) for i in range(n_lines)]
    freqs = [60.0 + 2.0 * i for i in range(n_f)]
    study = parse_workflow(scene(alphas, freqs, 32, 50.0), source="overhead.toml")
    rows = []
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0", env={"NUMBA_NUM_THREADS": "1"}) as cluster, \
            Client(cluster) as client:
        address = client.scheduler.address
        for rep in range(2):  # the first pair also warms every worker
            t_map = run_study(study, work / f"map{rep}.zarr", scheduler=address, progress=False,
                              dashboard=False, echo=lambda s: None)
            lines = [run_study(study.line({"alpha": a}), work / f"line{rep}-{i}.zarr",
                               scheduler=address, progress=False, dashboard=False,
                               echo=lambda s: None)
                     for i, a in enumerate(study.grid[0][1])]
            rows.append((t_map, lines))
    t_map, lines = rows[-1]
    m_c, l_c = t_map.compute_wall, sum(r.compute_wall for r in lines)
    m_w, l_w = t_map.wall, sum(r.wall for r in lines)
    m_t, l_t = t_map.task_seconds, sum(r.task_seconds for r in lines)
    n = len(study.points)
    return [
        f"## 2. per-point overhead: {n} points ({n_lines} alpha x {n_f} f, 32 particles x 50 s) "
        "as one map and as one scene per line, one LocalCluster of 2 workers (second of two "
        "rounds)",
        "",
        "| | map | lines summed | map / lines |",
        "| --- | --- | --- | --- |",
        f"| compute wall, s | {m_c:.2f} | {l_c:.2f} | {m_c / l_c:.3f} |",
        f"| run wall (store, warm-up, compute), s | {m_w:.2f} | {l_w:.2f} | {m_w / l_w:.3f} |",
        f"| in tasks, s | {m_t:.2f} | {l_t:.2f} | {m_t / l_t:.3f} |",
        f"| collisions | {t_map.collisions} | {sum(r.collisions for r in lines)} | |",
        "",
        f"per-point overhead of the map over the lines: {100 * (m_c / l_c - 1):+.1f} % of the "
        "compute wall (target <= +2 %)",
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--alphas", type=int, default=100)
    ap.add_argument("--freqs", type=int, default=100)
    ap.add_argument("--lines", type=int, default=8)
    ap.add_argument("--line-freqs", type=int, default=8)
    args = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bbb-maps-scale-"))
    try:
        lines = [f"# parameter maps at scale, {datetime.date.today()}, {cpu_name()}, "
                 f"{os.cpu_count()} cores, Python {platform.python_version()}, load average "
                 f"{os.getloadavg()[0]:.2f} at start", ""]
        lines += big_map(args.alphas, args.freqs, work, lambda s: None)
        lines += overhead(args.lines, args.line_freqs, work, lambda s: None)
        lines.append(f"load average at the end {os.getloadavg()[0]:.2f}")
        print("\n".join(lines))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
