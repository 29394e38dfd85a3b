"""The pilot of ``bbb plan``: what a workflow's cost is measured from, on this machine.

* Collisions per particle-second, c(f, family): measured by a *pilot* -- a few particles
  (default 8, at most PILOT_MAX_SHARE of a fixed-size scene's: a scene of fewer than 4
  particles per point is cheaper than its pilot and not piloted) over the workflow's own
  t_max, with its own parameters, numerics and family, at every frequency.  The collision
  count of the kernel is exact and deterministic (same seeds, same count on any machine), and
  c varies irregularly with f (1070 per particle-s in the creeping band 50-58 Hz from rest,
  ~50 in the spirals; benchmarks/results/pipeline-*.txt), so no interpolation over f from a
  table can stand in for it.  The pilot runs the whole t_max because c is not constant in time
  (launched particles fall into creeping one by one at 54-55 Hz; creeping from rest starts
  with a cascade), so a short pilot would be biased. It is cheap because it is few particles:
  for Fig. 2, 8 x 50 s at 124 frequencies is ~8 CPU-s, against 3409 CPU-s for the run.
  Results are cached per (kernel, parameters, numerics, t_max, family, frequency), so a second
  ``bbb plan`` -- or the same scene at another preset with the same t_max and numerics -- runs
  nothing.
* Kernel rate r (collisions per CPU-second of one core): the pilot's collisions over its own
  process CPU time (not wall time, so a load from other users while planning does not enter
  it); a pilot of less than TIMING_FLOOR_S CPU-s is timed again until its repeats reach it,
  and each cell keeps its fastest time (a short timing on a shared VM can read slow:
  benchmarks/results/pilot-timing-2026-11-24.md).

:func:`pilot_rates` returns a :class:`pipeline.execute.plan.Rates` table; :func:`benchmark_rate`
reads a kernel rate from a committed benchmark instead.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
from dataclasses import replace
from datetime import UTC, datetime
from pathlib import Path

# PILOT_CHUNK, the pilot's chunk index in the seed (no real chunk has it): importable from here
# as before pipeline.workflow.identity
from ..workflow.identity import PILOT_CHUNK, f_key, pilot_seed  # noqa: F401
from ..workflow.sanity import check_scene
from ..workflow.study import Study
from .machine_load import MachineShare
from .plan import Cell, Rates

__all__ = ["pilot_rates", "probe_lines", "pilot_share", "benchmark_rate", "plan_rates",
           "PILOT_PARTICLES", "PILOT_PARTICLES_TARGET", "PILOT_SHARE", "PILOT_MAX_SHARE",
           "pilot_particles", "cheaper_than_pilot", "machine_share", "TIMING_FLOOR_S",
           "SHARE_PROBE_S"]

#: pilot particles per (frequency, family) of a fixed-size scene, whose cost is its collision rates
PILOT_PARTICLES = 8
#: ... of a scene with a CI target, whose cost is set by the particles' spread of D: 8 particles
#: under-read it where the spread is wide (the R = 25 mm map's collisions 1.32 of the plan with 8,
#: 1.04 with 16: benchmarks/results/map-costs-2026-11-25-pilot-model.md; on a hold-out scene
#: written after the choice: benchmarks/results/plan-holdout-2026-11-25.txt)
PILOT_PARTICLES_TARGET = 16
#: a pilot that measured less CPU than this, s, is timed again (same seeds) until its repeats
#: add up to it, and each cell keeps its fastest repeat: on a shared 2-core VM a 0.3 s pilot
#: timed once can read slow enough to push the tiny scene of tests/pipeline/execute/test_plan.py past
#: its band (benchmarks/results/pilot-timing-2026-11-24.md)
TIMING_FLOOR_S = 1.5
#: a map's every line is piloted (``lines="auto"``) when that costs at most this share of the run
#: the probe lines price
PILOT_SHARE = 0.05
#: the most of a fixed-size run's simulation its default pilot costs: a pilot of n particles at
#: every (point, family) over the run's t_max simulates n / N of a run of N particles per
#: (point, family), known before anything runs.  A scene of fewer than 1 / PILOT_MAX_SHARE
#: particles is cheaper than a pilot of one particle is worth: `bbb plan` says so and does
#: not pilot it; below PILOT_PARTICLES / PILOT_MAX_SHARE particles the pilot shrinks
PILOT_MAX_SHARE = 0.25
#: how long `bbb plan` measures the share of a core one process gets now, s (machine_share)
SHARE_PROBE_S = 1.5
#: a cached pilot older than its format is recomputed (2: cells hold cv2, the per-particle spread)
CACHE_VERSION = 2


def pilot_particles(study: Study) -> int:
    """The default pilot size per (frequency, family): :data:`PILOT_PARTICLES_TARGET` for a
    scene with a CI target (``[accuracy] target_ci``; its run's size is what the pilot
    predicts, so no share of it is known before), else :data:`PILOT_PARTICLES`, at most
    :data:`PILOT_MAX_SHARE` of the scene's particles -- 0 for a scene cheaper than its pilot
    (:func:`cheaper_than_pilot`)."""
    if study.accuracy.adaptive:
        return PILOT_PARTICLES_TARGET
    return min(PILOT_PARTICLES, math.floor(PILOT_MAX_SHARE * study.accuracy.n_particles))


def cheaper_than_pilot(study: Study) -> str | None:
    """Why ``study`` is not piloted by default -- a fixed-size scene of fewer particles per
    (point, family) than 1 / :data:`PILOT_MAX_SHARE`, so that a pilot of even one particle
    would simulate more than that share of the run -- or None."""
    acc = study.accuracy
    if acc.adaptive or pilot_particles(study) >= 1:
        return None
    where = f"{len(study.points)} points" if study.grid else f"{len(study.frequencies)} frequencies"
    return (f"{study.name}: cheaper than its pilot -- {acc.n_particles} particles x "
            f"{acc.t_max:g} s at {where} x {len(study.families)} families; a pilot of one "
            f"particle per point would simulate 1/{acc.n_particles} of the run, more than "
            f"{PILOT_MAX_SHARE:.0%}: not piloted (run it: `bbb run` shows its progress and "
            "time; --pilot-particles 1 pilots it anyway)")


def pilot_rates(study: Study, *, particles: int | None = None,
                cache_dir: str | os.PathLike | None = "runs/plan-cache",
                echo=None, lines: str = "auto", cached_only: bool = False,
                label: str = "") -> Rates | None:
    """Measure (or read from the cache) a pilot :class:`Cell` at every (frequency, family)
    of ``study``: ``particles`` particles (default :func:`pilot_particles`), at most half the
    study's, over its t_max.  A grid
    is piloted along its probe lines (:func:`probe_lines`: the corners and the centre of its
    axes), every other point costed from them (:meth:`Rates.cell`), or with ``lines="all"``
    along every line; ``lines="auto"`` (default) pilots every line when that is cheap
    (:data:`PILOT_SHARE` of the run), else the probes.  ``cached_only``: None unless every
    cell is in the cache (`bbb scenes`).  ``echo`` gets one line per pilot (named by
    ``label``, a grid line's values) and a progress bar on stderr when that is a terminal."""
    from bbb.provenance import kernel_hash

    particles = max(1, pilot_particles(study) if particles is None else particles)
    if study.grid:
        return _grid_rates(study, particles, cache_dir, echo, lines, cached_only)
    acc = study.accuracy
    n = max(1, min(particles, acc.n_particles // 2))
    cells: dict[tuple[int, str], Cell] = {}
    todo = []
    caches = {}
    for fam in study.families:
        ident = {"v": CACHE_VERSION, "kernel": kernel_hash(), "params": study.base_params,
                 "numerics": {k: getattr(acc, k) for k in ("tol_t", "v_stick", "max_step")},
                 "t_max": acc.t_max, "sample_dt": acc.sample_dt, "n": n, "seed": study.seed,
                 "family": {k: v for k, v in vars(fam).items() if k != "description"},
                 "analysis": vars(study.analysis), "positions": bool(study.observables.positions)}
        digest = hashlib.sha256(json.dumps(ident, sort_keys=True, default=str).encode())
        path = Path(cache_dir) / f"{digest.hexdigest()[:20]}.json" if cache_dir else None
        stored = json.loads(path.read_text()) if path and path.exists() else {}
        caches[fam.name] = (path, stored)
        for f in study.frequencies:
            key = str(f_key(f))
            if key in stored:
                cells[(f_key(f), fam.name)] = Cell(**stored[key]["cell"])
            else:
                todo.append((f, fam))
    when = {s.get("_measured") for _, s in caches.values() if s}
    busy = (0.0, 0.0)
    if todo and cached_only:
        return None
    if todo:
        from .task import warm_numba

        warm = warm_numba(study)
        if echo:
            echo(f"{study.name}{label}: pilot of {n} particles x {acc.t_max:g} s at {len(todo)} "
                 f"(frequency, family) pairs (kernel ready in {warm:.1f} s) ...")
        w0, c0 = time.perf_counter(), time.process_time()
        measured = _fastest_timings(study, todo, n, _timing_share(study, n),
                                    f"{study.name}{label}" if echo else None)
        busy = (time.process_time() - c0, time.perf_counter() - w0)
        cells.update(measured)
        for (mhz, name), cell in measured.items():
            caches[name][1][str(mhz)] = {"cell": vars(cell)}
        now = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
        for path, stored in caches.values():
            if path is not None:
                stored.setdefault("_measured", now)
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(json.dumps(stored, indent=0, sort_keys=True))
        when.add(now)
    when.discard(None)
    shrunk = (f" (not {PILOT_PARTICLES}: a pilot simulates at most {PILOT_MAX_SHARE:.0%} of "
              "the run)" if not acc.adaptive and n < PILOT_PARTICLES and particles <
              PILOT_PARTICLES and particles == pilot_particles(study) else "")
    src = (f"pilot {n} particles x {acc.t_max:g} s per (frequency, family){shrunk}, "
           f"measured {', '.join(sorted(when))}" + (", cached" if not todo else ""))
    return Rates(cells, source=src, busy=busy)


def probe_lines(study: Study) -> list[tuple[tuple[str, object], ...]]:
    """The grid lines a grid scene's plan pilots, as grid values: for every combination of the
    string axes' values (contact) the lines hold, every corner of the numeric axes (their
    least and greatest values among those lines) and the centre (each numeric axis's middle
    value).  Corners are taken among the lines that exist, so a conditional axis (mu, only
    under contact = "coulomb") gets its own corners per contact model, and a model whose lines
    all hold mu's default is probed too."""
    import itertools

    lines = list(dict.fromkeys(p.grid for p in study.points))
    strings = {a for a, values in study.grid if isinstance(values[0], str)}
    groups: dict[tuple, list[tuple]] = {}
    for line in lines:
        groups.setdefault(tuple((a, v) for a, v in line if a in strings), []).append(line)
    out: list[tuple] = []
    for key, members in groups.items():
        order = [a for a, _ in members[0]]
        corner_values, centre = [], []
        for a in order:
            if a in strings:
                continue
            s = sorted({dict(m)[a] for m in members})
            corner_values.append([(a, v) for v in dict.fromkeys((s[0], s[-1]))])
            centre.append([(a, s[(len(s) - 1) // 2])])
        have = set(members)
        for combo in [*itertools.product(*corner_values), *itertools.product(*centre)]:
            values = {**dict(key), **dict(combo)}
            line = tuple((a, values[a]) for a in order)
            if line in have and line not in out:
                out.append(line)
    return out


def _grid_rates(study: Study, particles: int, cache_dir, echo, lines: str,
                cached_only: bool = False) -> Rates | None:
    """The pilot of a grid scene: the 1-D pilot of each probe line, or of every line
    (``lines="all"``), each cached as that line's scene's; ``lines="auto"``: the probe lines,
    then every line if that pilot costs at most PILOT_SHARE of the run they price
    (:func:`pilot_share`)."""
    if lines == "auto":
        probes = _grid_rates(study, particles, cache_dir, echo, "probes", cached_only)
        if probes is None:
            return None
        every = list(dict.fromkeys(p.grid for p in study.points))
        if len(probe_lines(study)) == len(every):
            return probes
        share = pilot_share(study, probes)
        if share > PILOT_SHARE:
            return replace(probes, source=f"{probes.source} (a pilot of every line would cost "
                           f"{share:.0%} of the run, more than {PILOT_SHARE:.0%})")
        rates = _grid_rates(study, particles, cache_dir, echo, "all", cached_only)
        if rates is None:
            return None
        return replace(rates, source=f"{rates.source} (its pilot costs {share:.1%} of the run)",
                       busy=tuple(a + b for a, b in zip(probes.busy, rates.busy, strict=True)))
    cells, sources, busy = {}, set(), (0.0, 0.0)
    todo = (probe_lines(study) if lines == "probes"
            else list(dict.fromkeys(p.grid for p in study.points)))
    for i, line in enumerate(todo):
        label = f" [{', '.join(f'{a}={v}' for a, v in line)}] (line {i + 1} of {len(todo)})"
        rates = pilot_rates(study.line(dict(line)), particles=particles, cache_dir=cache_dir,
                            echo=echo, cached_only=cached_only, label=label)
        if rates is None:
            return None
        cells.update({(mhz, fam, line): c for (mhz, fam), c in rates.cells.items()})
        sources.add(rates.source)
        busy = (busy[0] + rates.busy[0], busy[1] + rates.busy[1])
    scales = tuple((a, float(min(v)), float(max(v))) for a, v in study.grid
                   if not isinstance(v[0], str))
    every = len(dict.fromkeys(p.grid for p in study.points))
    src = (f"{'; '.join(sorted(sources))}; " + (
        f"{len(todo)} probe lines of the grid (corners and centre), the other lines costed "
        "from them by inverse-square distance" if lines == "probes" and len(todo) < every else
        f"every line of the grid ({len(todo)})"))
    return Rates(cells, source=src, scales=scales, busy=busy)


def pilot_share(study: Study, rates: Rates) -> float:
    """What a pilot of every line of the grid scene ``study`` costs, as a share of the run
    ``rates`` prices: its particles times each point's collisions per particle over the run's
    collisions.  Interpolated lines are guesses (the collision rate changes irregularly
    along an axis, as along f), so every line is piloted when this is small."""
    from .plan import predict

    plan = predict(study, rates, 1)
    n = next(iter(rates.cells.values())).n
    pilot = sum(n * r.collisions / r.particles for r in plan.rows if r.particles)
    return pilot / plan.collisions if plan.collisions else 1.0


def machine_share(busy: tuple[float, float] = (0.0, 0.0),
                  seconds: float = SHARE_PROBE_S) -> MachineShare:
    """What a run would get of this machine now (:class:`~pipeline.execute.plan.MachineShare`):
    the share of a core one process of ours gets -- its CPU time over the wall time of the
    pilot's simulation that just ran (``busy``: CPU s, wall s; :attr:`Rates.busy`), if it
    lasted at least ``seconds``, else of a spin of ``seconds`` -- the 1-minute load average,
    and whether the kernel shares the CPU between sessions before processes (Linux's
    autogroup, /proc/sys/kernel/sched_autogroup_enabled)."""
    if busy[1] >= seconds:
        share = busy[0] / busy[1]
    else:
        t0, c0 = time.perf_counter(), time.thread_time()
        while time.perf_counter() - t0 < seconds:
            sum(range(1000))
        share = (time.thread_time() - c0) / (time.perf_counter() - t0)
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):
        load = None
    try:
        grouped = Path("/proc/sys/kernel/sched_autogroup_enabled").read_text().strip() == "1"
    except OSError:
        grouped = False
    return MachineShare(min(1.0, share), load, grouped)


def plan_rates(study: Study, particles: int | None, lines: str, kernel_rate: str | None,
               echo=None) -> Rates:
    """`bbb plan`'s cost table: the pilot's, with the kernel rate of the benchmark table
    ``kernel_rate`` if given (ValueError, one line, if it cannot be read as one)."""
    check_scene(study, echo)  # pipeline.workflow.sanity: warnings; nothing moves -> refused
    rate = None
    if kernel_rate:
        try:
            rate = benchmark_rate(kernel_rate)
        except OSError as e:
            raise ValueError(f"--kernel-rate {kernel_rate}: {e.strerror}; allowed: a kernel "
                             "benchmark table, e.g. benchmarks/results/kernel-*.txt") from None
        except ValueError as e:
            raise ValueError(f"--kernel-rate {e}") from None
    rates = pilot_rates(study, particles=particles, lines=lines, echo=echo)
    return rates if rate is None else rates.with_rate(rate, Path(kernel_rate).name)


def benchmark_rate(path: str | os.PathLike) -> float:
    """Collisions per second of one core from a ``benchmarks/perf/kernel.py`` table
    (benchmarks/results/kernel-*.txt): summed collisions over summed wall time of its rows."""
    coll = wall = 0.0
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        parts = line.split()
        if len(parts) == 5 and not line.startswith("#"):
            try:
                _, c, w, _ = float(parts[0]), float(parts[2]), float(parts[3]), float(parts[4])
            except ValueError:
                continue
            coll, wall = coll + c, wall + w
    if wall <= 0:
        raise ValueError(f"{path}: no rows 'f family collisions wall rate' of a kernel benchmark")
    return coll / wall


def _timing_share(study: Study, n: int) -> float:
    """The CPU-s a pilot of ``n`` particles is timed to (:func:`_fastest_timings`) as a multiple
    of its first timing: up to TIMING_FLOOR_S, but for a fixed-size scene at most what keeps the
    pilot within PILOT_MAX_SHARE of the run (N / n times the first timing): repeating a small
    pilot of a small scene until 1.5 s would cost more than the run it prices."""
    acc = study.accuracy
    return math.inf if acc.adaptive else PILOT_MAX_SHARE * acc.n_particles / n


def _fastest_timings(study: Study, todo, n: int, share: float = math.inf,
                     desc: str | None = None) -> dict[tuple[int, str], Cell]:
    """The pilot cell at each (f, family) of ``todo``, keyed (f in mHz, family name), its
    cpu_s the least of its timings: the pilot is timed again (same seeds, so the same
    collisions) until all its timings add up to TIMING_FLOOR_S or ``share`` times its first
    timing, whichever is less, at most 20 rounds.  ``desc``: a progress bar (stderr, on a
    terminal only) over the first timings."""
    from tqdm import tqdm

    with tqdm(todo, desc=desc and f"{desc}: pilot", unit="pair", file=sys.stderr,
              disable=None if desc else True, leave=False) as bar:
        cells = {(f_key(f), fam.name): _pilot_cell(study, f, fam, n) for f, fam in bar}
    timed = sum(c.cpu_s for c in cells.values())
    floor = min(TIMING_FLOOR_S, share * timed)
    for _ in range(20):
        if timed >= floor:
            break
        for f, fam in todo:
            key = (f_key(f), fam.name)
            cpu = _pilot_cpu(study, f, fam, n)
            timed += cpu
            cells[key] = replace(cells[key], cpu_s=min(cells[key].cpu_s, cpu))
    return cells


def _pilot_run(study: Study, f: float, fam, n: int):
    """The pilot's simulation at (f, family): (SimRun, its process CPU time in s, seed)."""
    from bbb.simulate import simulate

    acc = study.accuracy
    positions = bool(study.observables.positions)
    seed = pilot_seed(study, f, fam)
    t0 = time.process_time()
    run = simulate(study.params(f), n, acc.t_max, seed,
                   sample_times=study.sample_times() if positions else None,
                   numerics=acc.numerics(), **fam.simulate_kwargs())
    return run, time.process_time() - t0, seed


def _pilot_cpu(study: Study, f: float, fam, n: int) -> float:
    """The pilot at (f, family) timed once more, process CPU s (the same seeds and collisions)."""
    return _pilot_run(study, f, fam, n)[1]


def _pilot_cell(study: Study, f: float, fam, n: int) -> Cell:
    from bbb.analysis import stats

    acc, an = study.accuracy, study.analysis
    positions = bool(study.observables.positions)
    times = study.sample_times()
    run, cpu, seed = _pilot_run(study, f, fam, n)
    D = hw = cv2 = math.nan
    if positions and n >= 2:
        T = an.duration(acc.t_max)
        fit = {"fit_from": an.fit_from * T, "fit_to": an.fit_to * T, "discard": an.discard}
        ci = stats.bootstrap_D(run.positions, times, n_resamples=400, ci=an.ci, seed=seed,
                               **fit)
        D, hw = ci.D, (ci.hi - ci.lo) / 2
        d_i = stats.per_particle_D(run.positions, times, **fit)
        if d_i.mean() > 0:  # the particles' relative spread of D, unbiased variance
            cv2 = float(d_i.var(ddof=1) / d_i.mean() ** 2)
    return Cell(float(f), fam.name, n, acc.t_max, int(run.counters["collisions"].sum()),
                cpu, float(D), float(hw), cv2)
