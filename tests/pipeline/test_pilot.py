"""The pilot of `bbb plan`: exact collisions, and a short pilot's timing taken at its fastest."""

from __future__ import annotations

import pipeline.pilot as pilot
from pipeline.workflow import parse_workflow

from .test_plan import PLAN_TINY


def test_a_short_pilot_keeps_each_cells_fastest_timing_and_its_exact_collisions(monkeypatch):
    """A pilot under TIMING_FLOOR_S of CPU is timed again: each cell's cpu_s is the least of
    its timings (a slow first one, inflated here by 0.3 s at 54 Hz, is dropped), the timings
    add up to the floor, and the collisions and D are those of the first pilot run."""
    study = parse_workflow(PLAN_TINY)
    first, repeats = {}, {}
    real_cell, real_cpu = pilot._pilot_cell, pilot._pilot_cpu

    def slow_first(study, f, fam, n):
        cell = real_cell(study, f, fam, n)
        cell = pilot.replace(cell, cpu_s=cell.cpu_s + 0.3 * (f == 54.0))
        first[f] = cell
        return cell

    def recorded(study, f, fam, n):
        cpu = real_cpu(study, f, fam, n)
        repeats.setdefault(f, []).append(cpu)
        return cpu

    monkeypatch.setattr(pilot, "_pilot_cell", slow_first)
    monkeypatch.setattr(pilot, "_pilot_cpu", recorded)
    rates = pilot.pilot_rates(study, cache_dir=None)
    timed = sum(c.cpu_s for c in first.values()) + sum(map(sum, repeats.values()))
    assert timed >= pilot.TIMING_FLOOR_S
    for f in study.frequencies:
        cell = rates.cells[(round(f * 1000), "rest")]
        assert cell.cpu_s == min([first[f].cpu_s, *repeats[f]])
        assert (cell.collisions, cell.D) == (first[f].collisions, first[f].D)
    assert rates.cells[(54000, "rest")].cpu_s < first[54.0].cpu_s  # the slow one was dropped
