"""The figures a user puts in a talk, from a reduced Dataset (the one
``open_study(path, reduced=True)`` returns), written as files with deterministic, readable
names (``<format>``: each of ``formats``, default PNG and PDF):

``curve_<var>_vs_frequency.<format>``
    ``var`` (D, and v and D_drift when present) against f with its CI, without grid axes
``curve_<var>_vs_frequency_by_<axis>[_<other>=<value>...].<format>``
    the same with one line per value of a grid axis, one figure per value of the others
``curve_D_family_vs_frequency[_<axis>=<value>...].<format>``
    D per initial-condition family, one line per family, one figure per grid point
``map_<var>_frequency-<axis>[_<other>=<value>...].<format>``
    heat maps of D (v, D_drift) over frequency x each grid axis of 2 or more values (one per
    value of the other axes), with the CI panel (:func:`pipeline.plot.heatmap.plot_map`)

Every figure is titled with the scene, what it fixes and the cut it shows
(:mod:`pipeline.plot.titles`).  A named axis and the axes that apply under one of its names
only (contact, and mu under Coulomb) are one axis of models (:mod:`pipeline.plot.models`): the
comparison ``curve_D_vs_frequency_by_contact`` has one curve per model (stick, slide,
Coulomb at each μ), not one figure per μ.  A grid axis of one value is fixed, not drawn along.
The map over frequency x the models is drawn only where no numeric axis is left to map.

A cut the map has no point of (every point absent: ``present`` False) is not drawn; one whose
points are present but failed is, its failures marked.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Container, Iterator, Sequence
from functools import partial
from pathlib import Path

import xarray as xr
from matplotlib import rc_context
from matplotlib.figure import Figure

from .curve import plot_curve
from .flags import present
from .heatmap import plot_map
from .labels import file_token
from .models import merge_conditional
from .style import FORMATS, STYLE, figure_files, save_figure

__all__ = ["VARIABLES", "plot_dataset", "talk_figures", "grid_axes"]

#: the variables drawn when present, each with its CI bounds <var>_lo, <var>_hi
VARIABLES = ("D", "v", "D_drift")


def grid_axes(ds: xr.Dataset) -> list[str]:
    """The grid axes of ``ds``: the dimensions of D besides ``frequency`` (and ``family``),
    named axes (the models) first."""
    axes = [d for d in ds["D"].dims if d not in ("frequency", "family")]
    return sorted(axes, key=lambda a: ds[a].dtype.kind in "iufb")


def _token(ds: xr.Dataset, axis: str, value) -> str:
    """``axis=value`` for a file name; a model of merged axes (``coulomb, μ = 0.3``) by each
    axis's value where it applies (``contact=coulomb_mu=0.3``)."""
    if isinstance(value, str) and ", " in value:
        i = list(ds[axis].values).index(value)
        extra = [c for c, v in ds.coords.items() if v.dims == (axis,) and c != axis]
        return "_".join([file_token(axis, value.split(", ")[0]),
                         *(file_token(c, ds[c].values[i]) for c in extra)])
    return file_token(axis, value)


def _cuts(ds: xr.Dataset, axes: list[str]):
    """(selection, name suffix) for every combination of one value of each of ``axes``."""
    for combo in itertools.product(*(ds[a].values for a in axes)):
        pick = dict(zip(axes, combo, strict=True))
        yield pick, "".join(f"_{_token(ds, a, v)}" for a, v in pick.items())


def talk_figures(ds: xr.Dataset, names: Container[str] | None = None
                 ) -> Iterator[tuple[str, Figure]]:
    """(name, Figure) of every figure of the module docstring for the reduced Dataset ``ds``
    (``names``: only those of these names), one at a time, in a deterministic order (a Figure
    is drawn when asked for)."""
    for name, draw in _planned(ds):
        if names is None or name in names:
            yield name, draw()


def _planned(ds: xr.Dataset) -> Iterator[tuple[str, Callable[[], Figure]]]:
    """(name, a call drawing its Figure) of every figure, in order."""
    ds = merge_conditional(ds)
    ds = ds.squeeze([a for a in grid_axes(ds) if ds.sizes[a] == 1])
    axes = grid_axes(ds)

    def drawn(cut: xr.Dataset, var: str) -> bool:
        return bool(present(cut, cut[var]).values.any())

    for var in (v for v in VARIABLES if v in ds.data_vars):
        if not axes:
            yield f"curve_{var}_vs_frequency", partial(plot_curve, ds, "frequency", var)
        for hue in axes:
            for pick, suffix in _cuts(ds, [a for a in axes if a != hue]):
                cut = ds.sel(pick)
                if drawn(cut, var):
                    yield (f"curve_{var}_vs_frequency_by_{hue}{suffix}",
                           partial(plot_curve, cut, "frequency", var, hue=hue))
    if "D_family" in ds.data_vars:
        for pick, suffix in _cuts(ds, axes):
            cut = ds.sel(pick)
            if drawn(cut, "D_family"):
                yield (f"curve_D_family_vs_frequency{suffix}",
                       partial(plot_curve, cut, "frequency", "D_family", hue="family"))
    numeric = [a for a in axes if ds[a].dtype.kind in "iuf"]
    if ds.sizes["frequency"] >= 2:
        for var in (v for v in VARIABLES if v in ds.data_vars):
            for axis in (a for a in (numeric or axes) if ds.sizes[a] >= 2):
                for pick, suffix in _cuts(ds, [a for a in axes if a != axis]):
                    cut = ds.sel(pick)
                    if drawn(cut, var):
                        yield (f"map_{var}_frequency-{axis}{suffix}",
                               partial(plot_map, cut, "frequency", axis, var))


def plot_dataset(ds: xr.Dataset, out_dir: str | os.PathLike, *,
                 formats: Sequence[str] = FORMATS,
                 names: Container[str] | None = None) -> list[Path]:
    """Write the figures of the module docstring for the reduced Dataset ``ds`` to
    ``out_dir`` (created if missing; ``names``: only those of these names); returns the files
    written, in the order written."""
    written: list[Path] = []
    for name, fig in talk_figures(ds, names):
        fig.set_label(name)
        with rc_context(STYLE):
            save_figure(fig, out_dir, formats=formats)
        written.extend(figure_files(out_dir, name, formats))
    return written
