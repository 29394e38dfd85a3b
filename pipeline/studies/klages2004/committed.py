"""The tables beside ``REPORT.md``: the CSV file each table the report reads is written to, and
reading them back, so that every claim section of the report is a function of committed files.

``make_figures`` writes every table a claim reads into the output folder (``figures/``) and
then writes the report from the tables *read back* from those files: the committed CSVs (six
significant digits) and REPORT.md cannot disagree by rounding, and :func:`claim_sections`
regenerates each claim section from the committed files alone (tests/pipeline/studies/
klages2004/test_committed.py compares it with the committed REPORT.md).

File names:

* this study: :data:`TABLE_FILES` (``diffusion_figure2.csv``, ``locking.csv``, ...);
* a further study (``pipeline.studies.<name>``): ``<scene>_<table>.csv`` per reduce table of
  each of its scenes, and ``<key>.csv`` for a table its ``draw`` hook adds (keyed
  ``<scene>_<table>`` already, e.g. ``contact_proj_locking``).  In memory the table is
  keyed ``<table>`` when the table is named after its scene (``mechanisms``), else
  ``<scene>_<table>``: :func:`study_file` and :func:`read_study_tables` are each other's
  inverse.
"""

from __future__ import annotations

import importlib
import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

from ...claims.markdown import markdown_table

__all__ = ["TABLE_FILES", "FLOAT_FORMAT", "CLAIMS_HEADING", "CLAIMS_INTRO", "NEEDS_STORES",
           "write_csv", "read_tables", "study_key", "study_file", "read_study_tables",
           "write_study_tables", "figure2_params", "claim_rows", "claim_sections",
           "rewrite_claim_sections", "summary_line", "main"]

#: this study's tables (as write_report reads them) -> the CSV beside REPORT.md
TABLE_FILES = {"figure2": "diffusion_figure2.csv", "ergodicity": "diffusion_ergodicity.csv",
               "figure2_matyas2004": "diffusion_figure2_matyas2004.csv",
               "finescale": "diffusion_finescale.csv", "locking": "locking.csv",
               "locking_matyas2004": "locking_matyas2004.csv",
               # the protocol study's verdicts (pipeline.studies.protocol), read by claim 2's note
               "protocol_verdicts": "protocol_verdicts.csv"}
#: every committed table keeps six significant digits
FLOAT_FORMAT = "%.6g"
#: the heading of this study's claims section in REPORT.md, and the paragraph under it
CLAIMS_HEADING = "## Claims"
CLAIMS_INTRO = (
    "Each measured number carries its 95 % CI; each claim is judged against the tolerance "
    "band in the 'judged by' column, with the reason for its width. Verdicts: **agrees** "
    "(the whole CI inside the band), **agrees within the CI** (the value inside, the CI "
    "reaching beyond an edge: the verdict flips inside the CI), **inconclusive** (the "
    "value outside, the CI reaching in), **disagrees** (the whole CI outside, or the "
    "feature not found), **partly** (some parts agree, or only a curve other than the "
    "claim's main one), **not measured** (a table missing; for a rule stated over all its "
    "parts, a part missing). Two kinds of row are never agrees or disagrees: **consistent** / "
    "**inconsistent** (a result compared with itself, e.g. runs sharing seeds and chunks: a "
    "check of the pipeline, not a test of the paper) and **by construction** (true by the "
    "design of the ensemble). A quantity shown with '(no CI)' is judged by its value alone. "
    "⚠ marks a D that depends on the run length (stationarity below). Every claim is "
    "registered with its id, rule, scope and commit (pipeline/studies/registry.py); once "
    "judged its rule and scope are frozen, and a changed rule or widened scope is a new id "
    "(T3 → T3b) judged beside the old one.")
#: claims whose measure reads a store, not a committed table, and why: regenerated from the
#: committed tables alone their rows are kept from the report the stores wrote
NEEDS_STORES = {
    "klages2004.spiral_approx": (
        "claim 15 reads the post-collision states of the figure3 and locking stores (distances "
        "of every state to the curve of Eqs. (8)-(9)), which are not committed; its measure "
        "(pipeline/studies/klages2004/measures.py) would have to read a table of those "
        "distances instead"),
}


def write_csv(df: pd.DataFrame, path: str | os.PathLike) -> Path:
    """``df`` as the committed CSV (no index, :data:`FLOAT_FORMAT`); returns the path."""
    df.to_csv(path, index=False, float_format=FLOAT_FORMAT)
    return Path(path)


def read_tables(out_dir: str | os.PathLike) -> dict[str, pd.DataFrame]:
    """This study's tables read back from ``out_dir`` (those present), keyed as
    :func:`~.report.write_report` takes them."""
    out = Path(out_dir)
    return {name: pd.read_csv(out / fn) for name, fn in TABLE_FILES.items()
            if (out / fn).is_file()}


def study_key(scene: str, table: str) -> str:
    """The in-memory key of a further study's table ``table`` of scene ``scene``."""
    return table if table == scene else f"{scene}_{table}"


def study_file(key: str, scenes: Sequence[str]) -> str:
    """The CSV file name of a further study's table keyed ``key`` (its scenes ``scenes``)."""
    return f"{key}_{key}.csv" if key in scenes else f"{key}.csv"


def _study_files(out_dir: str | os.PathLike, scenes: Sequence[str]) -> dict[str, Path]:
    """{key: path} of every ``<scene>_<table>.csv`` of the scenes in ``out_dir`` (the longest
    scene name that prefixes the file wins)."""
    out: dict[str, Path] = {}
    by_length = sorted(scenes, key=len, reverse=True)
    for path in sorted(Path(out_dir).glob("*.csv")):
        scene = next((s for s in by_length if path.stem.startswith(f"{s}_")), None)
        if scene is not None:
            out[study_key(scene, path.stem[len(scene) + 1:])] = path
    return out


def read_study_tables(out_dir: str | os.PathLike, scenes: Sequence[str]
                      ) -> dict[str, pd.DataFrame]:
    """A further study's tables read back from ``out_dir``: every ``<scene>_<table>.csv`` of
    its scenes, keyed by :func:`study_key`."""
    return {key: pd.read_csv(path) for key, path in _study_files(out_dir, scenes).items()}


def write_study_tables(out_dir: str | os.PathLike, tables: Mapping[str, pd.DataFrame],
                       scenes: Sequence[str]) -> list[Path]:
    """Write a further study's tables (keyed by :func:`study_key`) into ``out_dir`` and delete
    the CSVs of its scenes that are not among them (left by an earlier version of the study),
    so that :func:`read_study_tables` gives exactly ``tables``.  Returns the paths written."""
    for key, path in _study_files(out_dir, scenes).items():
        if key not in tables:
            path.unlink()
    return [write_csv(df, Path(out_dir) / study_file(key, scenes)) for key, df in tables.items()]


def figure2_params(stores: Mapping[str, str] | None = None, fast: bool = False
                   ) -> tuple[float | None, dict | None]:
    """(f at Γ = 1 in Hz, the parameters as a dict) of the Fig. 2 scene: from its store when
    one is given, else from the scene file (the same parameters); (None, None) if A = 0."""
    if stores and stores.get("figure2"):
        from ...tables.collisions import as_store

        p = as_store(stores["figure2"]).study.params(60.0)
    else:
        from ...workflow.scenes import load_scene

        p = load_scene("figure2", fast).params(60.0)
    if not p.A > 0:
        return None, None
    return math.sqrt(p.g / p.A) / (2 * math.pi), p.as_dict()


def claim_rows(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str] | None = None,
               fast: bool = False):
    """This study's claim rows and extrema (:func:`~.claims.evaluate`) with the Fig. 2
    scene's parameters."""
    from .claims import evaluate

    f_gamma1, params = figure2_params(stores, fast)
    return evaluate(tables, stores or {}, f_gamma1, params)


def claim_sections(out_dir: str | os.PathLike, studies: Sequence[str] | None = None,
                   stores: Mapping[str, str] | None = None) -> dict[str, list[str]]:
    """{heading: lines} of every claim section of REPORT.md, regenerated from the tables in
    ``out_dir``: this study's claims table under :data:`CLAIMS_HEADING`, and each further
    study's ``report_lines`` split at its ``## `` headings.  ``stores``: only claims that read
    a store (post-collision states) need them; without, those claims are 'not measured'."""
    from .scene_list import EXTRA_STUDIES

    rows, _ = claim_rows(read_tables(out_dir), stores)
    sections = {CLAIMS_HEADING: markdown_table(rows, claim_header="the paper says")}
    for name in EXTRA_STUDIES if studies is None else studies:
        m = importlib.import_module(f"pipeline.studies.{name}")
        heading = None
        for line in m.report_lines(read_study_tables(out_dir, m.SCENES)):
            if line.startswith("## "):
                heading = line
                sections[heading] = []
            elif heading is not None:
                sections[heading].append(line)
    return sections


def summary_line(rows: Sequence) -> str:
    """'Summary: **agrees** 13 (#5, …); …' of the claims table, by registered id."""
    by: dict[str, list[str]] = {}
    for i, r in enumerate(rows, 1):
        by.setdefault(r.verdict, []).append(r.id or str(i))
    return "Summary: " + "; ".join(f"**{v}** {len(n)} (#{', #'.join(n)})"
                                   for v, n in by.items()) + "."


def _cells(row: str) -> list[str]:
    import re

    return [c.strip() for c in re.split(r"(?<!\\)\|", row.strip())[1:-1]]


def _kept_rows(report: str, rows) -> list:
    """``rows`` with what was measured for the claims in :data:`NEEDS_STORES` (measured,
    verdict, notes) taken from ``report``, the report the stores wrote."""
    from ...claims.claim import Row
    from .claims import CLAIMS

    keep = {c.id for c in CLAIMS if c.quantity in NEEDS_STORES}
    old = {}
    for line in report.splitlines():
        if line.startswith("| ") and (c := _cells(line)) and c[0] in keep and len(c) == 6:
            old[c[0]] = Row(c[1].replace("\\|", "|"), c[2].replace("\\|", "|"),
                            c[3].strip("*"), c[5].replace("\\|", "|"),
                            c[4].replace("\\|", "|"), c[0])
    # the claim's text and rule are the code's; what was measured is the stores'
    return [Row(r.claim, old[r.id].measured, old[r.id].verdict, old[r.id].note, r.judged_by, r.id)
            if r.id in old else r for r in rows]


def _replace_section(text: str, heading: str, lines: list[str]) -> str:
    """``text`` with the section under ``heading`` (up to the next '## ' heading) replaced by
    ``lines``; appended before the section of changes if it is not there."""
    from .changes import HEADING

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
    """Rewrite every claims section of ``<out_dir>/REPORT.md`` from the committed tables beside
    it (:func:`claim_sections`), the rows of :data:`NEEDS_STORES` kept from it, and its
    section of changes against :func:`~.changes.previous_report`; the rest of the report (runs,
    parameters, figures) is the run's and stays.  Returns the path."""
    import datetime as dt
    import re

    from ...workflow.scenes import ROOT
    from .changes import HEADING, changes_section, previous_report

    path = Path(out_dir) / "REPORT.md"
    text = path.read_text(encoding="utf-8")
    sections = claim_sections(out_dir)
    rows, _ = claim_rows(read_tables(out_dir))
    rows = _kept_rows(text, rows)
    sections[CLAIMS_HEADING] = ["", CLAIMS_INTRO, "",
                                *markdown_table(rows, claim_header="the paper says"), "",
                                summary_line(rows)]
    headings = list(sections)
    previous, against = previous_report(out_dir, ROOT, headings)
    for heading, lines in sections.items():
        text = _replace_section(text, heading, lines)
    when = when or dt.datetime.now(dt.UTC).isoformat(timespec="seconds")
    note = (f"Claims sections regenerated {when} from the committed tables beside this report "
            "(`python -m pipeline.studies.klages2004.committed`), without the stores: the rows "
            "of " + ", ".join(f"claim {c.split(' ', 2)[1]}" for c in NEEDS_STORES.values())
            + " are the stores' and kept as the run wrote them.")
    text = re.sub(r"\n\nClaims sections regenerated [^\n]*\n+", "\n\n", text)
    text = re.sub(r"(\nWritten [^\n]*\n)", lambda m: m.group(1) + "\n" + note + "\n", text,
                  count=1)
    text = text.split(f"\n{HEADING}", 1)[0].rstrip("\n") + "\n"
    written = re.search(r"^Written (\S+) by", previous or "", re.M)
    text += "\n".join(changes_section(previous, text, written and written.group(1), against)) + "\n"
    path.write_text(text, encoding="utf-8")
    return path


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.studies.klages2004.committed [--out DIR]``: rewrite the claims
    sections of DIR/REPORT.md (default figures/) from the committed tables."""
    import argparse
    import sys

    ap = argparse.ArgumentParser(prog="python -m pipeline.studies.klages2004.committed",
                                 description=main.__doc__.split("\n")[0])
    ap.add_argument("--out", default="figures", help="the folder of REPORT.md and its tables")
    a = ap.parse_args(argv)
    if not (Path(a.out) / "REPORT.md").is_file():
        print(f"no REPORT.md in {a.out}: make_figures writes it first", file=sys.stderr)
        return 2
    print(rewrite_claim_sections(a.out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
