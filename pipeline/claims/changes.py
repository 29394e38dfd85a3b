"""What a new REPORT.md changed: the claim verdicts that differ from the last complete report.

The report compared with is the last *complete* one committed (:func:`previous_report`): the
newest version of ``figures/REPORT.md`` in the git history that is not a draft and holds every
claims section the studies write now (a partial regeneration on a branch is skipped); outside a
git checkout, or for another output folder, the REPORT.md about to be overwritten.  Once the
new report is written, :data:`HEADING` lists every claim whose verdict changed (old → new, with
the rule it is judged by now), the claims that are new -- with their registration and the id
whose rule or scope they change -- and those gone.  Why a verdict changed is the business of
the claim's own row (its rule, its notes) and of CHANGELOG.md; this section makes sure no
change goes unnoticed by a reader of the report.
"""

from __future__ import annotations

import os
import re
import subprocess
from collections.abc import Sequence
from pathlib import Path

__all__ = ["HEADING", "verdicts", "changes_section", "is_complete", "previous_report"]

HEADING = "## Verdicts changed since the previous report"
# a claims-table row: | <id> | claim | measured | **verdict** | judged by | notes |
_ROW = re.compile(r"^\| ([A-Z]?\d+[a-z]?) \| (.*?) \| .*? \| \*\*(.+?)\*\* \| (.*?) \|")
_REGISTERED = re.compile(r"\(registered ([^;)]*)(?:; supersedes ([A-Z]?\d+[a-z]?))?\)$")


def verdicts(report: str) -> dict[str, tuple[str, str, str]]:
    """{claim id ("5", "M1", "T3"): (claim text, verdict, judged by)} of a REPORT.md text (its
    claims tables, not its own section of changes)."""
    out = {}
    for line in report.split(HEADING, 1)[0].splitlines():
        m = _ROW.match(line)
        if m:
            out[m.group(1)] = (m.group(2), m.group(3), m.group(4))
    return out


def _key(cid: str) -> tuple:
    m = re.match(r"([A-Z]?)(\d+)([a-z]?)$", cid)
    return (m.group(1), int(m.group(2)), m.group(3)) if m else (cid, 0, "")


def is_complete(report: str, headings: Sequence[str]) -> bool:
    """Whether a REPORT.md text is a complete report: written by a whole make_figures run (not a
    draft, not claims sections regenerated from its tables), and every claims section heading
    of ``headings`` is there (compared up to its first ':' or '(')."""
    first = report.split("\n## ", 1)[0]
    if "--fast" in first or "draft accuracy" in first:
        return False
    if "Claims sections regenerated" in first:  # from the tables of a run: compare with that run's
        return False
    have = {re.split(r"[:(]", h, maxsplit=1)[0].strip() for h in report.splitlines() if h.startswith("## ")}
    return all(re.split(r"[:(]", h, maxsplit=1)[0].strip() in have for h in headings)


def _git(root: Path, *args: str) -> str | None:
    try:
        r = subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True,
                           timeout=60, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    return r.stdout if r.returncode == 0 else None


def previous_report(out_dir: str | os.PathLike, root: str | os.PathLike,
                    headings: Sequence[str]) -> tuple[str | None, str]:
    """(text, where from) of the report a new ``<out_dir>/REPORT.md`` is compared with: for
    the repository's ``figures/``, the newest committed version that :func:`is_complete` over
    the sections some committed report holds (a study whose section no committed report has yet
    is new, and does not make every older report partial); else (or without git) the
    REPORT.md in ``out_dir``."""
    out, root = Path(out_dir).resolve(), Path(root).resolve()
    if out == root / "figures":
        log = _git(root, "log", "--format=%H %h", "--", "figures/REPORT.md")
        texts = [(short, _git(root, "show", f"{full}:figures/REPORT.md"))
                 for full, short in (line.split() for line in (log or "").splitlines())]
        texts = [(short, text) for short, text in texts if text]
        # a section no committed report holds is a new study's: not required of the old ones
        required = [h for h in headings if any(is_complete(t, [h]) for _, t in texts)]
        for short, text in texts:
            if is_complete(text, required):
                return text, f"the last complete committed report, commit {short}"
    path = out / "REPORT.md"
    if path.is_file():
        return path.read_text(encoding="utf-8"), "the report this one replaced"
    return None, ""


def _short(text: str, n: int = 90) -> str:
    return text if len(text) <= n else text[: n - 1].rstrip() + "…"


def _registration(text: str) -> tuple[str, str]:
    """(claim text without its registration, "registered …; supersedes …")."""
    m = _REGISTERED.search(text)
    if not m:
        return text, ""
    reg = m.group(1) + (f"; supersedes {m.group(2)}" if m.group(2) else "")
    return text[:m.start()].rstrip(), reg


def changes_section(old: str | None, new: str, previous_written: str | None = None,
                    against: str = "the report this one replaced") -> list[str]:
    """The lines of :data:`HEADING` comparing the verdicts of ``old`` (the earlier report's
    text, ``against`` saying which; None: there was none) with ``new``'s."""
    when = f" (written {previous_written})" if previous_written else ""
    L = ["", HEADING, ""]
    if old is None:
        return L + ["No earlier report in this folder to compare with."]
    a, b = verdicts(old), verdicts(new)
    rows = []
    for cid in sorted(set(a) | set(b), key=_key):
        if cid not in a:
            text, reg = _registration(b[cid][0])
            rows.append(f"| {cid} | {_short(text)} | (new claim{', registered ' + reg if reg else ''}) "
                        f"| **{b[cid][1]}** | {_short(b[cid][2], 120)} |")
        elif cid not in b:
            rows.append(f"| {cid} | {_short(a[cid][0])} | **{a[cid][1]}** | (claim removed) | |")
        elif a[cid][1] != b[cid][1] or _registration(a[cid][0])[0] != _registration(b[cid][0])[0]:
            rows.append(f"| {cid} | {_short(b[cid][0])} | **{a[cid][1]}** | **{b[cid][1]}** | "
                        f"{_short(b[cid][2], 120)} |")
    if not rows:
        return L + [f"Every claim's verdict is the one of {against}{when}."]
    return L + [f"Against {against}{when}: claims whose verdict (or wording) changed, the "
                "claims registered since (a changed rule or scope is a new id beside the old "
                "one), and the rule each is judged by now (its row above gives the numbers).",
                "", "| # | claim (now) | before | now | judged by (now) |",
                "| --- | --- | --- | --- | --- |"] + rows
