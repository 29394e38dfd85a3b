"""A map's long tables sliced into its grid lines, for studies whose claims and figures read
one table per line.

A map scene (a workflow with a ``[grid]``) reduces to long tables: columns ``f``, then one per
grid axis, then the rest, rows sorted by the axes and then f (:mod:`pipeline.tables.catalog`).
A grid line -- one value per axis -- is bit for bit the scene without a grid that has those
values in ``[params]`` (same seed, so same chunks and same bootstraps), so the rows of one line
without the axis columns are exactly the table that scene gave: :func:`line_table`.
:func:`split_lines` turns a study's map tables, keyed ``<scene>_<table>``
(:func:`pipeline.tables.files.study_key`), into per-line tables keyed
``<line>_<table>``, which is what the study's rules and figures read.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import pandas as pd

__all__ = ["line_table", "split_lines", "point_index"]


def _matches(column: pd.Series, value: Any) -> np.ndarray:
    if isinstance(value, str):
        return (column.astype(str) == value).to_numpy()
    # a committed CSV keeps six significant digits: 0.05 reads back as 0.05, not 0.05 + eps
    return np.isclose(column.to_numpy(dtype=float), float(value), rtol=1e-9, atol=0.0)


def line_table(table: pd.DataFrame | None, values: Mapping[str, Any]) -> pd.DataFrame | None:
    """The rows of the long table ``table`` on the grid line ``values`` (axis -> value), without
    the axis columns, in the table's order, index 0..n-1; None if ``table`` is None, lacks an
    axis column or has no row on the line (a map without that line: as a scene not run)."""
    if table is None or any(a not in table for a in values):
        return None
    keep = np.ones(len(table), dtype=bool)
    for axis, value in values.items():
        keep &= _matches(table[axis], value)
    if not keep.any():
        return None
    return table.loc[keep, [c for c in table.columns if c not in values]].reset_index(drop=True)


def split_lines(tables: Mapping[str, pd.DataFrame | None], scene: str,
                lines: Mapping[str, Mapping[str, Any]], names: Iterable[str]
                ) -> dict[str, pd.DataFrame]:
    """{``<line>_<name>``: :func:`line_table` of the map's table ``name`` (keyed
    ``study_key(scene, name)``: ``<scene>_<name>``, or ``<name>`` when the table is named after
    the scene) at ``lines[line]``}, for every line and every table ``name`` the map has (those
    ``tables`` lacks are left out)."""
    from ..tables.files import study_key

    out = {}
    for name in names:
        t = tables.get(study_key(scene, name))
        for line, values in lines.items():
            sliced = line_table(t, values)
            if sliced is not None:
                out[f"{line}_{name}"] = sliced
    return out


def point_index(study, f: float, values: Mapping[str, Any]) -> int | None:
    """The store index of the point at frequency ``f`` (Hz, to 1 mHz) on the grid line
    ``values`` of a map's Study (a store's ``study``), or None if it has no such point."""
    for i, p in enumerate(study.points):
        g = dict(p.grid)
        if abs(p.f - f) < 1e-3 and all(
                g.get(a) == v if isinstance(v, str) else
                (a in g and math.isclose(float(g[a]), float(v), rel_tol=1e-9, abs_tol=0.0))
                for a, v in values.items()):
            return i
    return None
