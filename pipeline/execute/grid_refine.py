"""Refinement of a map in every direction (``[grid.refine]``), as a pure function: which points
to add, given the points there are and D (or v) with its CI at each.

Along every axis that has a resolution in ``[grid.refine]`` -- ``f`` and any numeric grid
axis -- the points are taken in lines (all other values fixed: a D(f) curve for ``f``, a
D(alpha) cut at one frequency for ``alpha``), and each line's gaps next to a significant
extremum (``extrema``) or between neighbours whose values differ beyond their CIs
(``jumps``) are split at their midpoint while wider than the axis's resolution
(:func:`pipeline.execute.adaptive.split_gaps`, the rule of frequency refinement).  New
frequencies sit on the 1 mHz grid, other values on a 1e-9 grid, so a point added is a function
of the data at the points before it only, and the same on every machine.  Repeated on the grown
map until nothing is added, every extremum and every significant jump along an axis ends with
neighbours at most that axis's resolution apart.

Only the lines through the workflow's own values are refined (``own``): along f the lines at
the grid's listed values, along another axis the lines at the listed frequencies (and the
other axes' listed values).  A value refinement added between two listed ones holds a few
points, not a curve: refining along it would fill it in point by point, round after round,
without bound on the cost -- measured on a D(f, α) map, whose rounds kept adding 50-100
points each while its listed lines had long converged.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..workflow.identity import f_key, point_key
from ..workflow.keys import GridRefine
from ..workflow.point import Point
from .adaptive import split_gaps

__all__ = ["refine_grid", "VALUE_DIGITS"]

#: a refined grid value (not f) is rounded to this many decimals
VALUE_DIGITS = 9

NewPoint = tuple[float, tuple[tuple[str, object], ...]]  # (f, grid values)


def refine_grid(points: Sequence[Point], table: np.ndarray, rule: GridRefine, *,
                ci: float = 0.95, own: Mapping[str, Sequence] | None = None) -> list[NewPoint]:
    """The points to add to a map of ``points`` whose value and CI at each is ``table`` (one
    row (value, lo, hi) per point, NaN where unknown), by ``rule``; in a deterministic order
    (axis by axis as ``rule.to`` gives them, then line by line in point order), none of them
    already a point.  ``own``: the workflow's own values per axis (``"f"``: its frequencies,
    Hz); only lines through them are refined (module docstring); None: every line."""
    have = {p.key for p in points}
    keep = None if own is None else {a: {_value_key(a, v) for v in vs} for a, vs in own.items()}
    out: dict[tuple, NewPoint] = {}
    for axis, res in rule.to:
        for line_key, members in _lines(points, axis).items():
            if keep is not None and not _through_own(line_key, axis, keep):
                continue
            x = np.array([_coord(points[i], axis) for i in members], dtype=np.float64)
            rows = table[members]
            gaps = split_gaps(x, rows[:, 0], rows[:, 1], rows[:, 2], ci=ci,
                              extrema=rule.extrema, jumps=rule.jumps)
            base = points[members[0]]
            for a, b in gaps:
                mid = _midpoint(axis, a, b, res)
                if mid is None:
                    continue
                new = _moved(base, axis, mid)
                key = point_key(*new)
                if key not in have and key not in out:
                    out[key] = new
    return list(out.values())


def _lines(points: Sequence[Point], axis: str) -> dict[tuple, list[int]]:
    """{the other values: indices of the points of that line along ``axis``}, in point order."""
    lines: dict[tuple, list[int]] = {}
    for i, p in enumerate(points):
        rest = tuple((a, v) for a, v in p.grid if a != axis)
        key = rest if axis == "f" else (f_key(p.f), rest)
        lines.setdefault(key, []).append(i)
    return lines


def _value_key(axis: str, v) -> object:
    """A value as compared with the workflow's own: f to 1 mHz, numbers to VALUE_DIGITS."""
    if axis == "f":
        return f_key(float(v))
    return v if isinstance(v, str) else round(float(v), VALUE_DIGITS)


def _through_own(line_key: tuple, axis: str, keep: Mapping[str, set]) -> bool:
    """Whether the line keyed ``line_key`` (as :func:`_lines` keys it) lies on own values."""
    rest = line_key if axis == "f" else line_key[1]
    if axis != "f" and "f" in keep and line_key[0] not in keep["f"]:
        return False
    return all(a not in keep or _value_key(a, v) in keep[a] for a, v in rest)


def _coord(p: Point, axis: str) -> float:
    return p.f if axis == "f" else float(dict(p.grid)[axis])


def _midpoint(axis: str, a: float, b: float, res: float) -> float | None:
    """The midpoint of the gap (a, b) on the axis's grid, None if the gap is not wider than
    the resolution ``res``."""
    if axis == "f":
        ka, kb = f_key(a), f_key(b)
        return (ka + kb) // 2 / 1000.0 if kb - ka > f_key(res) else None
    if b - a <= res * (1 + 1e-12):
        return None
    return round((a + b) / 2.0, VALUE_DIGITS)


def _moved(p: Point, axis: str, value: float) -> NewPoint:
    if axis == "f":
        return (value, p.grid)
    return (p.f, tuple((a, value if a == axis else v) for a, v in p.grid))
