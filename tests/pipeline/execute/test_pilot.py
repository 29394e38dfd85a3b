"""The pilot of `bbb plan`: exact collisions, and a short pilot's timing taken at its fastest.

The rule is tested with scripted CPU times (the collisions and D are real pilot runs), so no
test here depends on how fast this machine is; the one with the machine's own timings is
marked slow."""

from __future__ import annotations

import pytest

import pipeline.execute.pilot as pilot
from pipeline.workflow.load import parse_workflow

from .test_plan import PLAN_TINY


def _scripted(monkeypatch, first: dict[float, float], repeat: dict[float, float]):
    """Pilot cells whose first timing is ``first[f]`` s and every repeat ``repeat[f]`` s; returns
    ({f: the first cell}, {f: [repeat timings]}) as the pilot fills them."""
    cells, repeats = {}, {}
    real_cell = pilot._pilot_cell

    def cell(study, f, fam, n):
        cells[f] = pilot.replace(real_cell(study, f, fam, n), cpu_s=first[f])
        return cells[f]

    def cpu(study, f, fam, n):
        repeats.setdefault(f, []).append(repeat[f])
        return repeat[f]

    monkeypatch.setattr(pilot, "_pilot_cell", cell)
    monkeypatch.setattr(pilot, "_pilot_cpu", cpu)
    return cells, repeats


def test_a_short_pilot_is_timed_again_until_the_floor_and_keeps_each_cells_fastest_time(
        monkeypatch):
    """First timings 0.35 s at 54 Hz (slow) and 0.05 s elsewhere (0.5 s in all, under the
    1.5 s floor); each repeat 0.1 s at 54 Hz, 0.06 s elsewhere (0.28 s a round): 4 rounds
    reach 1.62 s; 54 Hz keeps 0.1 (its slow first timing dropped), the others their first
    0.05; collisions and D are those of the first run."""
    study = parse_workflow(PLAN_TINY)
    first = {f: 0.35 if f == 54.0 else 0.05 for f in study.frequencies}
    repeat = {f: 0.1 if f == 54.0 else 0.06 for f in study.frequencies}
    cells, repeats = _scripted(monkeypatch, first, repeat)
    rates = pilot.pilot_rates(study, cache_dir=None)
    assert {f: len(r) for f, r in repeats.items()} == {f: 4 for f in study.frequencies}
    for f in study.frequencies:
        cell = rates.cells[(round(f * 1000), "rest")]
        assert cell.cpu_s == (0.1 if f == 54.0 else 0.05)
        assert (cell.collisions, cell.D) == (cells[f].collisions, cells[f].D)
        assert cell.collisions > 0


def test_a_pilot_that_reaches_the_floor_at_once_keeps_its_first_timings(monkeypatch):
    """First timings of 0.5 s at each of 4 frequencies (2 s ≥ the 1.5 s floor): no repeat,
    each cell its first timing.  (The earlier version of the test above read the repeats of
    every frequency and failed here with KeyError: 54.0.)"""
    study = parse_workflow(PLAN_TINY)
    first = {f: 0.5 for f in study.frequencies}
    cells, repeats = _scripted(monkeypatch, first, dict.fromkeys(study.frequencies, 0.01))
    rates = pilot.pilot_rates(study, cache_dir=None)
    assert repeats == {}
    assert [rates.cells[(round(f * 1000), "rest")] for f in study.frequencies] == [
        cells[f] for f in study.frequencies]


@pytest.mark.slow
def test_with_this_machines_timings_each_cell_keeps_its_fastest_timing(monkeypatch):
    """The real timings, the first one at 54 Hz inflated by 0.3 s: each cell's cpu_s is the
    least of its timings, the timings add up to at least the floor, collisions and D are the
    first run's; where the first timings already reached the floor, nothing was repeated."""
    study = parse_workflow(PLAN_TINY)
    first, repeats = {}, {}
    real_cell, real_cpu = pilot._pilot_cell, pilot._pilot_cpu

    def slow_first(study, f, fam, n):
        cell = real_cell(study, f, fam, n)
        first[f] = pilot.replace(cell, cpu_s=cell.cpu_s + 0.3 * (f == 54.0))
        return first[f]

    def recorded(study, f, fam, n):
        cpu = real_cpu(study, f, fam, n)
        repeats.setdefault(f, []).append(cpu)
        return cpu

    monkeypatch.setattr(pilot, "_pilot_cell", slow_first)
    monkeypatch.setattr(pilot, "_pilot_cpu", recorded)
    rates = pilot.pilot_rates(study, cache_dir=None)
    assert sum(c.cpu_s for c in first.values()) + sum(map(sum, repeats.values())) >= (
        pilot.TIMING_FLOOR_S)
    for f in study.frequencies:
        cell = rates.cells[(round(f * 1000), "rest")]
        assert cell.cpu_s == min([first[f].cpu_s, *repeats.get(f, [])])
        assert (cell.collisions, cell.D) == (first[f].collisions, first[f].D)


def _grid_scene(n_particles: int) -> str:
    """Five alpha lines (probes: 0.5, 0.6, 0.7), two bouncing frequencies, fixed N."""
    return (PLAN_TINY.replace("values = [54.0, 55.0, 60.0, 72.0]", "values = [60.0, 72.0]")
            .replace("t_max = 30.0", "t_max = 5.0")
            .replace("n_particles = 128", f"n_particles = {n_particles}")
            .replace("[families.rest]", "[grid]\nalpha = [0.5, 0.55, 0.6, 0.65, 0.7]\n\n"
                     "[families.rest]"))


def test_the_pilots_share_of_a_run_is_its_particles_over_the_points():
    """A pilot of 8 particles per point of a fixed-N map costs 8 / N of the run: 5 % at 160."""
    from pipeline.execute.plan import Cell, Rates
    from pipeline.workflow.identity import f_key

    study = parse_workflow(_grid_scene(160))
    cells = {(f_key(p.f), "rest", p.grid): Cell(p.f, "rest", 8, 5.0, 1000 * (1 + i), 0.01)
             for i, p in enumerate(study.points)}
    assert pilot.pilot_share(study, Rates(cells, scales=(("alpha", 0.5, 0.7),))) == (
        pytest.approx(0.05))


@pytest.mark.parametrize("n_particles, every", [(256, True), (32, False)])
def test_auto_pilots_every_line_of_a_map_when_that_is_cheap(n_particles, every, tmp_path):
    """2 pilot particles per point: 0.8 % of 256 particles -> every line is piloted; 6.25 % of
    32 -> the probe lines only, the others interpolated (and the plan says why)."""
    study = parse_workflow(_grid_scene(n_particles))
    rates = pilot.pilot_rates(study, particles=2, cache_dir=tmp_path)
    lines = {k[2] for k in rates.cells}
    assert (len(lines) == 5) == every and len(lines) >= 3
    assert ("every line of the grid (5)" in rates.source) == every
    assert ("would cost 6%" in rates.source) == (not every)


def test_the_docs_quote_the_plans_settings():
    """docs/maps.md and docs/accuracy.md state the share below which every line is piloted
    and the fewest cells a line's CI law is pooled from, pipeline/README.md the most of a run
    a pilot simulates: the code's values."""
    from pathlib import Path

    from pipeline.execute.plan import POOL_MIN

    docs = Path(__file__).resolve().parents[3] / "docs"
    assert f"at most {100 * pilot.PILOT_SHARE:g} % of the run" in (docs / "maps.md").read_text()
    assert f"fewer than {POOL_MIN})" in (docs / "accuracy.md").read_text()
    readme = (docs.parent / "pipeline" / "README.md").read_text()
    assert (f"at most {100 * pilot.PILOT_MAX_SHARE:g} % of the run ({pilot.PILOT_PARTICLES} "
            f"particles per point, fewer below {pilot.PILOT_PARTICLES / pilot.PILOT_MAX_SHARE:g})"
            in readme)
    assert f"fewer than {1 / pilot.PILOT_MAX_SHARE:g} particles per point" in readme


def test_a_scene_with_a_ci_target_pilots_more_particles_than_a_fixed_size_one():
    """A target's cost is the particles' spread of D, which a small pilot under-reads."""
    from pipeline.workflow.scenes import load_scene

    assert pilot.pilot_particles(load_scene("dissipation_r25")) == pilot.PILOT_PARTICLES_TARGET
    assert pilot.pilot_particles(load_scene("protocol")) == pilot.PILOT_PARTICLES
    assert pilot.PILOT_PARTICLES_TARGET > pilot.PILOT_PARTICLES


@pytest.mark.parametrize("n_particles, expected", [(2, 0), (3, 0), (4, 1), (8, 2), (16, 4),
                                                   (31, 7), (32, 8), (512, 8)])
def test_a_fixed_size_pilot_simulates_at_most_a_quarter_of_its_run(n_particles, expected):
    """The pilot runs n particles at every (point, family) over the run's t_max: n / N of the
    run; the default is 8, shrunk to floor(N / 4), none below 4 particles."""
    study = parse_workflow(PLAN_TINY.replace("n_particles = 128", f"n_particles = {n_particles}")
                           .replace("chunk_size = 32", "chunk_size = 1"))
    n = pilot.pilot_particles(study)
    assert n == expected
    assert n / n_particles <= pilot.PILOT_MAX_SHARE
    assert (pilot.cheaper_than_pilot(study) is None) == (n >= 1)


def test_the_share_of_a_core_is_the_pilots_cpu_over_its_wall_time():
    """1 CPU-s in 4 s of wall: a quarter of a core."""
    assert pilot.machine_share(busy=(1.0, 4.0)).share == pytest.approx(0.25)


def _plan(start_up=4.0, makespan=6.0, workers=2):
    from types import SimpleNamespace

    return SimpleNamespace(wall_s=start_up + makespan, makespan=makespan, workers=workers,
                           overheads=SimpleNamespace(start_up=start_up))


def test_sessions_shared_fairly_give_the_runs_workers_together_the_pilots_share():
    """Autogroup: one process got 0.25 of a core, so the run's session gets 0.25 cores in all:
    start-up 4 s / 0.25 = 16 s, 2 workers x 6 s of tasks / 0.25 = 48 s: 64 s."""
    from pipeline.execute.machine_load import MachineShare, loaded_wall

    assert loaded_wall(_plan(), MachineShare(0.25, 9.0, True), 2).endswith("-> wall 64 s (1.1 min)")


def test_processes_shared_fairly_give_each_worker_its_own_share():
    """Per process: 0.25 of a core = 2 / (others + 1), 7 others; each of 2 workers gets
    2 / 9 of a core: the plan's 10 s x 4.5 = 45 s."""
    from pipeline.execute.machine_load import MachineShare, loaded_wall

    line = loaded_wall(_plan(), MachineShare(0.25, 9.0, False), 2)
    assert "7.0 runnable processes of others" in line and line.endswith("-> wall 45 s (0.8 min)")


def test_a_whole_core_counts_the_others_from_the_load_average():
    """One process got a whole core: the load average 1.6 less this process, 0.6 others, each
    of 2 workers 2 / 2.6 of a core: 10 s x 1.3 = 13 s; no others: the plan's own 10 s."""
    from pipeline.execute.machine_load import MachineShare, loaded_wall

    assert loaded_wall(_plan(), MachineShare(1.0, 1.6, True), 2).endswith("-> wall 13 s (0.2 min)")
    assert loaded_wall(_plan(), MachineShare(1.0, 0.5, True), 2).endswith("-> wall 10 s (0.2 min)")


def test_each_pilot_line_is_printed_once_naming_its_grid_line(tmp_path, monkeypatch, capsys):
    """A map of 2 contact models: 2 pilot lines on stderr, each naming its model, none twice;
    a second plan reads the cache and pilots nothing."""
    from pipeline.cli import main

    monkeypatch.chdir(tmp_path)
    wf = tmp_path / "m.toml"
    wf.write_text(PLAN_TINY.replace("values = [54.0, 55.0, 60.0, 72.0]", "values = [60.0]")
                  .replace("t_max = 30.0", "t_max = 10.0").replace("n_particles = 128", "n_particles = 8")
                  .replace("chunk_size = 32", "chunk_size = 8")
                  .replace("[families.rest]", '[grid]\ncontact = ["stick", "slide"]\n\n[families.rest]'))
    assert main(["plan", str(wf), "--workers", "2"]) == 0
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ": pilot of " in ln]
    assert len(lines) == len(set(lines)) == 2
    assert [("contact=stick" in ln, "contact=slide" in ln) for ln in lines] == [(1, 0), (0, 1)]
    assert main(["plan", str(wf), "--workers", "2"]) == 0
    assert ": pilot of " not in capsys.readouterr().err
