"""docs/accuracy.md quotes the stopping rule with Fig. 2's numbers: they are its scene's."""

from __future__ import annotations

from pathlib import Path

from pipeline.workflow.load import load_workflow

ROOT = Path(__file__).resolve().parents[1]


def test_the_stopping_rules_fig2_numbers_are_its_scenes():
    acc = load_workflow(ROOT / "workflows" / "figure2.toml").accuracy
    page = (ROOT / "docs" / "accuracy.md").read_text(encoding="utf-8")
    rule = " ".join(page.split("The\nrule (`decide` in `pipeline/execute/adaptive.py`)", 1)[1]
                    .split("(*cap*)", 1)[0].split())
    quoted = (f"{100 * acc.target_ci:g} % and {acc.d_resolved:g} mm²/s, stops so any D below "
              f"{acc.d_resolved:g} / {acc.target_ci:g} = {acc.d_resolved / acc.target_ci:.0f} mm²/s")
    assert quoted in rule, quoted
