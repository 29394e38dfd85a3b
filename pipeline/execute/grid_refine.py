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
"""

from __future__ import annotations

from collections.abc import Sequence

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
                ci: float = 0.95) -> list[NewPoint]:
    """The points to add to a map of ``points`` whose value and CI at each is ``table`` (one
    row (value, lo, hi) per point, NaN where unknown), by ``rule``; in a deterministic order
    (axis by axis as ``rule.to`` gives them, then line by line in point order), none of them
    already a point."""
    have = {p.key for p in points}
    out: dict[tuple, NewPoint] = {}
    for axis, res in rule.to:
        for members in _lines(points, axis).values():
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
