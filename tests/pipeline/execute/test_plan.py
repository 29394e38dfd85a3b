"""`bbb plan`: the cost model against a measured run, its table for every workflow, bad input."""

from __future__ import annotations

import logging
import math
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

from pipeline.cli import main
from pipeline.execute.pilot import pilot_rates
from pipeline.execute.plan import Cell, Overheads, Rates, makespan, particles_needed, predict
from pipeline.workflow.load import load_workflow, parse_workflow

from ..helpers import QUIET

ROOT = Path(__file__).resolve().parents[3]
BBB = Path(sys.executable).with_name("bbb")
WORKFLOWS = sorted((ROOT / "workflows").glob("*.toml"))

# Two creeping frequencies (most of the cost, as in Fig. 2) and two bouncing ones, fixed N:
# 16 tasks, ~4 CPU-s in all.
PLAN_TINY = """\
[study]
name = "plantiny"
seed = 11

[params]
preset = "klages2004"

[frequencies]
values = [54.0, 55.0, 60.0, 72.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 128
chunk_size = 32
t_max = 30.0

[observables.positions]
"""


@pytest.mark.parametrize("workflow", WORKFLOWS, ids=[w.stem for w in WORKFLOWS])
def test_plan_prints_a_table_for_every_workflow(workflow, tmp_path, monkeypatch, capsys):
    """Every workflow in workflows/ gets a table whose total row counts all its points (its
    frequencies, times its grid's lines) and chunks, and a predicted wall time (pilot of 2
    particles, cached under tmp_path)."""
    monkeypatch.chdir(tmp_path)
    assert main(["plan", str(workflow), "--workers", "2", "--pilot-particles", "2"]) == 0
    out = capsys.readouterr().out
    study = load_workflow(workflow)
    total = next(line for line in out.splitlines() if line.startswith("total"))
    units = len(study.points) * len(study.families)
    assert total.split()[1] == str(len(study.points))
    if study.accuracy.adaptive:  # a target-driven scene: at least one chunk each, at most the cap
        assert units <= int(total.split()[2]) <= units * study.accuracy.n_chunks
    else:
        assert int(total.split()[2]) == units * study.accuracy.n_chunks
    assert "predicted:" in out and "on 2 workers" in out


def test_the_plan_of_a_tiny_scene_is_its_arithmetic_on_fixed_rates():
    """Pilot cells of 1000, 500, 100, 50 collisions per particle-s at 54, 55, 60, 72 Hz and a
    kernel rate of 1e6 per CPU-s, half of it inside tasks, 0.01 s per task, 4 s start-up: each
    f is 128 particles x 30 s in 4 chunks of 32, a chunk 32 x 30 x c / 5e5 CPU-s (1.92, 0.96,
    0.192, 0.096 s); the tasks in order on 2 workers pair up, so the makespan is 2 x the sum
    of one chunk per f plus 2 tasks' overhead each."""
    study = parse_workflow(PLAN_TINY)
    per_s = {54.0: 1000, 55.0: 500, 60.0: 100, 72.0: 50}
    cells = {(round(f * 1000), "rest"): Cell(f, "rest", 8, 30.0, c * 8 * 30, c * 8 * 30 / 1e6)
             for f, c in per_s.items()}
    plan = predict(study, Rates(cells), workers=2,
                   overheads=Overheads(start_up=4.0, per_task=0.01, in_task=0.5))
    chunk = {f: 32 * 30.0 * c / 5e5 for f, c in per_s.items()}
    assert [(r.f, r.particles, r.chunks, r.why) for r in plan.rows] == [
        (f, 128, 4, "fixed") for f in per_s]
    assert plan.collisions == pytest.approx(sum(128 * 30.0 * c for c in per_s.values()))
    assert plan.cpu_s == pytest.approx(4 * sum(chunk.values()))
    assert plan.busy_s == pytest.approx(plan.cpu_s + 16 * 0.01)
    assert plan.makespan == pytest.approx(2 * sum(d + 0.01 for d in chunk.values()))
    assert plan.longest_task == pytest.approx(chunk[54.0] + 0.01)
    assert plan.wall_s == pytest.approx(4.0 + plan.makespan)


@pytest.mark.slow
def test_prediction_of_a_tiny_scene_matches_its_measured_run(tmp_path):
    """Collisions within 10 %, worker CPU within 30 %, and the compute wall within 1.5x once
    the load of other processes is taken out, of a real run on a 2-worker LocalCluster.
    A wall-time band on a shared machine: marked slow (`make test-slow`), not in `make test`.

    The worker CPU is the workers' process time (not the tasks' wall clocks), so a loaded
    machine does not inflate it; the compute wall is compared with the predicted makespan
    times the load inflation the tasks themselves saw (their wall time over the CPU time)."""
    from distributed import Client, LocalCluster

    from pipeline.execute.run import run_study, warm_numba

    study = parse_workflow(PLAN_TINY)
    plan = predict(study, pilot_rates(study, cache_dir=None), workers=2)
    with (LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                       env={"NUMBA_NUM_THREADS": "1"}, silence_logs=logging.CRITICAL) as cluster,
          Client(cluster) as client):
        client.run(warm_numba, study)  # numba's cache load is start-up, not task time
        cpu0 = client.run(time.process_time)
        report = run_study(study, tmp_path / "p.zarr", scheduler=cluster.scheduler_address,
                           **QUIET)
        cpu1 = client.run(time.process_time)
    worker_cpu = sum(cpu1[w] - cpu0[w] for w in cpu0)
    assert abs(plan.collisions / report.collisions - 1) <= 0.10
    assert 0.7 <= plan.busy_s / worker_cpu <= 1.3, (plan.busy_s, worker_cpu)
    inflation = max(1.0, report.task_seconds / worker_cpu)
    assert 1 / 1.5 <= report.compute_wall / (plan.makespan * inflation) <= 1.5, (
        report.compute_wall, plan.makespan, inflation)


def test_makespan_places_tasks_in_order_on_the_first_free_worker():
    """[3, 1, 1, 1] on 2 workers: the long task on one, the three short ones on the other."""
    assert makespan([3.0, 1.0, 1.0, 1.0], 2) == 3.0
    assert makespan([1.0, 1.0, 1.0, 3.0], 2) == 4.0  # the tail: the long task comes last
    assert makespan([2.0] * 5, 1) == 10.0


def _target_study(target_ci, d_resolved=None, max_particles=None):
    acc = SimpleNamespace(target_ci=target_ci, d_resolved=d_resolved,
                          max_particles=max_particles, chunk_size=512, n_particles=4096)
    return SimpleNamespace(accuracy=acc)


def _cell(D, hw_rel):
    """A pilot of 8 particles whose relative 95 % half-width is ``hw_rel``."""
    return Cell(60.0, "rest", 8, 50.0, 10_000, 0.01, D, D * hw_rel)


def test_target_driven_particles_follow_the_one_over_sqrt_n_law():
    """3 % needs (1.6 / 0.03)^2 = 2844 particles: 6 chunks of 512 = 3072; 10 % needs 256:
    one chunk."""
    law = _cell(300.0, 1.6 / math.sqrt(8))
    assert particles_needed(_target_study(0.03), law) == (3072, "target")
    assert particles_needed(_target_study(0.10), law) == (512, "target")


def test_target_driven_particles_take_the_pilots_spread_far_outside_the_law():
    """A pilot spread 4x the law's (mixed creeping/bouncing): 16x the particles, 10 % then
    needs 4096 = 8 chunks."""
    assert particles_needed(_target_study(0.10), _cell(300.0, 4 * 1.6 / math.sqrt(8))) == (
        4096, "law?")


def test_target_driven_zero_is_resolved_by_the_first_wave():
    """D = 1e-4 mm^2/s with a half-width of 50 % at 8 particles: far below d_resolved = 1."""
    assert particles_needed(_target_study(0.03, d_resolved=1.0), _cell(1e-4, 0.5)) == (
        512, "resolved")


def test_target_driven_particles_stop_at_the_cap():
    """1 % needs 25 600 particles; max_particles = 8192 stops at 16 chunks and says so;
    without max_particles the cap is n_particles (4096)."""
    law = _cell(300.0, 1.6 / math.sqrt(8))
    assert particles_needed(_target_study(0.01, max_particles=8192), law) == (8192, "cap")
    assert particles_needed(_target_study(0.01), law) == (4096, "cap")


def test_fixed_n_scene_keeps_its_particles():
    study = parse_workflow(PLAN_TINY)
    assert particles_needed(study, _cell(300.0, 0.5)) == (128, "fixed")


@pytest.mark.parametrize("args, needle", [
    (["plan", "no/such/workflow.toml"], "no/such/workflow.toml: no such workflow file"),
    (["plan", str(ROOT / "workflows" / "smoke.toml"), "--workers", "0"],
     "--workers: 0 is out of range"),
    (["plan", str(ROOT / "workflows" / "smoke.toml"), "--kernel-rate", str(ROOT / "README.md")],
     "no rows"),
], ids=["missing-workflow", "workers-0", "not-a-kernel-table"])
def test_bad_input_exits_2_in_one_line(args, needle, tmp_path):
    run = subprocess.run([str(BBB), *args], capture_output=True, text=True, cwd=tmp_path,
                         timeout=120)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and run.stderr.startswith("bbb: error: ")
    assert needle in run.stderr and run.stdout == ""



def test_a_map_line_between_two_probed_lines_is_costed_as_their_distance_weighted_mean():
    from pipeline.execute.plan import Cell, Rates
    from pipeline.workflow.identity import f_key

    def cell(coll):
        return Cell(60.0, "rest", 8, 10.0, coll, coll / 1e6)

    lines = {(("contact", "stick"), ("alpha", 0.5)): 100, (("contact", "stick"), ("alpha", 0.9)): 300,
             (("contact", "slide"), ("alpha", 0.7)): 10_000}
    rates = Rates({(f_key(60.0), "rest", g): cell(c) for g, c in lines.items()},
                  scales=(("alpha", 0.5, 0.9),))
    mid = rates.cell(60.0, "rest", (("contact", "stick"), ("alpha", 0.7)))
    assert mid.collisions == 200  # equidistant: the mean; the slide line never counts
    near = rates.cell(60.0, "rest", (("contact", "stick"), ("alpha", 0.6)))
    assert near.collisions == round((100 / 0.25**2 + 300 / 0.75**2) / (1 / 0.25**2 + 1 / 0.75**2))
    assert rates.cell(60.0, "rest", (("contact", "stick"), ("alpha", 0.9))).collisions == 300


def test_a_maps_plan_counts_its_points_not_its_frequencies():
    from pipeline.execute.plan import Cell, Rates, plan_table, predict
    from pipeline.workflow.identity import f_key
    from pipeline.workflow.load import parse_workflow

    from ..helpers import TINY

    study = parse_workflow(TINY + "[grid]\nalpha = [0.5, 0.7]\n", source="m.toml")
    cells = {(f_key(p.f), fam.name, p.grid): Cell(p.f, fam.name, 4, 10.0, 4000, 0.01)
             for p in study.points for fam in study.families}
    text = plan_table(predict(study, Rates(cells, scales=(("alpha", 0.5, 0.7),)), workers=2))
    head = next(ln for ln in text.splitlines() if ln.startswith("band"))
    total = next(ln for ln in text.splitlines() if ln.startswith("total"))
    assert head.split()[3] == "points" and total.split()[1] == "4"  # 2 f x 2 alpha


@pytest.mark.parametrize("refine, says", [
    ("\n[grid]\nalpha = [0.6, 0.7]\n\n[grid.refine]\nf = 0.5\n", "[grid.refine]"),
    ("\n[grid]\nalpha = [0.6, 0.7]\n", None),
])
def test_the_plan_says_refinement_is_not_priced(refine, says, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    wf = tmp_path / "w.toml"
    wf.write_text(PLAN_TINY.replace("[families.rest]", refine + "\n[families.rest]"))
    assert main(["plan", str(wf), "--workers", "2", "--pilot-particles", "2"]) == 0
    out = capsys.readouterr().out
    assert ("not priced" in out) == (says is not None)
    if says:
        assert says in out


def test_a_map_with_a_conditional_axis_probes_and_prices_every_contact_model():
    """mu applies under coulomb only: the stick lines hold mu's default, not the listed 0.3;
    each model gets its own probe lines, so the stick points are priced from stick pilots."""
    from pipeline.execute.pilot import probe_lines

    study = parse_workflow(PLAN_TINY.replace(
        "[families.rest]", '[grid]\ncontact = ["stick", "coulomb"]\nmu = [0.05, 0.3]\n\n'
        "[families.rest]"))
    probed = probe_lines(study)
    assert {dict(line)["contact"] for line in probed} == {"stick", "coulomb"}
    assert {dict(line)["mu"] for line in probed if dict(line)["contact"] == "coulomb"} == {0.05, 0.3}
    assert all(line in {p.grid for p in study.points} for line in probed)


# -- the CI-law constant from the scene's own pilot -------------------------------------------
def _spread_cell(D, cv2, n=8, f=60.0):
    return Cell(f, "rest", n, 50.0, 10_000, 0.01, D, D * 0.5, cv2)


def _spread_rates(lines: dict) -> Rates:
    """Cells keyed (f, family, line) from {line: [(D, cv2), ...]}, one frequency each."""
    from pipeline.workflow.identity import f_key

    return Rates({(f_key(60.0 + i), "rest", line): _spread_cell(D, cv2, f=60.0 + i)
                  for line, cells in lines.items() for i, (D, cv2) in enumerate(cells)})


def test_the_ci_law_is_pooled_from_the_lines_own_pilot_spread():
    """k = z sqrt(mean u), u = cv2 / (1 - cv2 / n) (cv2 = 1 of 8 particles: u = 8 / 7), over
    the line's cells where the target decides and two or more particles move: a rare-mover
    cell (cv2 = n) and one below d_resolved / target are left out; a line with fewer than
    POOL_MIN such cells takes the scene's pool; no pool: CI_LAW."""
    from pipeline.execute.plan import CI_LAW, POOL_MIN

    a, b = (("alpha", 0.5),), (("alpha", 0.7),)
    rates = _spread_rates({a: [(100.0, 1.0)] * POOL_MIN + [(100.0, 8.0), (1.0, 3.0)],
                           b: [(100.0, 3.0)] * 2})
    k, cells = rates.ci_law("rest", a, 0.05, 2.0, 1.96)
    assert (k, cells) == (pytest.approx(1.96 * math.sqrt(8 / 7)), POOL_MIN)
    k, cells = rates.ci_law("rest", b, 0.05, 2.0, 1.96)
    assert cells == POOL_MIN + 2
    assert k == pytest.approx(1.96 * math.sqrt((POOL_MIN * 8 / 7 + 2 * 3 / (1 - 3 / 8))
                                               / (POOL_MIN + 2)))
    assert _spread_rates({a: [(100.0, 1.0)] * (POOL_MIN - 1)}).ci_law(
        "rest", a, 0.05, 2.0, 1.96) == (CI_LAW, 0)


def test_pooling_small_pilots_recovers_the_spread_one_pilot_underestimates():
    """8 particles per cell whose D_i are exponential (relative variance 1, so k = z = 1.96):
    the pool of 200 cells' unbiased cv2 gives k within 5 %, where the typical single cell's
    spread (median of z sd / mean, as one pilot's bootstrap sees it) is biased low by > 10 %."""
    import numpy as np

    rng = np.random.default_rng(5)
    d = rng.exponential(1.0, size=(200, 8))
    cv2 = d.var(axis=1, ddof=1) / d.mean(axis=1) ** 2
    rates = _spread_rates({(("alpha", 0.5),): [(100.0, float(c)) for c in cv2]})
    k, _ = rates.ci_law("rest", (("alpha", 0.5),), 0.05, None, 1.96)
    assert k == pytest.approx(1.96, rel=0.05)
    single = np.median(1.96 * d.std(axis=1) / d.mean(axis=1))
    assert single < 0.9 * 1.96


def test_target_driven_particles_scale_with_the_pools_law():
    """5 % with the law's 1.6: (1.6 / 0.05)^2 = 1024 = 2 chunks of 512; a pool's k = 2.4 asks
    (2.4 / 0.05)^2 = 2304 = 5 chunks.  Near d_resolved the goal is max(target D, d_resolved):
    D = 20, d_resolved 2 -> (k 20 / 2)^2 = 256 (k 1.6: one chunk), 1024 (k 3.2: two); a pilot
    with one mover (cv2 = n) keeps its own half-width (D_hw sqrt(8) = 28.3 -> 200: one chunk)."""
    law = _cell(300.0, 1.6 / math.sqrt(8))
    assert particles_needed(_target_study(0.05), law, 1.6) == (1024, "target")
    assert particles_needed(_target_study(0.05), law, 2.4) == (2560, "target")
    near = _spread_cell(20.0, 0.5)
    study = _target_study(0.05, d_resolved=2.0)
    assert particles_needed(study, near, 1.6) == (512, "resolved")
    assert particles_needed(study, near, 3.2) == (1024, "resolved")
    assert particles_needed(study, _spread_cell(20.0, 8.0), 3.2) == (512, "resolved")


def test_a_target_plan_states_its_pooled_ci_law():
    """The plan of a target scene prints the range of its k; a fixed-N scene's prints none."""
    from pipeline.execute.plan import plan_table
    from pipeline.workflow.identity import f_key

    six = PLAN_TINY.replace("[54.0, 55.0, 60.0, 72.0]", "[60.0, 62.0, 64.0, 66.0, 68.0, 72.0]")
    fixed = parse_workflow(six)
    target = parse_workflow(six.replace("n_particles = 128",
                                        "target_ci = 0.05\nmax_particles = 1024"))
    for study, shown in ((target, "k 1.96-1.96 pooled"), (fixed, None)):
        cells = {(f_key(f), "rest"): Cell(f, "rest", 8, 30.0, 1000, 0.01, 100.0, 50.0, 8 / 9)
                 for f in study.frequencies}  # cv2 = 8/9 of 8 particles: u = 1, k = z
        text = plan_table(predict(study, Rates(cells), workers=2))
        assert ("CI law" in text) == (shown is not None) and (shown is None or shown in text)


def test_the_plan_of_a_scene_cheaper_than_its_pilot_returns_before_its_run_would(tmp_path):
    """2 particles per point, fewer than a pilot of one particle is worth (pilot.PILOT_MAX_SHARE):
    `bbb plan` says so without piloting and returns in less wall time than `bbb run` of the
    same scene takes (both real commands, timed here)."""
    wf = tmp_path / "cheap.toml"
    wf.write_text(PLAN_TINY.replace("n_particles = 128", "n_particles = 2")
                  .replace("chunk_size = 32", "chunk_size = 1"))

    def timed(*args: str) -> tuple[float, subprocess.CompletedProcess]:
        t0 = time.perf_counter()
        done = subprocess.run([str(BBB), *args], capture_output=True, text=True, cwd=tmp_path,
                              timeout=600)
        assert done.returncode == 0, done.stderr
        return time.perf_counter() - t0, done

    plan_s, plan = timed("plan", str(wf))
    run_s, _ = timed("run", str(wf), "--store", str(tmp_path / "cheap.zarr"), "--no-progress")
    assert "cheaper than its pilot" in plan.stdout and ": pilot of " not in plan.stderr
    assert plan_s < run_s, (plan_s, run_s)
