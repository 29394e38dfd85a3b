"""Soak: the invariant budget of issue 6 — ≥ 10⁹ collisions across the extreme-parameter table
of tests/bbb/dynamics/test_extremes.py, with zero particles below the surface and zero non-finite values.

    .venv/bin/python -m benchmarks.checks.soak [--target 1e9] [--workers 2] [--sample 1000] [--check 4]
    .venv/bin/python -m benchmarks.checks.soak --mix transport [--case KEY=VAL[,KEY=VAL...]] ...

Not part of CI (10–20 min on 2 cores).  Commit the output under benchmarks/results/.

Each case of the table runs for ``max(t_max of the test, 30 s)`` in tasks of a few hundred
particles, spread over ``--workers`` processes (largest tasks first).  A 4-particle pilot
measures each case's collisions per particle; the target is shared out evenly, and cases
whose particles come to rest (A = 0, f = 0.5 Hz, ...) take what they can give with at most
``--max-particles`` particles.  Checks stay cheap: every particle records a window of
``--sample`` consecutive events (collisions and lift-offs) near the end of its run (from the
start if it has fewer), every recorded value is checked to be finite, and the first ``--check``
particles of each task go through the independent trajectory checker
(tests/bbb/trajectory_check.py: each collision where the previous flight's parabola meets the
moving surface — 'off surf' —, Eqs. (5)-(6) — 'rule' —, carried stretches and lift-off times
— 'liftoff' —, the gap certified ≥ 0 along every flight — 'gap'; lift-off flights included,
the first flight from the initial state too when the record starts at t = 0) and have every
recorded flight searched on a fine time grid (tests/bbb/flight_check.py) for a point below
the surface.  'below' counts particles with any checker failure, a flight below the surface,
or a repaired velocity (counters['anomalies']).

'sticks' counts recorded collisions that ended a flight in sticking; 'arrested' those among
them where the particle could not have gone on chattering along the arc: its tangential
speed relative to the floor, v_t > 1 mm/s, was fast enough to leave the convex arc,
v_t²/R > (g + a_floor) n_y > 0, away from the cusps (|d| < S/2 - 0.01 mm, where a corner
would catch it), yet the sticking rule set it to zero (see the xfail'd tangent-touch case of
the test).  In a chattering cascade Eq. (6) multiplies v_t by β at each of infinitely many
collisions, so zeroing it there is the model's own limit; an arrest is where it is not.
Only collisions after a recorded flight are classified, and only on the paper's floor
(a tilted or thrown one shows '-': the classification assumes vertical vibration).

Parameter sets other than the table's: each ``--case KEY=VAL[,KEY=VAL...]`` (repeatable) is
one row, ``bbb.Params(**(BASE | overrides))`` with BASE the table's base parameters (the
paper's, f = 60 Hz) and every KEY passed on as it is (a value that parses as a float is one,
e.g. ``R=inf``; any other stays a string), particles of the 'launched' family.  ``--mix
transport`` adds the conveyor's preset rows (TRANSPORT_MIX).  Given any, the soak runs those
rows instead of the table, shares the target evenly among them and hands their tasks out
round-robin; the checks and the table are the same.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import math
import os
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

import numba
import numpy as np

from bbb import Params
from bbb.surface import cell_of
from benchmarks.common import cpu_name
from tests.bbb.dynamics.test_extremes import (
    BASE,
    CASES,
    Case,
    impacts,
    invariant_violations,
    rows_of,
    run_case,
)

T_SOAK = 30.0  # s, the shortest soak run of a case
TASK_COLLISIONS = 2e7  # ~10-15 s of kernel time per task
#: --mix transport: the conveyor (issue 14) on flat (R=inf) and curved floors, R=S/2 included,
#: tilt ±30°, throw 10°-90°, Γ = 1.4 (A=0.1), 4.3 (A=0.3), 7.2 (A=0.5)
TRANSPORT_MIX = (
    "tilt=-30,throw=60",
    "tilt=30,throw=10,A=0.5,R=inf",
    "tilt=-30,throw=10,A=0.5",
    "tilt=15,throw=45,A=0.3",
    "tilt=-5,throw=30,A=0.3,R=inf",
    "tilt=30,throw=90",
    "tilt=-30,throw=45,R=1.05",  # R = S/2 is refused on the conveyor (bbb.Params)
)
MIXES = {"transport": TRANSPORT_MIX}

_specs: tuple[str, ...] = ()  # the --case rows of this process (empty: the extremes table)


def overrides(spec: str) -> dict[str, float | str]:
    """``KEY=VAL[,KEY=VAL...]`` as a dict; VAL a float where it parses as one, else a string."""
    out: dict[str, float | str] = {}
    for item in spec.split(","):
        key, eq, val = (part.strip() for part in item.partition("="))
        if not (eq and key and val):
            raise ValueError(f"{item!r} is not KEY=VAL; expected KEY=VAL[,KEY=VAL...]")
        try:
            out[key] = float(val)
        except ValueError:
            out[key] = val
    return out


def no_claim(p, st, run) -> None:
    """A --case row claims nothing beyond the invariants every row is held to."""


def case_of(spec: str) -> Case:
    """The soak row of one ``--case``: the table's base parameters with the overrides."""
    try:
        p = Params(**(BASE | overrides(spec)))
    except TypeError:
        allowed = ", ".join(f.name for f in dataclasses.fields(Params))
        keys = sorted(overrides(spec))
        raise ValueError(f"--case {spec!r}: unknown key in {keys}; allowed: {allowed}") from None
    except ValueError as e:
        raise ValueError(f"--case {spec!r}: {e}") from None
    return Case(spec, p, "launched", no_claim)


def set_cases(specs: tuple[str, ...]) -> None:
    global _specs
    _specs = specs


def cases() -> list[Case]:
    """The soak's rows: the extremes table, or the --case rows if any were given."""
    return [case_of(s) for s in _specs] if _specs else CASES


@dataclass(frozen=True)
class Task:
    case: int
    seed: int
    n: int
    t_max: float
    record_from: float


def plan_case(index: int, share: float, per_particle: float, max_particles: int, sample: int) -> list[Task]:
    """Tasks of ``index`` that drive about ``share`` collisions (fewer when particles rest)."""
    case = cases()[index]
    t_max = max(case.t_max, T_SOAK)
    per_particle = max(per_particle, 1.0)
    particles = int(min(max_particles, math.ceil(share / per_particle)))
    # record the last ~`sample` collisions: the window opens when ~1.5 sample remain
    record_from = t_max * (1.0 - 1.5 * sample / per_particle) if per_particle > 3 * sample else 0.0
    per_task = int(max(1, min(1000, TASK_COLLISIONS // per_particle)))
    tasks = []
    for k, lo in enumerate(range(0, particles, per_task)):
        tasks.append(Task(index, 1000 * index + k, min(per_task, particles - lo), t_max, record_from))
    return tasks


def pilot(index: int) -> float:
    """Collisions per particle over a soak run of ``cases()[index]`` (4 particles)."""
    case = cases()[index]
    _, run = run_case(case, 4, max(case.t_max, T_SOAK), seed=999, record=0, n_samples=2)
    return float(run.counters["collisions"].mean())


def run_task(task: Task, sample: int, check: int) -> dict:
    case = cases()[task.case]
    p = case.params
    t0 = time.process_time()
    st, run = run_case(case, task.n, task.t_max, task.seed, record=sample, record_from=task.record_from,
                       n_samples=11)
    kernel = time.process_time() - t0
    v = invariant_violations(p, run, per_period=case.per_period, flights=sample,
                             brute_force_particles=check, start=st if task.record_from == 0 else None)
    arrested = sticks = 0
    classified = not p.transport
    for i in range(run.n_particles if classified else 0):
        rows = rows_of(run, i)
        if rows.shape[0] > 1 and np.all(np.isfinite(rows)):
            m = impacts(p, rows)
            stuck = m["from_flight"] & m["stuck"]
            sticks += int(np.count_nonzero(stuck))
            _, d = cell_of(rows[1:, 1], p.S)
            flies_off = ((np.abs(m["ut_in"]) > 1.0) & (m["ut_in"] ** 2 / p.R > m["weight"])
                         & (m["weight"] > 0) & (np.abs(d) < 0.5 * p.S - 0.01))
            arrested += int(np.count_nonzero(stuck & flies_off))
    for m in v.pop("messages"):
        print(f"  case {task.case} seed {task.seed}: {m}", file=sys.stderr, flush=True)
    v.update(case=task.case, particles=task.n, collisions=int(run.counters["collisions"].sum()),
             kernel_s=kernel, check_s=time.process_time() - t0 - kernel, sticks=sticks, arrested=arrested,
             classified=int(classified))
    return v


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--target", type=float, default=1.0e9, help="total collisions (default 1e9)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--sample", type=int, default=1000, help="recorded events per particle")
    ap.add_argument("--check", type=int, default=4,
                    help="particles per task through the trajectory checker and the brute force")
    ap.add_argument("--max-particles", type=int, default=100_000, help="per case")
    ap.add_argument("--case", action="append", default=[], metavar="KEY=VAL[,KEY=VAL...]",
                    help="a parameter set to soak instead of the extremes table (repeatable): bbb.Params "
                         "fields over the table's base, e.g. tilt=-30,throw=60,R=inf")
    ap.add_argument("--mix", choices=sorted(MIXES), action="append", default=[],
                    help="add a preset of --case rows (transport: tilt and throw, issue 14)")
    args = ap.parse_args()
    specs = tuple(s for m in args.mix for s in MIXES[m]) + tuple(args.case)
    try:
        for spec in specs:
            case_of(spec)
    except ValueError as e:
        ap.exit(2, f"{ap.prog}: error: {e}\n")
    if len(set(specs)) != len(specs):
        ap.exit(2, f"{ap.prog}: error: a --case is given twice: {sorted(specs)}\n")
    set_cases(specs)
    rows = cases()
    wall0 = time.perf_counter()
    print(f"# bbb soak (invariant budget, issue 6)  {datetime.datetime.now().isoformat(timespec='seconds')}")
    print(f"# CPU: {cpu_name()}  ({os.cpu_count()} cores)  python {platform.python_version()}  "
          f"numba {numba.__version__}  numpy {np.__version__}")
    print(f"# target {args.target:.3g} collisions, {args.workers} worker processes, sample {args.sample} "
          f"events/particle, trajectory checker and brute force on {args.check} particles/task, "
          "default Numerics")
    if specs:
        print(f"# {len(specs)} parameter sets (--case): bbb.Params over the base "
              f"{', '.join(f'{k}={v:g}' for k, v in BASE.items())}, 'launched' particles; tasks round-robin")
    sys.stdout.flush()

    with ProcessPoolExecutor(max_workers=args.workers, initializer=set_cases, initargs=(specs,)) as pool:
        per_particle = list(pool.map(pilot, range(len(rows))))
        # share the target evenly; cases that cannot reach their share give the rest to the others
        caps = [c * args.max_particles for c in per_particle]
        share = {}
        left, todo = args.target * 1.03, sorted(range(len(rows)), key=lambda i: caps[i])
        for k, i in enumerate(todo):
            share[i] = min(caps[i], left / (len(todo) - k))
            left -= share[i]
        planned = [plan_case(i, share[i], per_particle[i], args.max_particles, args.sample)
                   for i in range(len(rows))]
        if specs:  # round-robin: the k-th task of every row before the (k+1)-th of any
            tasks = [ts[k] for k in range(max(map(len, planned))) for ts in planned if k < len(ts)]
        else:
            tasks = [t for ts in planned for t in ts]
            # largest first: both workers busy to the end
            tasks.sort(key=lambda t: -t.n * per_particle[t.case])
        print(f"# {len(tasks)} tasks; pilot took {time.perf_counter() - wall0:.1f} s")
        print()
        sys.stdout.flush()
        futures = [pool.submit(run_task, t, args.sample, args.check) for t in tasks]
        done: list[dict] = []
        for fut in as_completed(futures):
            done.append(fut.result())
            total = sum(d["collisions"] for d in done)
            print(f"  {len(done)}/{len(tasks)} tasks, {total:.3e} collisions, "
                  f"{time.perf_counter() - wall0:.0f} s", file=sys.stderr, flush=True)
    wall = time.perf_counter() - wall0

    keys = ("particles", "collisions", "rows", "checked", "off_surface", "rule", "liftoff", "gap", "flights",
            "below", "anomalies", "nonfinite", "sticks", "arrested", "classified", "kernel_s", "check_s")
    per_case = {i: dict.fromkeys(keys, 0) | {"worst_gap": math.inf} for i in range(len(rows))}
    for d in done:
        agg = per_case[d["case"]]
        for k in keys:
            agg[k] += d[k]
        agg["worst_gap"] = min(agg["worst_gap"], d["worst_gap"])
    head = (f"{'case':<66} {'particles':>9} {'collisions':>11} {'rows':>10} {'checked':>9} {'off surf':>8} "
            f"{'rule':>5} {'liftoff':>7} {'gap':>5} {'flights bf':>10} {'min gap mm':>10} {'below':>5} "
            f"{'anomal':>6} {'nonfin':>6} {'sticks':>7} {'arrested':>8} {'coll/s/core':>11}")

    def line(name: str, a: dict) -> str:
        rate = a["collisions"] / a["kernel_s"] if a["kernel_s"] > 0 else float("nan")
        return (f"{name[:66]:<66} {a['particles']:9d} {a['collisions']:11.4e} {a['rows']:10d} "
                f"{a['checked']:9d} {a['off_surface']:8d} {a['rule']:5d} {a['liftoff']:7d} {a['gap']:5d} "
                f"{a['flights']:10d} "
                f"{a['worst_gap']:10.2e} {a['below']:5d} {a['anomalies']:6d} {a['nonfinite']:6d} "
                + (f"{a['sticks']:7d} {a['arrested']:8d}" if a["classified"] else f"{'-':>7} {'-':>8}")
                + f" {rate:11.3e}")

    print(head)
    print("-" * len(head))
    tot = dict.fromkeys(keys, 0) | {"worst_gap": math.inf}
    for i, case in enumerate(rows):
        a = per_case[i]
        for k in keys:
            tot[k] += a[k]
        tot["worst_gap"] = min(tot["worst_gap"], a["worst_gap"])
        print(line(case.name, a))
    print("-" * len(head))
    print(line("total", tot))
    print()
    print(f"total collisions        {tot['collisions']:.4e}  (target {args.target:.3g})")
    print(f"particles below surface {tot['below']}  (trajectory checker on {tot['checked']} flights and "
          f"carried stretches: off the surface {tot['off_surface']}, against Eqs. (5)-(6) {tot['rule']}, "
          f"lift-off {tot['liftoff']}, gap not certified >= 0 {tot['gap']}; "
          f"brute-forced flights: {tot['flights']}, lowest gap {tot['worst_gap']:.2e} mm; "
          f"anomalies: {tot['anomalies']})")
    print(f"non-finite values       {tot['nonfinite']}  (recorded collisions and sampled positions)")
    print(f"wall time               {wall:.0f} s on {args.workers} workers  (kernel {tot['kernel_s']:.0f} s, "
          f"checks {tot['check_s']:.0f} s of CPU; {tot['collisions'] / wall:.3e} collisions/s overall)")
    ok = (tot["collisions"] >= args.target and tot["below"] == 0 and tot["nonfinite"] == 0
          and tot["anomalies"] == 0)
    print(f"verdict                 {'PASS' if ok else 'FAIL'}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
