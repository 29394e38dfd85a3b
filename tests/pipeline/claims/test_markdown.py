"""The generic claims table (pipeline/claims/markdown.py) as REPORT.md sections print it."""

from __future__ import annotations

import re

from pipeline.claims.claim import Row
from pipeline.claims.markdown import markdown_table


def _cells(line: str) -> list[str]:
    # split on the '|' that are not escaped: what a markdown renderer does
    return [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]


def test_a_claim_whose_text_holds_a_pipe_or_a_newline_stays_one_six_column_row():
    row = Row(claim="no current", measured="max |v| = 2.34 mm/s\nat 84 Hz", verdict="disagrees",
              note="a | b", judged_by="0 ± 0")
    header, rule, line = markdown_table([row], prefix="T")
    assert len(_cells(header)) == len(_cells(rule)) == 6
    assert _cells(line) == ["T1", "no current", r"max \|v\| = 2.34 mm/s at 84 Hz", "**disagrees**",
                            "0 ± 0", r"a \| b"]
