"""docs/maps.md runs: its workflows are valid and have the points the page says."""

from __future__ import annotations

import re
from pathlib import Path

from pipeline.workflow.load import parse_workflow

PAGE = Path(__file__).resolve().parents[1] / "docs" / "maps.md"


def blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)


def test_the_alpha_map_has_nine_points_with_alpha_innermost_but_f():
    s = parse_workflow(blocks("toml")[0], source="maps.md")
    assert [(dict(p.grid)["alpha"], p.f) for p in s.points] == [
        (a, f) for a in (0.5, 0.6, 0.7) for f in (54.0, 60.0, 72.0)]


def test_the_contact_map_has_four_lines_at_the_peak_acceleration_it_names():
    s = parse_workflow(blocks("toml")[1], source="maps.md")
    assert len({p.grid for p in s.points}) == 4
    assert all(abs(p.params.gamma - 1.5) < 1e-12 for p in s.points)


def test_the_refinement_block_refines_the_alpha_map():
    s = parse_workflow(blocks("toml")[0] + "\n" + blocks("toml")[2], source="maps.md")
    assert s.grid_refine.to == (("f", 0.5), ("alpha", 0.025))
