"""What a workflow will cost before it runs (``bbb plan``): CPU and wall time on this machine.

The cost model, and where each number comes from:

* Collisions per particle-second c(f, family) and the kernel rate r (collisions per
  CPU-second of one core): a :class:`Rates` table, measured by a pilot (pipeline/execute/pilot.py)
  or with r from a ``benchmarks/perf/kernel.py`` table.  The prediction is for the cores being
  ours: on a shared machine the wall time grows by the load
  (:func:`pipeline.execute.machine_load.loaded_wall`: from the
  share of a core the pilot got).
* Task CPU = chunk_size x t_max x c / r; a task's wall adds the per-task overhead
  PER_TASK_S (store write + dispatch, measured) and the run adds START_UP_S (LocalCluster,
  numba cache load, store creation).  Wall = START_UP_S + the makespan of the tasks placed
  in submission order on the first free worker (what Dask does with run.py's priorities):
  that accounts for the tail, the longest single task at the end.
* A target-driven scene (``[accuracy] target_ci``, ``d_resolved``, ``max_particles``):
  the particles per (frequency, family) from the law "95 % CI half-width of D = k D /
  sqrt(N)" (docs/accuracy.md, fact 1) with k from the scene's own pilot
  (:meth:`Rates.ci_law`: the particles' relative spread of D pooled over a line's cells; 1.6,
  measured on the paper's arcs at f >= 58 Hz, without a pool): N = (k D / goal)^2 with the
  stopping rule's goal max(target_ci D, d_resolved), where the pilot's own bootstrap
  half-width stands in for k D when it saw one mover or none (D = 0 from rest in the
  creeping regime is resolved by the first wave), and the pilot's own relative spread for k
  when it is more than twice k (mixed creeping/bouncing frequencies); rounded up to whole
  chunks (the wave rule of pipeline/execute/adaptive.py ends there when the law holds) and
  capped at ``max_particles``.  The wall time ignores the waits between waves.

This module is the pure part: ``predict`` and ``plan_table`` take a workflow and a
:class:`Rates` table; ``pipeline.execute.pilot.pilot_rates`` measures one.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, replace
from statistics import NormalDist

from ..workflow.identity import f_key
from ..workflow.study import Study

__all__ = ["Cell", "Rates", "Overheads", "TaskRow", "Plan", "predict", "plan_table",
           "particles_needed", "makespan", "CI_LAW", "POOL_MIN", "BAND_EDGES"]

#: relative 95 % CI half-width of D times sqrt(N), measured at f >= 58 Hz (docs/accuracy.md):
#: the plan's constant when the pilot has no spread to pool (Rates.ci_law)
CI_LAW = 1.6
#: fewest pilot cells the CI-law constant is pooled from
POOL_MIN = 5
#: frequency bands of the table, Hz (the creeping band, the VHO and destroyed resonances,
#: the two-loop and the three/four-loop spirals of Fig. 2)
BAND_EDGES = (50.0, 58.0, 66.0, 80.0, 100.0)


@dataclass(frozen=True)
class Overheads:
    """Measured on this machine (benchmarks/results/pipeline-2026-11-22.txt), s.

    start_up -- LocalCluster start, numba cache load, store creation: the standard Fig. 2
                run took 474 s wall for 470 s of computing
    per_task -- store write + dispatch of one chunk: 5.9 s of writes over 248 chunks of 512
                particles (standard), 2.25 s over 124 chunks of 64 (draft)
    in_task  -- the kernel rate inside pipeline tasks (two workers at once, Dask and the store
                in the same process) over a lone process's CPU-time rate, measured in one
                session of benchmarks/perf/pipeline.py: Fig. 2 at standard ran 1.55e6 collisions
                per task-second (1.44e9 in 934 s) where section 1 measured 1.885e6 per
                CPU-second at Fig. 2's mix of frequencies (55, 60, 80 Hz weighted 76/7/17 %)
    """

    start_up: float = 4.0
    per_task: float = 0.024
    in_task: float = 0.82


@dataclass(frozen=True)
class Cell:
    """The pilot at one (frequency, family): ``n`` particles over ``t_max`` s.

    collisions -- summed over the n particles;  cpu_s -- process CPU time of the simulation
    D, D_hw    -- D (mm^2/s) and its absolute 95 % bootstrap half-width at n particles
                  (NaN without positions)
    cv2        -- the particles' relative spread of D: var(D_i) / mean(D_i)^2 over the n
                  particles' own MSD slopes D_i (unbiased variance; NaN without positions or
                  when mean(D_i) <= 0), pooled over a line into the CI-law constant
    """

    f: float
    family: str
    n: int
    t_max: float
    collisions: int
    cpu_s: float
    D: float = math.nan
    D_hw: float = math.nan
    cv2: float = math.nan

    @property
    def per_particle_s(self) -> float:
        """Collisions per particle-second."""
        return self.collisions / (self.n * self.t_max)


@dataclass(frozen=True)
class Rates:
    """The cost table: a pilot cell per (frequency in mHz, family name), and the kernel rate
    (collisions per CPU-second of one core) -- the pilot's own unless ``rate`` is given."""

    cells: dict[tuple, Cell]
    rate: float | None = None
    source: str = ""
    #: a grid's probed lines: cells keyed (f in mHz, family, grid values); the numeric axes'
    #: (lo, hi), by which the nearest probed line of a point is found
    scales: tuple[tuple[str, float, float], ...] = ()
    #: (CPU s, wall s) of the pilot's simulation in this process, where it ran now (not read
    #: from the cache): the share of a core a process of ours gets on this machine now
    busy: tuple[float, float] = (0.0, 0.0)

    def cell(self, f: float, family: str, grid: tuple = ()) -> Cell:
        """The pilot cell for (f, family) at the grid values ``grid`` (() without a grid):
        the probed line's own, else the inverse-square-distance mean of the probed lines'
        (numeric axes scaled to their range; a string axis must match) -- the collision
        rate varies irregularly along any axis, as along f, so this is a guess: a plan of
        every line is ``pilot_rates(lines="all")``."""
        if not grid:
            return self.cells[(f_key(f), family)]
        key = (f_key(f), family, grid)
        if key in self.cells:
            return self.cells[key]
        lines = sorted({k[2] for k in self.cells if k[0] == key[0] and k[1] == family}, key=repr)
        scale = {a: (hi - lo) or 1.0 for a, lo, hi in self.scales}
        want = dict(grid)

        def distance2(line) -> float:
            d = 0.0
            for a, v in line:
                if isinstance(v, str):
                    d += 0.0 if v == want[a] else math.inf
                else:
                    d += ((v - want[a]) / scale[a]) ** 2
            return d

        weights = [(1.0 / d2, self.cells[(key[0], family, line)])
                   for d2, line in ((distance2(line), line) for line in lines) if math.isfinite(d2)]
        total = sum(w for w, _ in weights)

        def mean(attr: str) -> float:
            return sum(w * getattr(c, attr) / c.n for w, c in weights) / total

        first = weights[0][1]
        return Cell(f, family, first.n, first.t_max, round(mean("collisions") * first.n),
                    mean("cpu_s") * first.n, mean("D") * first.n,
                    mean("D_hw") * first.n)

    def ci_law(self, family: str, grid: tuple, target: float | None, d_resolved: float | None,
               z: float) -> tuple[float, int]:
        """(k, cells): the CI-law constant -- 95 % half-width of D = k D / sqrt(N) -- from this
        pilot's own spread, k = z sqrt(mean of cv2 / (1 - cv2 / n)) (each cell's var(D_i) over
        mean(D_i)^2 - var / n, the unbiased estimate of the squared mean), pooled over the
        piloted cells of ``family`` on the line ``grid`` (the whole scene's if the line has
        fewer than POOL_MIN) where the relative target decides (target D >= d_resolved) and
        at least two particles move (cv2 < n / 2: one mover of n has cv2 = n); (CI_LAW, 0)
        without such cells.  Pooling is what makes 8 particles enough: one cell's spread from
        8 is biased low, the mean of many cells' unbiased ratios much less."""
        def pool(cells) -> list[float]:
            floor = (d_resolved or 0.0) / target if target else 0.0
            return [c.cv2 / (1 - c.cv2 / c.n) for c in cells if math.isfinite(c.cv2)
                    and c.cv2 < c.n / 2 and c.D > 0 and c.D >= floor]
        own = [c for k, c in self.cells.items() if k[1] == family and k[2:] == ((grid,) if grid
                                                                               else ())]
        values = pool(own)
        if len(values) < POOL_MIN:
            values = pool(c for k, c in self.cells.items() if k[1] == family)
        if len(values) < POOL_MIN:
            return CI_LAW, 0
        return z * math.sqrt(sum(values) / len(values)), len(values)

    @property
    def kernel_rate(self) -> float:
        if self.rate is not None:
            return self.rate
        cpu = sum(c.cpu_s for c in self.cells.values())
        return sum(c.collisions for c in self.cells.values()) / cpu

    def with_rate(self, rate: float, source: str) -> Rates:
        """The same collisions with another kernel rate (collisions per CPU-s)."""
        return replace(self, rate=rate, source=f"{self.source}; kernel rate from {source}")

    def scaled(self, factor: float) -> Rates:
        """The same table with the kernel rate times ``factor`` (a perturbed cost model)."""
        return replace(self, rate=self.kernel_rate * factor)


@dataclass(frozen=True)
class TaskRow:
    """The prediction for one (point, family): particles, chunks, collisions, CPU-s (f: the
    point's frequency, Hz)."""

    f: float
    family: str
    particles: int
    chunks: int
    collisions: float
    cpu_s: float
    why: str  # fixed | target | resolved | law? | cap
    grid: tuple = ()  # the point's grid values (a map's)


@dataclass(frozen=True)
class Plan:
    name: str
    rows: tuple[TaskRow, ...]
    workers: int
    rate: float
    overheads: Overheads
    makespan: float
    longest_task: float
    source: str
    header: str
    t_max: float
    #: the pilot's simulation time, CPU-s (its cells' fastest timings)
    pilot_cpu_s: float = 0.0
    #: a target scene's CI-law constants k, one per (family, line) (Rates.ci_law)
    laws: tuple[float, ...] = ()

    @property
    def cpu_s(self) -> float:
        return sum(r.cpu_s for r in self.rows)

    @property
    def collisions(self) -> float:
        return sum(r.collisions for r in self.rows)

    @property
    def chunks(self) -> int:
        return sum(r.chunks for r in self.rows)

    @property
    def busy_s(self) -> float:
        """Worker time in tasks, s: task CPU plus the per-task overhead."""
        return self.cpu_s + self.chunks * self.overheads.per_task

    @property
    def wall_s(self) -> float:
        return self.overheads.start_up + self.makespan


# -- the model (pure) -------------------------------------------------------------------------
def particles_needed(study: Study, cell: Cell, law: float = CI_LAW) -> tuple[int, str]:
    """(particles, why) one (frequency, family) is expected to end with.

    Fixed-N scene: (n_particles, "fixed").  Target-driven (``accuracy.target_ci``): the
    chunks the 1/sqrt(N) law (half-width ``law`` D / sqrt(N): :meth:`Rates.ci_law`) asks for to
    reach the rule's goal max(target_ci D, d_resolved) -- the wave rule of
    pipeline/execute/adaptive.py doubles until that number is in reach, then goes to it, so
    with an exact law it ends there -- capped at ``max_particles`` (default n_particles);
    ``why`` says which rule decided.  Where the pilot saw one mover or none (D ~ 0, or a rare
    mover) the point's own bootstrap half-width stands in for law D.
    """
    acc = study.accuracy
    target = getattr(acc, "target_ci", None)
    if target is None:
        return acc.n_particles, "fixed"
    d_resolved = getattr(acc, "d_resolved", None)
    cap = getattr(acc, "max_particles", None) or acc.n_particles
    k, why = law, "target"
    if cell.D > 0 and math.isfinite(cell.D_hw):
        k_pilot = cell.D_hw / cell.D * math.sqrt(cell.n)
        if k_pilot > 2 * law:  # far outside the law: trust the point's own spread
            k, why = k_pilot, "law?"
    need = (k / target) ** 2 if cell.D > 0 or not math.isfinite(cell.D) else math.inf
    if d_resolved is not None and math.isfinite(cell.D_hw):
        # the half-width times sqrt(N), mm^2/s: the law's k D where the pilot's particles move
        # alike (two or more movers), the point's own bootstrap spread where one or none does
        alike = cell.D > 0 and math.isfinite(cell.cv2) and cell.cv2 < cell.n / 2
        spread = k * cell.D if alike else cell.D_hw * math.sqrt(cell.n)
        need_abs = (spread / d_resolved) ** 2
        if need_abs <= need:
            need, why = need_abs, "resolved"
    cap_chunks = max(1, cap // acc.chunk_size)
    chunks = max(1, math.ceil(need / acc.chunk_size)) if math.isfinite(need) else math.inf
    if chunks > cap_chunks:
        chunks, why = cap_chunks, "cap"
    return int(chunks) * acc.chunk_size, why


def makespan(durations: list[float], workers: int) -> float:
    """Wall time of tasks taken in this order by the first free of ``workers`` workers, s."""
    free = [0.0] * workers
    for d in durations:
        heapq.heapreplace(free, free[0] + d)
    return max(free)


def predict(study: Study, rates: Rates, workers: int, overheads: Overheads = Overheads()
            ) -> Plan:
    """CPU and wall time of ``study`` on ``workers`` cores from the cost table ``rates``."""
    acc = study.accuracy
    r = rates.kernel_rate * overheads.in_task
    rows, durations, laws = [], [], {}
    target = getattr(acc, "target_ci", None)
    z = NormalDist().inv_cdf(0.5 + study.analysis.ci / 2) if target is not None else 0.0
    for point in study.points:
        f = point.f
        for fam in study.families:
            cell = rates.cell(f, fam.name, point.grid)
            key = (fam.name, point.grid)
            if target is not None and key not in laws:  # pooled once per (family, line)
                laws[key] = rates.ci_law(fam.name, point.grid, target,
                                         getattr(acc, "d_resolved", None), z)
            law = laws[key][0] if target is not None else CI_LAW
            n, why = particles_needed(study, cell, law)
            chunk_cpu = acc.chunk_size * acc.t_max * cell.per_particle_s / r
            chunks = n // acc.chunk_size
            rows.append(TaskRow(f, fam.name, n, chunks, n * acc.t_max * cell.per_particle_s,
                                chunks * chunk_cpu, why, point.grid))
            durations += [chunk_cpu + overheads.per_task] * chunks
    size = (f"target_ci {target:g} (chunks of {acc.chunk_size})" if target is not None else
            f"{acc.n_particles} particles in chunks of {acc.chunk_size}")
    fams = "family" if len(study.families) == 1 else "families"
    where = (f"{len(study.points)} points ({' x '.join(a for a, _ in study.axes)})"
             if study.grid else f"{len(study.frequencies)} frequencies")
    header = (f"{study.name}: {where} x {len(study.families)} "
              f"{fams}, accuracy {acc.preset}: {size}, t_max {acc.t_max:g} s")
    return Plan(study.name, tuple(rows), workers, r, overheads, makespan(durations, workers),
                max(durations, default=0.0), rates.source, header, acc.t_max,
                sum(c.cpu_s for c in rates.cells.values()), tuple(k for k, _ in laws.values()))


def _band(f: float) -> str:
    lo = max((e for e in BAND_EDGES if e <= f), default=None)
    hi = min((e for e in BAND_EDGES if e > f), default=None)
    if lo is None:
        return f"< {hi:g}"
    return f">= {lo:g}" if hi is None else f"{lo:g}-{hi:g}"


def plan_table(plan: Plan) -> str:
    """The plan as text: one row per frequency band and family, the total, the wall time."""
    groups: dict[tuple[str, str], list[TaskRow]] = {}
    for row in sorted(plan.rows, key=lambda r: r.f):
        groups.setdefault((_band(row.f), row.family), []).append(row)
    grid = any(r.grid for r in plan.rows)  # a map: its rows count points, not frequencies
    w = 6 if grid else 5
    head = (f"{'band (Hz)':<10} {'family':<10} {'points' if grid else 'freqs':>{w}} "
            f"{'particles/pt' if grid else 'particles/f':>12} {'chunks':>6} "
            f"{'coll/particle-s':>15} {'collisions':>10} {'CPU-s':>8} {'share':>6}  stop")
    lines = [plan.header, f"cost model: {plan.source}; {plan.rate:.3g} collisions per task-s "
             f"(kernel rate x {plan.overheads.in_task:g} inside pipeline tasks)", "", head]
    if plan.laws:
        lines.insert(2, f"CI law: half-width = k D / sqrt(N), k {min(plan.laws):.2f}-"
                     f"{max(plan.laws):.2f} pooled from the pilot's spread ({CI_LAW:g} without "
                     "a pool)")
    total_cpu = plan.cpu_s or 1.0
    for (band, fam), rows in groups.items():
        ns = [r.particles for r in rows]
        n_text = f"{min(ns)}" if min(ns) == max(ns) else f"{min(ns)}-{max(ns)}"
        pps = sum(r.collisions for r in rows) / sum(r.particles for r in rows) / plan.t_max
        whys = sorted({r.why for r in rows})
        why = ", ".join(f"{w} {sum(r.why == w for r in rows)}" for w in whys)
        cpu = sum(r.cpu_s for r in rows)
        lines.append(f"{band:<10} {fam:<10} {len(rows):>{w}} {n_text:>12} "
                     f"{sum(r.chunks for r in rows):>6} {pps:>15.4g} "
                     f"{sum(r.collisions for r in rows):>10.3g} {cpu:>8.1f} "
                     f"{100 * cpu / total_cpu:>5.1f}%  {why}")
    freqs = len({(r.f, r.grid) for r in plan.rows})
    lines.append(f"{'total':<10} {'':<10} {freqs:>{w}} {'':>12} {plan.chunks:>6} {'':>15} "
                 f"{plan.collisions:>10.3g} {plan.cpu_s:>8.1f} {100.0:>5.1f}%")
    lines.append("")
    lines.append(f"predicted: {plan.cpu_s:.0f} CPU-s in tasks; wall {plan.wall_s:.0f} s "
                 f"({plan.wall_s / 60:.1f} min) on {plan.workers} workers = start-up "
                 f"{plan.overheads.start_up:g} s + {plan.makespan:.0f} s of tasks (CPU / "
                 f"workers {plan.cpu_s / plan.workers:.0f} s, {plan.chunks} x "
                 f"{plan.overheads.per_task:g} s per task, the tail); longest task "
                 f"{plan.longest_task:.1f} s")
    lines.append(f"pilot: {plan.pilot_cpu_s:.1f} CPU-s of simulation, "
                 f"{100 * plan.pilot_cpu_s / total_cpu:.1f} % of the run's")
    return "\n".join(lines)
