"""docs/reproducing.md: what `make figures` computes, the two commands' run times and the maps'
costs, every number read from a results file or the committed run log, not typed."""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
PAGE_TEXT = (ROOT / "docs" / "reproducing.md").read_text(encoding="utf-8")


def test_the_pages_map_numbers_are_the_committed_benchmarks():
    """The numbers quoted under "Maps at scale" are read off the results files, not typed."""
    results = ROOT / "benchmarks" / "results"
    scale = (results / "maps-scale-2026-11-25.txt").read_text(encoding="utf-8")
    plan = (results / "maps-plan-2026-11-25.txt").read_text(encoding="utf-8")
    text = PAGE_TEXT.split("Maps at scale", 1)[1].split("\n\n", 1)[0]

    def cell(table: str, row: str, col: int) -> str:
        line = next(ln for ln in table.splitlines() if ln.startswith(f"| {row}"))
        return line.split("|")[col].strip()

    quoted = [cell(scale, "task graph built", 2), cell(scale, "open_study", 2),
              cell(scale, "compute wall", 4), cell(plan, "CPU in tasks, s (probes)", 4),
              cell(plan, "CPU in tasks, s (all)", 4)]
    assert re.findall(r"\d+\.\d+", text) == quoted


MAP_COSTS = ROOT / "benchmarks" / "results" / "map-costs-2026-11-28-default.md"


def test_the_pages_map_costs_are_the_committed_results():
    """The maps' planned and measured costs are copied from their results file, row by row."""
    rows = [ln for ln in MAP_COSTS.read_text(encoding="utf-8").splitlines() if ln.startswith("|")]
    assert len(rows) >= 4
    shown = PAGE_TEXT.split("<!-- map costs:", 1)[1].split("\n\n", 1)[0].splitlines()[1:]
    assert shown == rows
    assert MAP_COSTS.name in PAGE_TEXT.split("<!-- map costs:", 1)[1].splitlines()[0]


def _cells(line: str) -> list[str]:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def _ratios(cell: str) -> list[str]:
    """The measured / planned ratios of a cell: "1523 / 1616 (1.06)" -> ["1.06"]."""
    return re.findall(r"\((\d+\.\d+)\)", cell)


def _after_map_costs() -> str:
    """The paragraph under the PAGE_TEXT's map-costs table, its lines joined."""
    return " ".join(PAGE_TEXT.split("<!-- map costs:", 1)[1].split("\n\n", 2)[1].split())


def test_every_maps_default_plan_is_within_30_percent_at_its_listed_points():
    """The page says so: every ratio measured / planned of the default plans' rows, at the
    points the scene lists (chunks, collisions, CPU-s)."""
    rows = [_cells(ln) for ln in MAP_COSTS.read_text(encoding="utf-8").splitlines()
            if ln.startswith("| `") and "not the default" not in ln]
    ratios = [float(r) for cells in rows for c in cells[2:5] for r in _ratios(c)]
    assert len(rows) == 5 and len(ratios) == 15
    assert all(0.7 <= r <= 1.3 for r in ratios), ratios
    assert "At the points a scene lists, every map's default plan came within ±30 %" in _after_map_costs()


def test_the_pages_refinement_and_hold_out_costs_are_the_committed_results():
    """What refinement cost the D(f, α) map, and the refined hold-out map's plan against its
    run, are read from their results files."""
    row = next(_cells(ln) for ln in MAP_COSTS.read_text(encoding="utf-8").splitlines()
               if ln.startswith("| `dissipation` (every line piloted) (16 pilot particles)"))
    listed = int(row[2].split("/")[1].split("(")[0])
    points, chunks = re.findall(r"(\d+) points, (\d+) chunks", row[6])[0]
    whole = re.findall(r"= (\d+\.\d+) x", row[6])
    holdout = (ROOT / "benchmarks" / "results" / "plan-holdout-map-2026-11-28.txt").read_text(
        encoding="utf-8")
    h = _cells(next(ln for ln in holdout.splitlines() if ln.startswith("| `plan_holdout_map`")))
    (h_chunks, h_coll, h_cpu), (all_points, listed_points) = map(_ratios, h[2:5]), re.findall(r"\d+", h[1])
    added = int(all_points) - int(listed_points)
    text = _after_map_costs()
    for quoted in (f"refinement added {points} points and {chunks} chunks to its listed points' {listed}",
                   f"whole map cost {whole[0]} × the planned chunks and {whole[1]} × the planned collisions",
                   f"cost {h_chunks[0]} × the planned chunks and {h_coll[0]} × the planned collisions",
                   f"{h_chunks[1]} × and {h_coll[1]} × with refinement's {added} points",
                   f"CPU-s {h_cpu[0]} × the plan's"):
        assert quoted in text, quoted


def _prose(section: str) -> str:
    """The first paragraph under a PAGE_TEXT heading, its lines joined."""
    return " ".join(PAGE_TEXT.split(section, 1)[1].strip().split("\n\n", 1)[0].split())


def test_the_pages_stopping_rule_is_figure2s_scene_and_its_table():
    """The rule's numbers are the scene's; the rows the resolution stopped above D ~ 0 are
    counted from the committed Fig. 2 table."""
    from pipeline.store.layout import STOP_LEGEND, TARGET, ZERO
    from pipeline.workflow.load import load_workflow

    study = load_workflow(ROOT / "workflows" / "figure2.toml")
    acc = study.accuracy
    text = _prose("## What `make figures` computes")
    table = pd.read_csv(ROOT / "figures" / "diffusion_figure2.csv")
    above = table[(table["stop"] == STOP_LEGEND[ZERO]) & (table["D"] > acc.d_resolved)]
    rel = ((above["D_hi"] - above["D_lo"]) / 2 / above["D"]).max()
    for quoted in (f"{len(study.points)} frequencies", f"≤ {100 * acc.target_ci:g} % of D",
                   f'("{STOP_LEGEND[TARGET]}") or ≤ {acc.d_resolved:g} mm²/s ("{STOP_LEGEND[ZERO]}")',
                   f"{acc.max_particles} particles", f"D < {acc.d_resolved / acc.target_ci:.0f} mm²/s",
                   f"{len(above)} frequencies of {above['f'].min():g}–{above['f'].max():g} Hz",
                   f"D of {above['D'].min():.0f}–{above['D'].max():.0f} mm²/s",
                   f"up to {100 * rel:.1f} % of D"):
        assert quoted in text, quoted


def test_the_pages_times_of_the_two_commands_are_read_from_results_files():
    """make test's time is its measured run; make figures' is the runs of the generated table,
    the D(f, α) map's measured wall time and the other separately run maps' measured CPU-s
    over 2 cores."""
    results = ROOT / "benchmarks" / "results"
    test_s = float(re.search(r"^make test: (\d+) s wall$",
                             (results / "make-test-2026-11-28.txt").read_text(encoding="utf-8"), re.M)[1])
    runs_s = float(re.search(r"\*\*all of the above\*\* \| \*\*[\d.]+ min \((\d+) s\)\*\*", PAGE_TEXT)[1])
    regen = (results / "dissipation-regeneration-2026-11-28.txt").read_text(encoding="utf-8")
    map_s = float(re.search(r"collisions in ([\d.]+) s wall", regen)[1])
    others = [_cells(ln) for ln in MAP_COSTS.read_text(encoding="utf-8").splitlines()
              if ln.startswith("| `") and not ln.startswith("| `dissipation` ")
              and "not the default" not in ln]
    cpu = sum(float(c[4].split("/")[1].split("(")[0]) for c in others)
    total_h = (runs_s + map_s + cpu / 2) / 3600
    block = PAGE_TEXT.split("## The two commands", 1)[1].split("```", 2)[1]
    assert f"test suite: {test_s / 60:.1f} min on 2 cores (measured: below)" in block
    assert f"about {total_h:.1f} h on 2 cores from nothing (measured: below)" in block
    text = " ".join(PAGE_TEXT.split("<!-- times:", 1)[1].split("\n\n", 1)[0].split())
    words = dict(enumerate(("none", "one", "two", "three", "four", "five", "six", "seven")))
    for quoted in (f"`make test` took {test_s / 60:.1f} min ({test_s:.0f} s:",
                   f"`make figures` about {total_h:.1f} h: the runs above, {runs_s / 60:.1f} min",
                   f"the {words[len(others) + 1]} maps", f"the D(f, α) map {map_s / 60:.1f} min",
                   f"the other {words[len(others)]} {cpu:.0f} CPU-s, {cpu / 2 / 60:.1f} min over 2 cores"):
        assert quoted in text, quoted
