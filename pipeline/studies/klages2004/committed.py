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

__all__ = ["TABLE_FILES", "FLOAT_FORMAT", "CLAIMS_HEADING", "write_csv", "read_tables",
           "study_key", "study_file", "read_study_tables", "write_study_tables", "figure2_params",
           "claim_rows", "claim_sections"]

#: this study's tables (as write_report reads them) -> the CSV beside REPORT.md
TABLE_FILES = {"figure2": "diffusion_figure2.csv", "ergodicity": "diffusion_ergodicity.csv",
               "figure2_matyas2004": "diffusion_figure2_matyas2004.csv",
               "finescale": "diffusion_finescale.csv", "locking": "locking.csv",
               "locking_matyas2004": "locking_matyas2004.csv",
               # the protocol study's verdicts (pipeline.studies.protocol), read by claim 2's note
               "protocol_verdicts": "protocol_verdicts.csv"}
#: every committed table keeps six significant digits
FLOAT_FORMAT = "%.6g"
#: the heading of this study's claims section in REPORT.md
CLAIMS_HEADING = "## Claims"


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
