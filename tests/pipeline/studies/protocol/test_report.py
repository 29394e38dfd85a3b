"""The protocol section: verdict tables and a paragraph whose names and numbers come from
the tables."""

from __future__ import annotations

from pipeline.studies.protocol import STUDY
from pipeline.studies.protocol.claims import verdicts_table
from pipeline.studies.protocol.report import paragraph
from pipeline.studies.protocol.tables import protocol_name

from .synthetic import curves


def report_lines(tables):
    """The study's REPORT.md section from its tables."""
    return STUDY.report(tables)


def test_the_paragraph_names_the_reproducing_protocol():
    c = curves()
    text = paragraph(verdicts_table(c), c)
    assert protocol_name("launched", 10.0, "displaced") in text
    assert "counts only moving particles" in text and "starts from launched" in text


def test_the_paragraph_says_none_when_none_does():
    c = curves(good=None)
    assert paragraph(verdicts_table(c), c).startswith("None of the ")


def test_numbers_are_read_from_the_table():
    c = curves()
    sel = (c["ensemble"] == "mixture") & (c["definition"] == "displaced") & (c["f"] == 54.0) \
        & (c["T"] == 5.0)
    c.loc[sel, "share"] = 0.123
    text = paragraph(verdicts_table(c), c)
    assert "50 %, 12 %, 50 % at 50, 54, 58 Hz for T = 5 s" in text


def test_the_section_has_a_row_per_protocol_and_per_families_line():
    c = curves()
    v = verdicts_table(c)
    lines = report_lines({"protocol_verdicts": v, "protocol_curves": c})
    assert lines[1].startswith("## Protocol")
    n_protocols = v[v["claim"].astype(str) != "16"]["protocol"].nunique()
    rows = [x for x in lines if x.startswith("| ") and not x.startswith(("| protocol", "| ---"))]
    assert len(rows) == n_protocols + 2 * 3  # + claim 16 per (T, definition)
    assert report_lines({})[-2].startswith("Not measured")
