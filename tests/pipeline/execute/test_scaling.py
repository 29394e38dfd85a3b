"""The scaling model of `bbb plan --workers N,...` (pipeline/execute/scaling.py) on cases whose
wall time is known by hand, and its table on a workflow."""

from __future__ import annotations

import math
import random

import pytest

from pipeline.cli import main
from pipeline.execute.adaptive import predicted_waves, wave_ends
from pipeline.execute.plan import Cell, Rates
from pipeline.execute.scale_plan import plan_report, units_of
from pipeline.execute.scaling import Costs, Deployment, Unit, ready_times, simulate
from pipeline.workflow.load import parse_workflow

from .test_plan import PLAN_TINY


def local(n: int, cores: int | None = None) -> Deployment:
    return Deployment("local", n, cores or n)


def random_units(rng: random.Random, n: int) -> list[Unit]:
    return [Unit(rng.randrange(5), rng.uniform(0.1, 3.0),
                 tuple(rng.randrange(1, 5) for _ in range(rng.randrange(1, 4)))) for _ in range(n)]


def test_one_worker_takes_the_sum_of_the_tasks():
    """One worker, no overheads: the wall time is every task's time added up, whatever the
    waves and priorities."""
    units = random_units(random.Random(1), 40)
    total = sum(u.task_s * sum(u.waves) for u in units)
    tl = simulate(units, local(1))
    assert tl.wall == pytest.approx(total, rel=1e-12)
    assert tl.tasks == sum(sum(u.waves) for u in units)
    assert tl.busy == pytest.approx(total, rel=1e-12)


@pytest.mark.parametrize("n_tasks, workers", [(10, 1), (10, 3), (10, 10), (257, 256), (1000, 64)])
def test_equal_independent_tasks_take_ceil_n_over_workers_times_one_task(n_tasks, workers):
    d = 1.75
    units = [Unit(i, d, (1,)) for i in range(n_tasks)]
    assert simulate(units, local(workers)).wall == pytest.approx(math.ceil(n_tasks / workers) * d)


def test_a_chain_of_waves_takes_its_critical_path():
    """One unit, waves of 1, 2, 4 tasks of 2 s, 8 workers, 0.5 s per decision: each wave waits
    for the one before and its decision, so 3 x (2 + 0.5) s, not the 2 s of its tasks side by
    side; with the decisions' cost per chunk read (0.1 s x 1, 3, 7 chunks) added."""
    unit = [Unit(0, 2.0, (1, 2, 4))]
    assert simulate(unit, local(8), Costs(decide_fixed=0.5)).wall == pytest.approx(7.5)
    tl = simulate(unit, local(8), Costs(decide_fixed=0.5, decide=0.1))
    assert tl.wall == pytest.approx(7.5 + 0.1 * (1 + 3 + 7))
    assert tl.bound == "waves"


def test_the_waves_of_many_units_overlap_on_few_workers():
    """Two units of waves (1, 1) of 1 s on 2 workers: the second waves start when the first
    are done, 2 s; on 1 worker every task in turn, 4 s."""
    units = [Unit(0, 1.0, (1, 1)), Unit(1, 1.0, (1, 1))]
    assert simulate(units, local(2)).wall == pytest.approx(2.0)
    assert simulate(units, local(1)).wall == pytest.approx(4.0)


def test_a_later_wave_of_a_lower_point_index_goes_first_once_a_slot_is_free():
    """Priority -fi, as waves.py submits.  Unit A (index 0): waves (1, 1, 1); unit B (index 1):
    one wave of 3; tasks of 1 s, 2 workers.  Holding one task each (slots=1), A's second and
    third waves go before B's queued tasks: A1 B1 | A2 B2 | A3 B3, 3 s (first come first
    served would take 4 s).  Holding two (Dask's prefetch, slots=2), B2 and B3 are already on
    the workers when A2 is submitted, so A2 waits for one of them: 4 s."""
    units = [Unit(0, 1.0, (1, 1, 1)), Unit(1, 1.0, (3,))]
    assert simulate(units, Deployment("local", 2, 2, slots=1)).wall == pytest.approx(3.0)
    assert simulate(units, Deployment("local", 2, 2, slots=2)).wall == pytest.approx(4.0)


def test_the_client_decides_one_wave_after_another():
    """One worker, 10 s per decision: A1 (0-1 s); B runs (1-6 s) while A's decision runs (1-11
    s); B's decision takes its turn after it (11-21 s), and so does A2's dispatch (the
    scheduler shares the client's timeline): A2 21-22 s, its decision 22-32 s."""
    units = [Unit(0, 1.0, (1, 1)), Unit(1, 5.0, (1,))]
    assert simulate(units, local(1), Costs(decide_fixed=10.0)).wall == pytest.approx(32.0)


def test_workers_sharing_cores_run_at_cores_over_busy_workers():
    """8 equal tasks of 1 s on 8 workers sharing 2 cores take 4 s (as on 2 workers), not 1 s;
    3 tasks on 3 workers sharing 2 cores run at 2/3 of a core each, 1.5 s (2 s on 2 workers);
    a task alone runs on one core, never faster."""
    eight = [Unit(i, 1.0, (1,)) for i in range(8)]
    assert simulate(eight, local(8, cores=2)).wall == pytest.approx(4.0)
    assert simulate(eight, local(2)).wall == pytest.approx(4.0)
    three = [Unit(i, 1.0, (1,)) for i in range(3)]
    assert simulate(three, local(3, cores=2)).wall == pytest.approx(1.5)
    assert simulate(three, local(2)).wall == pytest.approx(2.0)
    assert simulate(three[:1], local(3, cores=2)).wall == pytest.approx(1.0)


def test_the_scheduler_bounds_a_run_of_tiny_tasks():
    """10^4 tasks of 1 ms on 256 workers with 2 ms of scheduler time each: the scheduler's
    20 s, not the 0.04 s of work per worker."""
    units = [Unit(0, 0.001, (10_000,))]
    tl = simulate(units, local(256), Costs(sched=0.002))
    assert tl.wall == pytest.approx(20.0 + 0.001, rel=1e-6)
    assert tl.bound == "serial"


def test_the_client_bounds_a_run_whose_results_it_handles_slower_than_they_come():
    units = [Unit(0, 0.001, (1000,))]
    tl = simulate(units, local(64), Costs(result=0.01))
    assert tl.wall == pytest.approx(1000 * 0.01, rel=1e-3)
    assert tl.bound == "serial"


def test_local_start_up_shares_the_cores_and_slurm_workers_load_the_kernel_in_turn():
    costs = Costs(base=1.0, worker_start=2.0, warm=0.5, cold=9.0)
    # local: client warm 0.5; 8 processes on 2 cores 2 x 4 = 8 s; one warm, then 7 on 2 cores
    t0, ready = ready_times(Deployment("local", 8, 2), costs)
    assert t0 == pytest.approx(1.0 + 0.5 + 8.0 + 0.5 + 0.5 * 3.5)
    assert {t for t, _ in ready} == {t0}
    # slurm: jobs of 4 single-core workers: start 2 s, then loads one after another per host;
    # cold, the first of each host compiles
    t0, ready = ready_times(Deployment("slurm", 8, 1, per_host=4, cold=True), costs)
    assert [t for t, _ in ready] == pytest.approx([11.0, 11.5, 12.0, 12.5] * 2)
    assert [h for _, h in ready] == [0] * 4 + [1] * 4
    assert t0 == pytest.approx(11.0)  # the first worker (the client is ready at 1 + 9 s)


def test_wave_ends_follow_the_rule_and_count_its_waves():
    assert wave_ends(1, 1, 32) == [1]
    assert wave_ends(1, 8, 32) == [1, 2, 4, 8]
    assert wave_ends(1, 11, 32) == [1, 2, 4, 8, 11]
    assert wave_ends(1, 100, 32) == [1, 2, 4, 8, 16, 32]
    for need in range(1, 70):
        assert len(wave_ends(1, need, 32)) == predicted_waves(1, need, 32)


def test_a_workflows_units_hold_the_plans_chunks_in_its_waves():
    """Fixed N: one wave per (point, family) of all its chunks; the task time is the chunk's
    CPU over the kernel rate inside tasks plus the per-task overhead."""
    study = parse_workflow(PLAN_TINY)
    cells = {(round(f * 1000), "rest"): Cell(f, "rest", 8, 30.0, 1000 * 8 * 30, 1.0)
             for f in (54.0, 55.0, 60.0, 72.0)}
    units = units_of(study, Rates(cells, rate=1e6))
    assert [u.waves for u in units] == [(4,)] * 4
    assert [u.key for u in units] == [0, 1, 2, 3]
    assert units[0].task_s == pytest.approx(32 * 30 * 1000 / (1e6 * 0.82) + 0.024)
    adaptive = parse_workflow(PLAN_TINY.replace("n_particles = 128",
                                                "target_ci = 0.5\nmax_particles = 512"))
    units = units_of(adaptive, Rates(cells, rate=1e6))
    assert all(u.waves[0] == 1 and all(w >= 1 for w in u.waves) for u in units)


def test_plan_with_a_list_of_workers_prints_a_row_for_each(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "w.toml").write_text(PLAN_TINY.replace("t_max = 30.0", "t_max = 10.0"))
    assert main(["plan", "w.toml", "--workers", "1,2,8", "--pilot-particles", "2",
                 "--cluster", "slurm", "--cores-per-job", "4"]) == 0
    out = capsys.readouterr().out
    rows = [line.split() for line in out.splitlines() if line[:7].strip() in ("1", "2", "8")]
    assert [r[0] for r in rows] == ["1", "2", "8"]
    assert rows[0][2] == "1.00" and rows[0][3] == "100.0%"
    assert "SLURM jobs of 4 single-core workers" in out
    assert "predicted:" in out and "on 1 workers" in out  # the plan's table at the first N


def test_the_chunk_size_sweep_keeps_the_sizes_that_divide_n_particles(tmp_path):
    study = parse_workflow(PLAN_TINY)
    cells = {(round(f * 1000), "rest"): Cell(f, "rest", 8, 30.0, 1000 * 8 * 30, 1.0)
             for f in (54.0, 55.0, 60.0, 72.0)}
    text = plan_report(study, Rates(cells, rate=1e6), [1, 8], chunk_sizes=(16, 32, 48))
    sweep = text[text.index("chunk sizes at 8 workers"):].splitlines()
    assert [line.split()[0] for line in sweep[2:4]] == ["16", "32"]  # 48 does not divide 128
    assert sweep[4].startswith(">= 90 % efficiency at 8 workers: chunk_size")


def test_plan_refuses_a_malformed_worker_list(capsys):
    assert main(["plan", "w.toml", "--workers", "2,x"]) == 2
    assert main(["plan", "w.toml", "--workers", "2,0"]) == 2
    err = capsys.readouterr().err
    assert "'x' is not an integer" in err and "0 is out of range" in err


def test_the_work_bound_counts_the_workers_as_they_become_ready():
    """4 SLURM workers of one job loading the kernel one after another (1 s each): ready at 1,
    2, 3, 4 s; 10 CPU-s of work cannot be done before 5 s (1 + 2 + 3 by 4 s, the last 4 on 4
    workers), not 1 + 10 / 4 = 3.5 s."""
    units = [Unit(0, 2.5, (4,))]
    tl = simulate(units, Deployment("slurm", 4, 1, per_host=4), Costs(warm=1.0))
    assert tl.bounds["work"] == pytest.approx(5.0)
    # the 4 tasks are queued at 1 s: the first two workers ready each take two (one running,
    # one held: Dask's prefetch; work stealing is not simulated), 2 + 2 x 2.5 = 7 s
    assert tl.wall == pytest.approx(7.0)
