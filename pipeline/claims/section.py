"""A study's REPORT.md section made from its claim records and a short template of its own words.

A :class:`Section` is what a study writes itself: its heading, a paragraph of its own words (a
``str.format`` template over the facts the study reads off its tables), and how its verdicts
are laid out.  :func:`section_lines` does the rest, the same way for every study:

* ``layout="table"``: one row per judged claim (:func:`~.markdown.markdown_table`: id, claim,
  measured, verdict, judged by, notes), and the summary line of the verdicts if ``summary``;
* ``layout="by claim"``: the claims judged on several lines (a contact model, a protocol):
  one row per claim, a verdict column per line, then what was measured, per claim and line;
* ``layout="by line"``: the same records the other way round, one row per line, a
  "**verdict**: measured" cell per claim (or the columns verdict and measured for one claim).

Verdicts come in as {line: rows} (one line, ``None``, for a study judged once); a study's
further lines (a table that is not a claim, a paragraph generated from its tables) follow the
verdicts.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from .claim import Row
from .markdown import markdown_table, md_cell

__all__ = ["LAYOUTS", "Section", "section_lines", "verdict_lines", "summary_line"]

LAYOUTS = ("table", "by claim", "by line")


@dataclass(frozen=True)
class Section:
    """A study's REPORT.md section as a template.

    heading -- the section's '## ' heading (without the '## ')
    words   -- the study's own paragraph under it: a ``str.format`` template over the facts
               the study reads off its tables (``{points}``), "" for none
    layout  -- how the verdicts are laid out (:data:`LAYOUTS`)
    prefix  -- the numbering of claims without a registered id ("M": M1, M2, ...)
    claim_header -- the header of the claim column ("the paper says")
    summary -- a line counting the verdicts ('Summary: **agrees** 13 (#5, …); …')
    lead    -- ``by claim``: the line under the verdicts that introduces what was measured
    """

    heading: str
    words: str = ""
    layout: str = "table"
    prefix: str = ""
    claim_header: str = "claim"
    summary: bool = False
    lead: str = "Measured:"

    def __post_init__(self):
        if self.layout not in LAYOUTS:
            raise ValueError(f"Section {self.heading!r}: layout {self.layout!r} is not one of "
                             f"{', '.join(LAYOUTS)}")


def summary_line(rows: Sequence[Row]) -> str:
    """'Summary: **agrees** 13 (#5, …); …' of a claims table, by registered id."""
    by: dict[str, list[str]] = {}
    for i, r in enumerate(rows, 1):
        by.setdefault(r.verdict, []).append(r.id or str(i))
    return "Summary: " + "; ".join(f"**{v}** {len(n)} (#{', #'.join(n)})"
                                   for v, n in by.items()) + "."


def _by_claim(section: Section, verdicts: Mapping[str | None, Sequence[Row]],
              labels: Sequence[str] = ()) -> list[str]:
    lines = list(verdicts)
    first = verdicts[lines[0]]
    names = list(labels) or [r.claim for r in first]
    L = [f"| {section.claim_header} | " + " | ".join(md_cell(n) for n in lines) + " |",
         "| --- |" + " --- |" * len(lines)]
    for i, name in enumerate(names):
        L.append(f"| {md_cell(name)} | " + " | ".join(verdicts[n][i].verdict for n in lines)
                 + " |")
    L += ["", section.lead, ""]
    for i, name in enumerate(names):
        L.append(f"- {name}: " + "; ".join(f"**{n}**: {verdicts[n][i].measured}" for n in lines))
    return L


def _by_line(section: Section, verdicts: Mapping[str | None, Sequence[Row]],
             labels: Sequence[str] = ()) -> list[str]:
    first = next(iter(verdicts.values()))
    names = list(labels) or [r.claim for r in first]
    if len(names) == 1:
        L = [f"| {section.claim_header} | verdict | measured |", "| --- | --- | --- |"]
        L += [f"| {md_cell(n)} | **{rs[0].verdict}** | {md_cell(rs[0].measured)} |"
              for n, rs in verdicts.items()]
        return L
    L = [f"| {section.claim_header} | " + " | ".join(md_cell(n) for n in names) + " |",
         "| --- |" + " --- |" * len(names)]
    for n, rs in verdicts.items():
        L.append(f"| {md_cell(n)} | " + " | ".join(f"**{r.verdict}**: {md_cell(r.measured)}"
                                                    for r in rs) + " |")
    return L


def verdict_lines(section: Section, verdicts: Mapping[str | None, Sequence[Row]],
                  labels: Sequence[str] = ()) -> list[str]:
    """The verdicts laid out as ``section.layout`` says (no heading, no words): for a second
    table of records in a section (``further``)."""
    if section.layout == "table":
        rows = [r for rs in verdicts.values() for r in rs]
        L = markdown_table(rows, prefix=section.prefix, claim_header=section.claim_header)
        return L + (["", summary_line(rows)] if section.summary else [])
    if not verdicts:
        return []
    return (_by_claim if section.layout == "by claim" else _by_line)(section, verdicts, labels)


def section_lines(section: Section, verdicts: Mapping[str | None, Sequence[Row]],
                  facts: Mapping[str, object] | None = None, further: Sequence[str] = (),
                  labels: Sequence[str] = ()) -> list[str]:
    """The section's lines: a blank line, the heading, the study's words (formatted with
    ``facts``), its verdicts laid out as ``section.layout`` says, and ``further`` lines.

    verdicts -- {line: the rows judged on it}; {None: rows} for a study judged once
    labels   -- the claims' names in the ``by claim``/``by line`` layouts (default: their text)
    """
    L = ["", f"## {section.heading}", ""]
    if section.words:
        try:
            L += [section.words.format(**(facts or {})), ""]
        except KeyError as e:
            raise KeyError(f"section {section.heading!r}: its words name {e}, which its facts "
                           "do not give") from None
    return L + verdict_lines(section, verdicts, labels) + list(further)
