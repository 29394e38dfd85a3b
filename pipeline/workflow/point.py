"""One point of a study -- a frequency and a value of every grid axis -- and its Params.

:func:`resolve_params` turns a preset, a frequency and the [params]/[grid] values into
bbb.Params (``Gamma``, the peak floor acceleration in g, becomes the amplitude A at each
point's f); :class:`Point` is what the store, the tasks and the tables index by.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from bbb.params import PRESETS, Params

from .identity import point_key

__all__ = ["Grid", "Point", "resolve_params", "fmt_value", "combinations", "CONDITIONAL_AXES",
           "elsewhere", "map_coords"]

#: a grid: (axis, values) per [grid] axis, in the workflow's order
Grid = tuple[tuple[str, tuple[Any, ...]], ...]

#: axes that apply only where another key has a value, {axis: (key, value, the axis's value
#: elsewhere)}: mu, the Coulomb friction, is 0 under every other contact model (bbb.Params)
CONDITIONAL_AXES: dict[str, tuple[str, Any, Any]] = {"mu": ("contact", "coulomb", 0.0)}


def elsewhere(axis: str, values: Mapping[str, Any]):
    """The value a conditional axis (:data:`CONDITIONAL_AXES`) takes at a point whose other
    keys are ``values`` (overrides and grid values) when its condition fails there; None
    when the axis is not conditional or its condition holds (a key absent from ``values``
    has bbb.Params' default)."""
    if axis not in CONDITIONAL_AXES:
        return None
    other, when, value = CONDITIONAL_AXES[axis]
    return None if values.get(other, _PARAM_DEFAULTS[other]) == when else value


_PARAM_DEFAULTS = {f.name: f.default for f in dataclasses.fields(Params)}


def combinations(grid: Grid, overrides: Mapping[str, Any]):
    """Every combination of the grid's axis values as (axis, value) pairs, in axis order
    (one empty combination without a grid), each once: a conditional axis
    (:data:`CONDITIONAL_AXES`) takes its value only where its condition holds, elsewhere the
    value it has there (a map of contact x mu has one stick line, not one per mu)."""
    import itertools

    names = [a for a, _ in grid]
    seen = set()
    for combo in itertools.product(*(values for _, values in grid)):
        pairs = dict(zip(names, combo, strict=True))
        for a in CONDITIONAL_AXES.keys() & pairs.keys():
            other = elsewhere(a, {**overrides, **pairs})
            if other is not None:
                pairs[a] = other
        out = tuple(pairs.items())
        if out not in seen:
            seen.add(out)
            yield out


def map_coords(grid: Grid, points: Iterable[Point]) -> dict[str, tuple[Any, ...]]:
    """Where every view of a map puts its points (``open_study``, the tables' Dataset, the
    figures): the coordinates of the unstacked map, ``{"frequency": Hz, axis: values, ...}``.

    A point sits at the values its :class:`Point` holds, which are also the store's
    coordinates and the tables' columns: a conditional axis (:data:`CONDITIONAL_AXES`) at
    its value elsewhere -- mu = 0 under stick and slide, whatever ``[grid]`` lists -- so
    each axis has the workflow's values and every value a point holds (that mu = 0, a value
    ``[grid.refine]`` added).  Numbers ascending (frequency too); names (``contact``) in the
    workflow's order, any other after them.  A cell of this product that no point holds is
    absent (the presence mask ``present`` of :func:`pipeline.tables.dataset.presence`)."""
    points = list(points)
    out: dict[str, tuple[Any, ...]] = {"frequency": tuple(sorted({float(p.f) for p in points}))}
    for axis, listed in grid:
        held = {dict(p.grid)[axis] for p in points} | set(listed)
        if all(isinstance(v, str) for v in held):
            out[axis] = tuple(listed) + tuple(sorted(held - set(listed)))
        else:
            out[axis] = tuple(sorted(held))
    return out


def resolve_params(preset: str, f: float, values: Mapping[str, Any]) -> Params:
    """The Params of ``preset`` at f (Hz) with ``values`` (overrides and grid values); a
    ``Gamma`` among them (peak floor acceleration in g) becomes A = Gamma g / (2 pi f)^2 at
    this f.  Raises ValueError as bbb.Params does."""
    v = dict(values)
    gamma = v.pop("Gamma", None)
    if gamma is not None:
        g = float(v.get("g", PRESETS[preset]["g"] if preset in PRESETS else 1.0))
        v["A"] = float(gamma) * g / (2.0 * math.pi * float(f)) ** 2
    return Params.preset(preset, f=float(f), **v)


@dataclass(frozen=True)
class Point:
    """One point of a study: its frequency f (Hz), its grid values as (axis, value) pairs in
    the study's axis order (empty without a grid), and its Params."""

    f: float
    grid: tuple[tuple[str, Any], ...]
    params: Params

    @property
    def key(self) -> int | tuple:
        """:func:`pipeline.workflow.identity.point_key`: f_key(f) without a grid."""
        return point_key(self.f, self.grid)

    def columns(self) -> dict[str, Any]:
        """The point as a table row's leading columns: {"f": Hz, axis: value, ...}."""
        return {"f": self.f, **dict(self.grid)}

    def label(self) -> str:
        """The point as a person reads it: ``f = 60 Hz, alpha = 0.5, contact = "slide"``."""
        return ", ".join([f"f = {self.f:g} Hz"] + [f"{a} = {fmt_value(v)}" for a, v in self.grid])


def fmt_value(v: Any) -> str:
    return f'"{v}"' if isinstance(v, str) else f"{v:g}"
