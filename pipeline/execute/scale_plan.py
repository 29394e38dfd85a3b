"""``bbb plan --workers 2,8,64,256``: a workflow's wall time at several worker counts, from the
plan's task costs (pipeline/execute/plan.py) run through the simulation of
pipeline/execute/scaling.py with the overheads measured on this machine (``MEASURED``).

Each (point, family) becomes a :class:`~pipeline.execute.scaling.Unit`: its tasks take the
plan's chunk CPU plus the per-task overhead, in the waves the rule of
pipeline/execute/adaptive.py takes to reach the plan's particles (:func:`wave_ends`: 1, 2, 4,
... chunks, then the rest), or in one wave for a fixed-N scene.  The table gives the wall
time, the speed-up over one worker of the same kind, the efficiency (speed-up / N) and what
bounds it; :func:`chunk_size_sweep` the same at one N for other chunk sizes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..workflow.study import Study
from .adaptive import wave_ends
from .plan import Overheads, Rates, plan_table, predict
from .scaling import Costs, Deployment, Timeline, Unit, simulate

__all__ = ["MEASURED", "units_of", "Row", "scaling_rows", "scaling_table", "chunk_size_sweep",
           "sweep_table", "plan_report"]

#: overheads measured on this machine, s (benchmarks/results/scaling-overheads-2026-11-25.txt,
#: job_wait from slurm-fixture-2026-11-25.txt; tests/pipeline/execute/test_scaling_docs.py
#: checks these against those files); base is an estimate (the store's layout).  warm and cold
#: are a fresh process's: its imports (bbb, numba: 0.33 s) and the kernel's load or compile --
#: a new worker imports bbb with its first warm-up
MEASURED = Costs(base=0.1, worker_start=0.43, warm=0.52, cold=6.94, sched=0.0009925,
                 submit=0.000185, result=0.0009925, decide_fixed=0.0013, decide=0.00111, end=0.15,
                 job_wait=2.14)


def units_of(study: Study, rates: Rates, overheads: Overheads | None = None) -> list[Unit]:
    """The (point, family) units of ``study`` as the plan costs them, point-major."""
    overheads = overheads or Overheads()
    plan = predict(study, rates, 1, overheads)
    acc = study.accuracy
    per_point = len(study.families)
    units = []
    for i, row in enumerate(plan.rows):
        task_s = row.cpu_s / row.chunks + overheads.per_task
        if acc.adaptive:
            ends = wave_ends(1, row.chunks, acc.n_chunks)
            waves = tuple(b - a for a, b in zip([0, *ends[:-1]], ends, strict=True))
        else:
            waves = (row.chunks,)
        units.append(Unit(i // per_point, task_s, waves))
    return units


@dataclass(frozen=True)
class Row:
    workers: int
    timeline: Timeline
    speed_up: float
    efficiency: float


def _deployment(kind: str, n: int, cores: int, per_job: int, cold: bool) -> Deployment:
    return Deployment(kind, n, cores, min(per_job, n), cold)


def scaling_rows(units: list[Unit], workers: list[int], *, kind: str = "local", cores: int = 2,
                 per_job: int = 32, cold: bool = False, costs: Costs = MEASURED) -> list[Row]:
    """The simulated run at each worker count, with speed-up and efficiency over 1 worker."""
    one = simulate(units, _deployment(kind, 1, cores, per_job, cold), costs).wall
    rows = []
    for n in workers:
        tl = simulate(units, _deployment(kind, n, cores, per_job, cold), costs)
        rows.append(Row(n, tl, one / tl.wall, one / tl.wall / n))
    return rows


def _where(kind: str, cores: int, per_job: int, cold: bool) -> str:
    where = (f"a LocalCluster on this machine's {cores} cores" if kind == "local"
             else f"SLURM jobs of {per_job} single-core workers")
    cache = "cold (every host compiles)" if cold else "numba's cache read from the shared disk"
    return f"{where}; kernel: {cache}"


def scaling_table(units: list[Unit], workers: list[int], *, kind: str = "local", cores: int = 2,
                  per_job: int = 32, cold: bool = False, costs: Costs = MEASURED) -> str:
    """The scaling table: one row per worker count."""
    rows = scaling_rows(units, workers, kind=kind, cores=cores, per_job=per_job, cold=cold,
                        costs=costs)
    tasks = sum(sum(u.waves) for u in units)
    waves = max((len(u.waves) for u in units), default=0)
    lines = [f"scaling (pipeline/execute/scaling.py): {len(units)} (point, family) units, "
             f"{tasks} tasks in up to {waves} waves each; {_where(kind, cores, per_job, cold)}",
             f"{'workers':>7} {'wall (s)':>9} {'speed-up':>8} {'effic.':>6}  {'bound':<10} "
             f"{'start-up':>8} {'work/N':>8} {'waves':>8} {'serial':>8}"]
    for r in rows:
        b = r.timeline.bounds
        lines.append(f"{r.workers:>7} {r.timeline.wall:>9.1f} {r.speed_up:>8.2f} "
                     f"{100 * r.efficiency:>5.1f}%  {r.timeline.bound:<10} "
                     + " ".join(f"{b[k]:>8.1f}" for k in ("start-up", "work", "waves", "serial")))
    lines.append("bounds (s): lower bounds of the wall time -- start-up; the work over the cores; "
                 "the longest chain of one unit's waves; the serial time of client and scheduler "
                 "(one process) per task and decision; bound = the largest (tail: the wall exceeds every "
                 "bound by > 15 %)")
    return "\n".join(lines)


def chunk_size_sweep(study: Study, rates: Rates, workers: int, sizes: list[int], *,
                     overheads: Overheads | None = None, **kw
                     ) -> list[tuple[int, Row, int]]:
    """(chunk_size, the row at ``workers``, the most workers -- a power of 2 up to
    ``workers`` -- still at >= 90 % efficiency) for each of ``sizes`` that divides the study's
    n_particles (the store's chunking: each size is a different store and seeds)."""
    out = []
    for size in sizes:
        acc = study.accuracy
        if acc.n_particles % size:
            continue
        sized = replace(study, accuracy=replace(acc, chunk_size=size))
        units = units_of(sized, rates, overheads)
        ns = [2 ** k for k in range(workers.bit_length()) if 2 ** k < workers] + [workers]
        rows = scaling_rows(units, ns, **kw)
        good = max((r.workers for r in rows if r.efficiency >= 0.9), default=1)
        out.append((size, rows[-1], good))
    return out


def sweep_table(sweep: list[tuple[int, Row, int]], workers: int) -> str:
    lines = [f"chunk sizes at {workers} workers:",
             f"{'chunk_size':>10} {'tasks':>7} {'wall (s)':>9} {'effic.':>6}  {'bound':<10} "
             "most workers at >= 90 %"]
    for size, r, good in sweep:
        lines.append(f"{size:>10} {r.timeline.tasks:>7} {r.timeline.wall:>9.1f} "
                     f"{100 * r.efficiency:>5.1f}%  {r.timeline.bound:<10} {good}")
    ok = [size for size, r, _ in sweep if r.efficiency >= 0.9]
    lines.append(f">= 90 % efficiency at {workers} workers: chunk_size "
                 + (", ".join(map(str, ok)) if ok else "none of these"))
    return "\n".join(lines)


def plan_report(study: Study, rates: Rates, workers: list[int], *, kind: str = "local",
                cores: int = 2, per_job: int = 32, cold: bool = False,
                chunk_sizes: tuple[int, ...] = ()) -> str:
    """What `bbb plan` prints: the plan's table at the first worker count
    (pipeline/execute/plan.py), the scaling table at every one, the chunk size sweep at the
    largest if ``chunk_sizes`` are given, and what the plan does not price."""
    where = {"kind": kind, "cores": cores, "per_job": per_job, "cold": cold}
    text = plan_table(predict(study, rates, workers[0])) + "\n\n"
    text += scaling_table(units_of(study, rates), workers, **where)
    if chunk_sizes:
        n = max(workers)
        text += "\n\n" + sweep_table(chunk_size_sweep(study, rates, n, list(chunk_sizes),
                                                         **where), n)
    if study.refine is not None or study.grid_refine is not None:
        which = "[grid.refine]" if study.grid_refine is not None else "[frequencies] refine"
        text += (f"\nnot priced: the points refinement ({which}) adds where D changes -- the "
                 "plan covers the points the workflow lists; a refined run costs more")
    return text
