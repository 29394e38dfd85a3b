"""The ``[grid]`` table of a workflow: its axes, read and checked, and every point's Params
checked before anything runs.

A ``[grid]`` holds sweep axes -- ``NAME = [v1, v2, ...]`` for any ``[params]`` key but the
preset (:data:`pipeline.workflow.keys.GRID_AXES`), distinct values of the key's type, not also
given in ``[params]`` -- and its settings (:class:`pipeline.workflow.keys.GridTable`:
``invalid``).  The points are every combination of the axes with ``[frequencies]``, frequency
innermost (:attr:`pipeline.workflow.study.Study.points`).  Every mistake is one line naming the
file, the line, the key and what is allowed (:class:`pipeline.workflow.schema.Reader`).
"""

from __future__ import annotations

import dataclasses
import re

from .keys import GRID_AXES, GridRefine, GridRefineTable, GridTable, ParamsTable
from .point import Grid, Point, combinations, resolve_params
from .schema import Key, Reader, declared, tname
from .suggest import did_you_mean

__all__ = ["Grid", "read_grid", "check_points"]


def read_grid(r: Reader, doc: dict) -> tuple[Grid, str, GridRefine | None]:
    """The [grid] axes, (axis, values) in the workflow's order, its ``invalid`` policy and
    its refinement rule ([grid.refine], None without)."""
    raw = doc.get("grid")
    if raw is None:
        return (), "refuse", None
    settings = {k.name for k in declared(GridTable)} | {"refine"}
    if not isinstance(raw, dict):
        r.fail(("grid",), f"must be a table, got {tname(raw)}",
               "[grid] with axes such as alpha = [0.5, 0.7]")
    params = doc.get("params") if isinstance(doc.get("params"), dict) else {}
    axes = []
    for name, values in raw.items():
        path = ("grid", name)
        if name in settings:
            continue
        if name not in GRID_AXES:
            r.fail(path, "unknown key" + did_you_mean(name, [*GRID_AXES, *settings]),
                   "an axis named by a [params] key (" + ", ".join(GRID_AXES)
                   + "), or " + ", ".join(sorted(settings)))
        if name in params:
            r.fail(path, "given in both [params] and [grid]",
                   f"{name} in [params] (one value) or in [grid] (an axis), not both")
        for a, b in (("A", "Gamma"), ("Gamma", "A")):
            if name == a and (b in params or b in raw):
                r.fail(path, f"{a} with {b} (the amplitude twice)",
                       "A (mm) or Gamma (peak floor acceleration in g), not both")
        decl = next(k for k in declared(ParamsTable) if k.name == name)
        axes.append((name, _axis_values(r, path, decl, values)))
    if not axes:
        r.fail(("grid",), "no axis", "one or more axes such as alpha = [0.5, 0.7]")
    tbl = r.table({k: v for k, v in raw.items() if k in settings - {"refine"}}, ("grid",),
                  GridTable)
    refine = _read_refine(r, raw["refine"], axes) if "refine" in raw else None
    return tuple(axes), tbl["invalid"], refine


def _read_refine(r: Reader, raw, axes: list) -> GridRefine:
    """[grid.refine]: its settings and a resolution (> 0) per refined axis: f (Hz, >= 2 mHz:
    new frequencies sit on the 1 mHz grid) or a numeric grid axis."""
    path = ("grid", "refine")
    settings = {k.name for k in declared(GridRefineTable)}
    numeric = [a for a, v in axes if not isinstance(v[0], str)]
    allowed = ("a resolution > 0 per refined axis: f (Hz, >= 0.002)"
               + (", " + ", ".join(numeric) if numeric else "") + "; and "
               + ", ".join(sorted(settings)))
    if not isinstance(raw, dict):
        r.fail(path, f"must be a table, got {tname(raw)}", allowed)
    to = []
    for name, value in raw.items():
        if name in settings:
            continue
        if name != "f" and name not in numeric:
            why = ("a string axis is not refined" if name in dict(axes)
                   else "not an axis of this grid")
            r.fail(path + (name,), f"unknown key ({why})"
                   + did_you_mean(name, ["f", *numeric, *settings]), allowed)
        least = 0.002 if name == "f" else 0.0
        if isinstance(value, bool) or not isinstance(value, int | float) or not (
                value > least or (name == "f" and value == least)):
            r.fail(path + (name,), f"must be a resolution, got {value!r}", allowed)
        to.append((name, float(value)))
    if not to:
        r.fail(path, "no axis to refine", allowed)
    tbl = r.table({k: v for k, v in raw.items() if k in settings}, path, GridRefineTable)
    return GridRefine(tuple(to), tbl["extrema"], tbl["jumps"], tbl["quantity"])


def _axis_values(r: Reader, path: tuple[str, ...], k: Key, values) -> tuple:
    """One [grid] axis: a non-empty list of distinct values, each of the key's type and range."""
    kind = "a string" if k.kind == "str" else "a number"
    allowed = f"a non-empty list of distinct values, each {kind}: {k.allowed_text()}"
    if not isinstance(values, list) or not values:
        r.fail(path, f"must be a non-empty list, got {tname(values)} {values!r}", allowed)
    types = {"string" if isinstance(v, str) else "boolean" if isinstance(v, bool)
             else "number" if isinstance(v, int | float) else tname(v) for v in values}
    if len(types) > 1:
        r.fail(path, f"mixed types ({', '.join(sorted(types))}) in {values!r}", allowed)
    each = dataclasses.replace(k, allowed=allowed)  # a bad value's line says: a list of ...
    out = tuple(r.check(v, path, each, {}) for v in values)
    out = tuple(float(v) if k.kind == "float" else v for v in out)
    dup = [v for i, v in enumerate(out) if v in out[:i]]
    if dup:
        r.fail(path, f"repeated values {sorted(set(dup), key=str)!r}", allowed)
    return out


def check_points(r: Reader, preset: str, overrides: dict, grid: Grid, invalid: str,
                 freqs: tuple[float, ...]) -> None:
    """Every point's Params, before anything runs: a point bbb.Params refuses is refused here,
    in one line naming it (``invalid = "refuse"``), or left out (``"skip"``), but not all."""
    n_ok, first = 0, None
    for pairs in combinations(grid, overrides):
        for f in freqs:
            try:
                resolve_params(preset, f, {**overrides, **dict(pairs)})
                n_ok += 1
            except ValueError as e:
                if invalid == "refuse" or first is None:
                    first = (Point(f, pairs, None), e)  # type: ignore[arg-type]
                if invalid == "refuse":
                    break
        if first and invalid == "refuse":
            break
    if first is None:
        return
    point, e = first
    fld = _field_of(e)
    axes = [a for a, _ in grid]
    if fld == "A" and "Gamma" in axes + list(overrides):  # A is Gamma's, at this f
        fld = "Gamma"
    path = (("grid", fld) if fld in axes else ("params", fld) if fld in overrides
            else ("grid",))
    if invalid == "refuse":
        r.fail(path, f"invalid parameters at the point {point.label()}: {e}".replace(
            "; allowed:", ", allowed:"),
            'grid values that bbb.Params accepts at every point, or invalid = "skip" in [grid] '
            "to leave such points out")
    if n_ok == 0:
        r.fail(path, f"every point is invalid, e.g. {point.label()}: {e}".replace(
            "; allowed:", ", allowed:"), "grid values that bbb.Params accepts at some points")


def _field_of(e: ValueError) -> str | None:
    """'Params.alpha = ... is out of range' -> 'alpha'."""
    m = re.search(r"Params\.(\w+)", str(e))
    return m.group(1) if m else None
