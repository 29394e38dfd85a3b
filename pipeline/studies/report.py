"""``figures/REPORT.md``: every registered study's section, the runs, the figures, and what
changed since the last complete report; and the command that regenerates the claims sections
from the committed tables alone::

    python -m pipeline.studies.report [--out DIR]

The report is the studies' sections in the registry's order (:mod:`pipeline.studies.registry`;
each section made by :meth:`~pipeline.studies.interface.Study.report` from the study's claim
records and its own words), then the parameters, the runs and the figures with their
captions, then the section of changes (:mod:`pipeline.claims.changes`).  Every measured number
is computed from the stores and from the tables *read back* from their committed CSVs, so the
claims sections are a function of committed files: the command rewrites them from those files,
and tests/pipeline/studies/test_report.py compares it with the committed REPORT.md.
"""

from __future__ import annotations

import datetime as _dt
import math
import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from ..claims.changes import HEADING, changes_section, previous_report
from ..claims.claim import Row
from ..claims.markdown import md_cell
from ..tables.collisions import as_store
from .interface import Study
from .registry import studies as registered

__all__ = ["TITLE", "COMMAND", "write_report", "claim_sections", "section_headings",
           "rewrite_claim_sections", "main"]

TITLE = "# Klages, Barna & Mátyás (2004): the claims beside our measurements"
#: the command that regenerates the claims sections from the committed tables
COMMAND = "python -m pipeline.studies.report"


def _scene_rows(stores: Mapping[str, str], run_log: Mapping | None) -> list[str]:
    lines = ["| scene | workflow | accuracy | particles × t_max | points × families | chunks "
             "done | task time (sum of chunk_seconds) | wall time of the run |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    total = 0.0
    for name, path in stores.items():
        try:
            st = as_store(path)
        except Exception as e:  # a store that cannot be opened is reported, not fatal
            lines.append(f"| {name} | – | – | – | – | – | – | cannot open: {md_cell(e)} |")
            continue
        g = st.group()
        secs = float(np.nansum(np.asarray(g["chunk_seconds"][...])))
        total += secs
        done = st.done()
        acc = st.study.accuracy
        log = (run_log or {}).get("scenes", {}).get(name, {})
        wall = (f"{log['wall_s']:.0f} s ({log.get('computed', 0)} chunks computed on "
                f"{log.get('workers', '?')} workers)" if "wall_s" in log else "–")
        if log.get("separate_run"):
            wall = (f"{log.get('wall_s', 0.0):.0f} s (its chunks computed by a separate "
                    "`bbb run`)")
        lines.append(f"| {name} | `{log.get('workflow', st.study.source)}` | {acc.preset} | "
                     f"{acc.n_particles} × {acc.t_max:g} s | {_points(st.study)} × "
                     f"{len(st.study.families)} | {int(done.sum())}/{done.size} | {secs:.0f} s | "
                     f"{wall} |")
    lines.append(f"\nTotal task time over all scenes: {total:.0f} s ≈ {total / 3600:.2f} core-hours.")
    return lines


def _points(study) -> str:
    """A scene's points as the runs table says them: "124" frequencies, or for a map
    "234 (26 f × 9 lines of tilt, throw)"."""
    if not study.grid:
        return f"{len(study.frequencies)}"
    lines = len({p.grid for p in study.points})
    axes = ", ".join(a for a, _ in study.grid)
    return (f"{len(study.points)} ({len(study.frequencies)} f × {lines} lines of {axes})")


def _params_lines(stores: Mapping[str, str], scene: str) -> list[str]:
    """The parameters of ``scene``'s store (else the first store), numerics, accuracy, version."""
    path = stores.get(scene) or next(iter(stores.values()), None)
    if path is None:
        return ["(no store)"]
    st = as_store(path)
    attrs = st.attrs()  # JSON-string attributes decoded
    p = attrs.get("params", {})
    lines = ["| quantity | value |", "| --- | --- |"]
    for k, unit in (("g", "mm/s²"), ("A", "mm"), ("R", "mm"), ("S", "mm"), ("alpha", ""),
                    ("beta", "")):
        if k in p:
            lines.append(f"| {k} | {p[k]:g} {unit} |")
    for k, v in attrs.get("numerics", {}).items():
        lines.append(f"| numerics.{k} | {v:g} |")
    lines.append(f"| accuracy preset (scene {scene}) | {attrs.get('accuracy', {}).get('preset')} |")
    lines.append(f"| bbb version | {attrs.get('bbb_version')} |")
    lines.append(f"| store created | {attrs.get('created')} |")
    A = p.get("A")
    g = p.get("g", 9800.0)
    lines += ["", (
        f"**Amplitude.** The paper prints A = 0.01 (units of 1 mm) with g = 9800 mm/s². With "
        "A = 0.01 the peak floor acceleration Γ = A(2πf)²/g stays below 0.41 for f ≤ 100 Hz and "
        "no particle ever leaves the floor (docs/amplitude.md). The paper's own landmarks — "
        "onset near 50 Hz, the 1/1 spot at v_y⁺ ≈ 100 near 54 Hz, the VHO at ≈ 70 near 60 Hz — "
        f"fit A = 0.1, which we use (A = {A:g} mm here; Γ = 1 at f = "
        f"{math.sqrt(g / A) / (2 * math.pi):.1f} Hz)." if A else "")]
    return lines



def _split(lines: Sequence[str]) -> dict[str, list[str]]:
    """{'## heading': the lines under it} of a study's section lines."""
    out: dict[str, list[str]] = {}
    heading = None
    for line in lines:
        if line.startswith("## "):
            heading = line
            out[heading] = []
        elif heading is not None:
            out[heading].append(line)
    return out


def section_headings(studies: Sequence[Study] | None = None) -> list[str]:
    """The '## ' heading of every study's section (its first), in order."""
    return [f"## {s.section.heading}" for s in (studies or registered())]


def write_report(out_dir: str | os.PathLike, *, stores: Mapping[str, str],
                 tables: Mapping[str, Mapping[str, pd.DataFrame]],
                 figures: Sequence[str | os.PathLike] = (), run_log: Mapping | None = None,
                 studies: Sequence[Study] | None = None) -> Path:
    """Write ``<out_dir>/REPORT.md`` and return its path (without the section of changes,
    which :func:`pipeline.make_figures.make_figures` appends).

    stores  -- scene name -> store path, every study's scenes
    tables  -- study name -> its tables, read back from their CSVs (any may be missing)
    figures -- paths of the figures drawn (listed with their studies' captions)
    run_log -- make_figures' log: per-scene wall time of this invocation, FAST flag
    """
    studies = list(studies or registered())
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fast = bool((run_log or {}).get("fast"))
    L = [TITLE, ""]
    L.append(f"Written {_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')} by "
             f"`python -m pipeline.make_figures{' --fast' if fast else ''}`"
             + (" — **draft accuracy (FAST): numbers are rough**" if fast else "") + ". "
             "Every measured number below is computed from the stores and tables; regenerate, "
             "do not edit.")
    if run_log and "wall_s" in run_log:
        L.append(f"\nWall time of the runs and reductions behind it: {run_log['wall_s']:.0f} s "
                 f"({run_log['wall_s'] / 60:.1f} min; per scene below).")
    for s in studies:
        L += s.report(tables.get(s.name, {}), stores)
    first = studies[0].scenes[0] if studies and studies[0].scenes else ""
    L += ["", "## Parameters actually used", ""] + _params_lines(stores, first)
    L += ["", "## Runs", ""] + _scene_rows(stores, run_log)
    if figures:
        captions = {k: v for s in studies for k, v in s.captions.items()}
        L += ["", "## Figures", ""]
        for p in figures:
            p = Path(p)
            if p.suffix == ".png":
                L.append(f"- [`{p.name}`]({p.name}) (and `.pdf`): {captions.get(p.stem, '')}")
    path = out / "REPORT.md"
    path.write_text("\n".join(L) + "\n", encoding="utf-8")
    return path


def _cells(row: str) -> list[str]:
    return [c.strip() for c in re.split(r"(?<!\\)\|", row.strip())[1:-1]]


def _kept(study: Study, report: str, verdicts):
    """``verdicts`` with what was measured for the study's claims that read a store
    (``needs_stores``: measured, verdict, notes) taken from ``report``, the report the stores
    wrote."""
    keep = {c.id for c in study.claims if c.quantity in study.needs_stores}
    if not keep:
        return verdicts
    old = {}
    for line in report.splitlines():
        if line.startswith("| ") and (c := _cells(line)) and c[0] in keep and len(c) == 6:
            old[c[0]] = Row(c[1].replace("\\|", "|"), c[2].replace("\\|", "|"),
                            c[3].strip("*"), c[5].replace("\\|", "|"),
                            c[4].replace("\\|", "|"), c[0])
    # the claim's text and rule are the code's; what was measured is the stores'
    return {line: [Row(r.claim, old[r.id].measured, old[r.id].verdict, old[r.id].note,
                       r.judged_by, r.id) if r.id in old else r for r in rows]
            for line, rows in verdicts.items()}


def claim_sections(out_dir: str | os.PathLike, stores: Mapping[str, str] | None = None,
                   report: str | None = None, studies: Sequence[Study] | None = None
                   ) -> dict[str, list[str]]:
    """{heading: lines} of every study's sections of REPORT.md, regenerated from the tables in
    ``out_dir``.  ``stores``: only claims that read a store (post-collision states) need them;
    without, their rows are taken from ``report`` when given, else 'not measured'."""
    sections: dict[str, list[str]] = {}
    for s in studies or registered():
        tables = s.read_tables(out_dir)
        verdicts = s.judge(tables, stores)
        if report is not None and not stores:
            verdicts = _kept(s, report, verdicts)
        sections.update(_split(s.report(tables, stores, verdicts)))
    return sections


def _replace_section(text: str, heading: str, lines: list[str]) -> str:
    """``text`` with the section under ``heading`` (up to the next '## ' heading) replaced by
    ``lines``; appended before the section of changes if it is not there."""
    body = "\n".join([heading, *lines]).rstrip("\n") + "\n\n"
    start = text.find(f"\n{heading}\n")
    if start < 0:
        at = text.find(f"\n{HEADING}")
        at = len(text) if at < 0 else at + 1
        return text[:at] + body + text[at:]
    start += 1
    end = text.find("\n## ", start + len(heading))
    end = len(text) if end < 0 else end + 1
    return text[:start] + body + text[end:]


def rewrite_claim_sections(out_dir: str | os.PathLike, when: str | None = None) -> Path:
    """Rewrite every study's sections of ``<out_dir>/REPORT.md`` from the committed tables
    beside it (:func:`claim_sections`), the rows of claims that read a store kept from it, and
    its section of changes against :func:`~pipeline.claims.changes.previous_report`; the rest
    of the report (runs, parameters, figures) is the run's and stays.  Returns the path."""
    from ..workflow.scenes import ROOT

    studies = registered()
    path = Path(out_dir) / "REPORT.md"
    text = path.read_text(encoding="utf-8")
    sections = claim_sections(out_dir, report=text, studies=studies)
    previous, against = previous_report(out_dir, ROOT, section_headings(studies))
    for heading, lines in sections.items():
        text = _replace_section(text, heading, lines)
    when = when or _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
    kept = [c for s in studies for c in s.claims if c.quantity in s.needs_stores]
    note = (f"Claims sections regenerated {when} from the committed tables beside this report "
            f"(`{COMMAND}`), without the stores"
            + (": the rows of " + ", ".join(f"claim {c.id}" for c in kept) + " read the stores "
               "and are kept as the run wrote them." if kept else "."))
    text = re.sub(r"\n\nClaims sections regenerated [^\n]*\n+", "\n\n", text)
    text = re.sub(r"(\nWritten [^\n]*\n)", lambda m: m.group(1) + "\n" + note + "\n", text,
                  count=1)
    text = text.split(f"\n{HEADING}", 1)[0].rstrip("\n") + "\n"
    written = re.search(r"^Written (\S+) by", previous or "", re.M)
    text += "\n".join(changes_section(previous, text, written and written.group(1), against)) + "\n"
    path.write_text(text, encoding="utf-8")
    return path


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.studies.report [--out DIR]``: rewrite the claims sections of
    DIR/REPORT.md (default figures/) from the committed tables."""
    import argparse
    import sys

    ap = argparse.ArgumentParser(prog=COMMAND, description=main.__doc__.split("\n")[0])
    ap.add_argument("--out", default="figures", help="the folder of REPORT.md and its tables")
    a = ap.parse_args(argv)
    if not (Path(a.out) / "REPORT.md").is_file():
        print(f"no REPORT.md in {a.out}: make_figures writes it first", file=sys.stderr)
        return 2
    print(rewrite_claim_sections(a.out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
