"""Tables as the committed CSV files beside REPORT.md, and reading them back, so that every
claim section of the report is a function of committed files.

A study's tables are written into the output folder (``figures/``) and the report is written
from the tables *read back* from those files: the committed CSVs (six significant digits) and
REPORT.md cannot disagree by rounding.  File names of a study that keeps the reduce tables of
its scenes: ``<scene>_<table>.csv`` per reduce table of each scene, and ``<key>.csv`` for a
table the study adds (keyed ``<scene>_<table>`` already, e.g. ``contact_proj_locking``).  In
memory the table is keyed ``<table>`` when the table is named after its scene
(``mechanisms``), else ``<scene>_<table>``: :func:`study_file` and :func:`read_study_tables`
are each other's inverse.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

__all__ = ["FLOAT_FORMAT", "write_csv", "study_key", "study_file", "read_study_tables",
           "write_study_tables"]

#: every committed table keeps six significant digits
FLOAT_FORMAT = "%.6g"


def write_csv(df: pd.DataFrame, path: str | os.PathLike) -> Path:
    """``df`` as the committed CSV (no index, :data:`FLOAT_FORMAT`); returns the path."""
    df.to_csv(path, index=False, float_format=FLOAT_FORMAT)
    return Path(path)


def study_key(scene: str, table: str) -> str:
    """The in-memory key of a study's table ``table`` of scene ``scene``."""
    return table if table == scene else f"{scene}_{table}"


def study_file(key: str, scenes: Sequence[str]) -> str:
    """The CSV file name of a study's table keyed ``key`` (its scenes ``scenes``)."""
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
    """A study's tables read back from ``out_dir``: every ``<scene>_<table>.csv`` of its
    scenes, keyed by :func:`study_key`."""
    return {key: pd.read_csv(path) for key, path in _study_files(out_dir, scenes).items()}


def write_study_tables(out_dir: str | os.PathLike, tables: Mapping[str, pd.DataFrame],
                       scenes: Sequence[str]) -> list[Path]:
    """Write a study's tables (keyed by :func:`study_key`) into ``out_dir`` and delete the CSVs
    of its scenes that are not among them (left by an earlier version of the study), so that
    :func:`read_study_tables` gives exactly ``tables``.  Returns the paths written."""
    for key, path in _study_files(out_dir, scenes).items():
        if key not in tables:
            path.unlink()
    return [write_csv(df, Path(out_dir) / study_file(key, scenes)) for key, df in tables.items()]
