"""The report's section of changed verdicts: every change is listed, and none is invented."""

from __future__ import annotations

import re
from pathlib import Path

from pipeline.claims.changes import HEADING, changes_section, verdicts

REPORT = Path(__file__).resolve().parents[3] / "figures" / "REPORT.md"


def _claim_rows(text: str) -> list[str]:
    """Rows of the numbered claims tables (before the section of changes, whose rows look
    alike): first cell an id (5, M1, T3), fourth a verdict."""
    return [line for line in text.split(HEADING, 1)[0].splitlines()
            if re.match(r"^\| [A-Z]?\d+[a-z]? \|", line) and " | **" in line]


def test_every_numbered_claim_row_of_the_committed_report_is_read():
    text = REPORT.read_text(encoding="utf-8")
    rows = _claim_rows(text)
    assert len(rows) >= 19
    assert len(verdicts(text)) == len(rows)


def test_a_changed_verdict_is_listed_with_its_old_and_new_value():
    text = REPORT.read_text(encoding="utf-8")
    cid, (claim, verdict, _) = next(iter(verdicts(text).items()))
    other = "agrees" if verdict != "agrees" else "disagrees"
    row = next(r for r in _claim_rows(text) if r.startswith(f"| {cid} |"))
    new = text.replace(row, row.replace(f"| **{verdict}** |", f"| **{other}** |", 1))
    lines = changes_section(text, new, "2026-01-01")
    assert HEADING in lines
    listed = [r for r in lines if r.startswith(f"| {cid} |")]
    assert listed and f"**{verdict}** | **{other}**" in listed[0]
    assert len([r for r in lines if re.match(r"^\| [A-Z]?\d+[a-z]? \|", r)]) == 1


def test_an_unchanged_report_lists_no_claim():
    text = REPORT.read_text(encoding="utf-8")
    lines = changes_section(text, text)
    assert not [r for r in lines if re.match(r"^\| [A-Z]?\d+[a-z]? \|", r)]
    assert any("is the one of the report this one replaced" in r for r in lines)


def test_a_claim_new_or_gone_is_listed_as_such():
    text = REPORT.read_text(encoding="utf-8")
    row = _claim_rows(text)[-1]
    lines = changes_section(text.replace(row + "\n", ""), text)
    assert any("(new claim" in r for r in lines)
    lines = changes_section(text, text.replace(row + "\n", ""))
    assert any("(claim removed)" in r for r in lines)


def test_the_rows_of_a_reports_own_section_of_changes_are_not_read_as_its_verdicts():
    text = REPORT.read_text(encoding="utf-8").split(HEADING, 1)[0]
    cid, (claim, verdict, _) = next(iter(verdicts(text).items()))
    other = "agrees" if verdict != "agrees" else "disagrees"
    # a section of changes whose row for cid matches the claims-table pattern
    fake = f"{HEADING}\n\n| {cid} | {claim} | **{other}** | **{other}** | x |\n"
    assert verdicts(text + fake)[cid][1] == verdict


def test_a_new_claim_is_listed_with_its_registration_and_the_id_it_supersedes():
    text = REPORT.read_text(encoding="utf-8")
    row = next(r for r in _claim_rows(text) if r.startswith("| T3b |"))
    lines = changes_section(text.replace(row + "\n", ""), text)
    listed = next(r for r in lines if r.startswith("| T3b |"))
    assert "registered 2026-11-25 1b0f70e; supersedes T3" in listed


def test_a_draft_or_a_report_without_a_claims_section_is_not_complete():
    from pipeline.claims.changes import is_complete

    text = REPORT.read_text(encoding="utf-8")
    headings = ["## Claims", "## Transport on a vibro-conveyor (scenes …)"]
    made = text.replace(next(line for line in text.splitlines()
                             if line.startswith("Claims sections regenerated")), "")
    assert is_complete(made, headings)
    assert not is_complete(text, headings)  # its claims sections regenerated from the tables
    text = made
    assert not is_complete(text.replace("## Transport on", "## Conveyors on"), headings)
    assert not is_complete(text.replace("make_figures`", "make_figures --fast`", 1), headings)


def _full_then_partial(tmp_path) -> None:
    """A git repository whose figures/REPORT.md was committed complete, then partial."""
    import subprocess

    def git(*a):
        subprocess.run(["git", "-C", str(tmp_path), *a], check=True, capture_output=True)
    git("init", "-q")
    git("config", "user.email", "t@t"), git("config", "user.name", "t")
    (tmp_path / "figures").mkdir()
    report = tmp_path / "figures" / "REPORT.md"
    for body in ("## Claims\nfull\n## Transport\nx\n", "## Claims\npartial\n"):
        report.write_text("# R\n\nWritten now by `python -m pipeline.make_figures`.\n" + body)
        git("add", "-A"), git("commit", "-qm", "r")


def test_the_previous_report_is_the_last_complete_committed_one(tmp_path):
    """In a repository whose newest committed report lacks a section, the one before it is
    the report compared with."""
    from pipeline.claims.changes import previous_report

    _full_then_partial(tmp_path)
    text, where = previous_report(tmp_path / "figures", tmp_path, ["## Claims", "## Transport"])
    assert "full" in text and "last complete committed report" in where


def test_a_new_studys_section_does_not_make_every_older_report_partial(tmp_path):
    """A section no committed report holds yet (a study added since) is not asked of the old
    reports: the last complete one is still found, and a partial one still skipped."""
    from pipeline.claims.changes import previous_report

    _full_then_partial(tmp_path)
    text, where = previous_report(tmp_path / "figures", tmp_path,
                                  ["## Claims", "## Transport", "## Impacts"])
    assert "full" in text and "last complete committed report" in where
