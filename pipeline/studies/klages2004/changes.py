"""What a new REPORT.md changed: the claim verdicts that differ from the report it replaces.

``make_figures`` reads the verdicts of the REPORT.md it is about to overwrite and, once the new
report is written, appends :data:`HEADING` listing every claim whose verdict changed (old →
new, with the rule it is judged by now) and the claims that are new or gone.  Why a verdict
changed is the business of the claim's own row (its rule, its notes) and of CHANGELOG.md;
this section makes sure no change goes unnoticed by a reader of the report.
"""

from __future__ import annotations

import re

__all__ = ["HEADING", "verdicts", "changes_section"]

HEADING = "## Verdicts changed since the previous report"
# a claims-table row: | <id> | claim | measured | **verdict** | judged by | notes |
_ROW = re.compile(r"^\| ((?:[A-Z])?\d+) \| (.*?) \| .*? \| \*\*(.+?)\*\* \| (.*?) \|")


def verdicts(report: str) -> dict[str, tuple[str, str, str]]:
    """{claim id ("5", "M1", "T3"): (claim text, verdict, judged by)} of a REPORT.md text (its
    claims tables, not its own section of changes)."""
    out = {}
    for line in report.split(HEADING, 1)[0].splitlines():
        m = _ROW.match(line)
        if m:
            out[m.group(1)] = (m.group(2), m.group(3), m.group(4))
    return out


def _short(text: str, n: int = 90) -> str:
    return text if len(text) <= n else text[: n - 1].rstrip() + "…"


def changes_section(old: str | None, new: str, previous_written: str | None = None) -> list[str]:
    """The lines of :data:`HEADING` comparing the verdicts of ``old`` (the replaced report's
    text; None: there was none) with ``new``'s."""
    when = f" (written {previous_written})" if previous_written else ""
    L = ["", HEADING, ""]
    if old is None:
        return L + ["No earlier report in this folder to compare with."]
    a, b = verdicts(old), verdicts(new)
    rows = []
    for cid in sorted(set(a) | set(b), key=lambda k: (k.rstrip("0123456789"), int(re.sub(r"\D", "", k)))):
        if cid not in a:
            rows.append(f"| {cid} | {_short(b[cid][0])} | (new claim) | **{b[cid][1]}** | "
                        f"{_short(b[cid][2], 120)} |")
        elif cid not in b:
            rows.append(f"| {cid} | {_short(a[cid][0])} | **{a[cid][1]}** | (claim removed) | |")
        elif a[cid][1] != b[cid][1] or a[cid][0] != b[cid][0]:
            rows.append(f"| {cid} | {_short(b[cid][0])} | **{a[cid][1]}** | **{b[cid][1]}** | "
                        f"{_short(b[cid][2], 120)} |")
    if not rows:
        return L + [f"Every claim's verdict is the one of the previous report{when}."]
    return L + [f"Against the report this one replaced{when}: claims whose verdict (or wording) "
                "changed, and the rule each is judged by now (its row above gives the numbers).",
                "", "| # | claim (now) | before | now | judged by (now) |",
                "| --- | --- | --- | --- | --- |"] + rows
