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

A cut the map has no point of (every point absent: ``present`` False, e.g. mu = 0.3 under
stick) is not drawn; one whose points are present but failed is, its failures marked.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Sequence
from pathlib import Path

import xarray as xr
from matplotlib import rc_context
from matplotlib.figure import Figure

from .curve import plot_curve
from .flags import present
from .heatmap import plot_map
from .labels import file_token
from .style import FORMATS, STYLE, figure_files, save_figure

__all__ = ["VARIABLES", "plot_dataset", "grid_axes"]

#: the variables drawn when present, each with its CI bounds <var>_lo, <var>_hi
VARIABLES = ("D", "v", "D_drift")


def grid_axes(ds: xr.Dataset) -> list[str]:
    """The grid axes of ``ds``: the dimensions of D besides ``frequency`` (and ``family``)."""
    return [d for d in ds["D"].dims if d not in ("frequency", "family")]


def _cuts(ds: xr.Dataset, axes: list[str]):
    """(selection, name suffix) for every combination of one value of each of ``axes``."""
    for combo in itertools.product(*(ds[a].values for a in axes)):
        pick = dict(zip(axes, combo, strict=True))
        yield pick, "".join(f"_{file_token(a, v)}" for a, v in pick.items())


def plot_dataset(ds: xr.Dataset, out_dir: str | os.PathLike, *,
                 formats: Sequence[str] = FORMATS) -> list[Path]:
    """Write the figures of the module docstring for the reduced Dataset ``ds`` to
    ``out_dir`` (created if missing); returns the files written, in the order written."""
    axes = grid_axes(ds)
    written: list[Path] = []

    def save(fig: Figure, name: str) -> None:
        fig.set_label(name)
        with rc_context(STYLE):
            save_figure(fig, out_dir, formats=formats)
        written.extend(figure_files(out_dir, name, formats))

    def drawn(cut: xr.Dataset, var: str) -> bool:
        return bool(present(cut, cut[var]).values.any())

    for var in (v for v in VARIABLES if v in ds.data_vars):
        if not axes:
            save(plot_curve(ds, "frequency", var), f"curve_{var}_vs_frequency")
        for hue in axes:
            for pick, suffix in _cuts(ds, [a for a in axes if a != hue]):
                cut = ds.sel(pick)
                if drawn(cut, var):
                    save(plot_curve(cut, "frequency", var, hue=hue),
                         f"curve_{var}_vs_frequency_by_{hue}{suffix}")
    if "D_family" in ds.data_vars:
        for pick, suffix in _cuts(ds, axes):
            cut = ds.sel(pick)
            if drawn(cut, "D_family"):
                save(plot_curve(cut, "frequency", "D_family", hue="family"),
                     f"curve_D_family_vs_frequency{suffix}")
    if ds.sizes["frequency"] >= 2:
        for var in (v for v in VARIABLES if v in ds.data_vars):
            for axis in (a for a in axes if ds.sizes[a] >= 2):
                for pick, suffix in _cuts(ds, [a for a in axes if a != axis]):
                    cut = ds.sel(pick)
                    if drawn(cut, var):
                        save(plot_map(cut, "frequency", axis, var),
                             f"map_{var}_frequency-{axis}{suffix}")
    return written
