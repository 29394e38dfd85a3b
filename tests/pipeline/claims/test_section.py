"""A study's REPORT section from its records: each layout shows every record's verdict where it
belongs, the words are filled from the facts (a fact they name and nobody gives is an error),
and a layout that does not exist is refused."""

from __future__ import annotations

import pytest

from pipeline.claims.claim import Row
from pipeline.claims.section import Section, section_lines

ROWS = [Row("A holds", "a = 1", "agrees", id="X1"), Row("B holds", "b = 2", "disagrees", id="X2")]


def test_the_table_layout_has_one_row_per_record_under_its_id_and_counts_the_verdicts():
    lines = section_lines(Section("Study", "{n} points.", summary=True), {None: ROWS}, {"n": 7})
    assert lines[:4] == ["", "## Study", "", "7 points."]
    assert [ln.split(" | ")[0] for ln in lines if ln.startswith("| X")] == ["| X1", "| X2"]
    assert "| **disagrees** |" in next(ln for ln in lines if ln.startswith("| X2"))
    assert lines[-1] == "Summary: **agrees** 1 (#X1); **disagrees** 1 (#X2)."


def test_the_by_claim_layout_puts_each_lines_verdict_in_its_column():
    other = [Row("A holds", "a = 3", "partly", id="X1"), Row("B holds", "b = 4", "agrees", id="X2")]
    lines = section_lines(Section("S", layout="by claim", lead="Measured:"),
                          {"left": ROWS, "right": other}, labels=("A", "B"))
    assert "| claim | left | right |" in lines
    assert "| A | agrees | partly |" in lines and "| B | disagrees | agrees |" in lines
    assert "- B: **left**: b = 2; **right**: b = 4" in lines


def test_the_by_line_layout_has_a_row_per_line_and_a_cell_per_claim():
    lines = section_lines(Section("S", layout="by line", claim_header="protocol"),
                          {"p1": ROWS}, labels=("A", "B"))
    assert "| protocol | A | B |" in lines
    assert "| p1 | **agrees**: a = 1 | **disagrees**: b = 2 |" in lines
    one = section_lines(Section("S", layout="by line", claim_header="protocol"), {"p1": ROWS[1:]})
    assert "| p1 | **disagrees** | b = 2 |" in one


def test_words_naming_a_fact_nobody_gives_are_an_error_that_names_it():
    with pytest.raises(KeyError, match="points"):
        section_lines(Section("S", "{points} points."), {None: ROWS}, {"lines": 3})


def test_a_layout_that_does_not_exist_is_refused():
    with pytest.raises(ValueError, match="table, by claim, by line"):
        Section("S", layout="matrix")
