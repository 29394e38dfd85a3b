"""Claims as markdown: the claims table of a REPORT section (one row per judged claim) and a
safe table cell.  Generic: a study's report builds its sections from these."""

from __future__ import annotations

from collections.abc import Sequence

from .claim import Row

__all__ = ["markdown_table", "md_cell"]


def md_cell(text) -> str:
    """One markdown table cell: a '|' in the text would end the cell, a newline the row."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def markdown_table(rows: Sequence[Row], prefix: str = "", claim_header: str = "claim"
                   ) -> list[str]:
    """The claims table of a REPORT section: header lines and one row per claim, under its
    registered id, else numbered ``prefix`` + 1, 2, ... (e.g. "M1")."""
    L = [f"| # | {claim_header} | we measured | verdict | judged by | notes |",
         "| --- | --- | --- | --- | --- | --- |"]
    for i, r in enumerate(rows, 1):
        cid = r.id or f"{prefix}{i}"
        L.append(f"| {cid} | {md_cell(r.claim)} | {md_cell(r.measured)} | **{r.verdict}** | "
                 f"{md_cell(r.judged_by)} | {md_cell(r.note)} |")
    return L
