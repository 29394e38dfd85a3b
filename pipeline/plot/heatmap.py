"""Heat maps of a reduced Dataset: one variable over two dimensions (D over frequency x a grid
axis, by default ``alpha``), each cell standing for a value that was computed and for no other
(:func:`cells`):

* a numeric axis of three values or more is drawn to scale: each value's cell reaches to the
  midpoints between it and its neighbours, but no farther from it than the axis's median
  spacing, so that a value far from the others (66 and 80 Hz after a 2 Hz grid) gets a cell
  at most twice the typical width and the range between them shows as not computed;
* a numeric axis of one or two values, and a named axis such as ``contact``, is drawn as one
  equal cell per value at 0, 1, ..., its ticks labelled with the values: two values of α are
  two rows, not a band from 0.5 to 0.9.

What a cell shows:

* its value on the colour scale of :mod:`pipeline.plot.scales` (a diverging map centred at 0
  for a signed quantity such as v, a log scale for D spanning more than two decades), the
  colorbar labelled with the unit (``"D (mm²/s)"``);
* the "not computed" hatch of the axes' background where the map does not have the point
  (:func:`pipeline.plot.flags.absent`: ``present`` False) or nothing was computed -- never a
  colour of the scale, so an absent v is not read as the white of v = 0 -- and a mid grey where
  the point is present but ``var`` is NaN, legend "estimator failed";
* a marker per flag the point carries (:data:`pipeline.plot.flags.FLAGS`: ``o`` non-ergodic,
  ``s`` non-stationary, ``D`` not diffusive, ``^`` accelerating; side by side where a cell
  has several), black with a white edge so that it shows on every colour, a legend above the
  map saying which marker means what;
* optionally contour lines of another variable, or of a callable ``(ds) -> DataArray`` (the
  integer locking ratio k, ...), labelled with their values.

A figure made here is titled with the scene and what it fixes, and the cut (values of other
axes) it shows (:func:`pipeline.plot.titles.figure_title`).

The CI is shown in a second panel beside the map: the relative half-width
(hi - lo) / 2 / |var| in %, where both bounds are known.  Masking cells above a threshold
was the other choice; it was not taken because the threshold would be arbitrary, it hides
what was measured, and near an onset (D -> 0) every relative CI is large, so masking would
blank exactly the region where D is known to be small.  A second panel shows where the map
can be trusted without hiding anything.  Artists carry a ``gid`` (``"map"``, ``"ci"``,
``"failed"``, ``"flag:<flag>"``, ``"absent"``, ``"contours"``) so they can be found again.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr
from matplotlib import rc_context
from matplotlib.axes import Axes
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from .flags import FAILED, FLAGS, NOT_COMPUTED, absent, failed, flagged
from .labels import DRIFT_NOTE, axis_label, symbol
from .scales import value_scale
from .style import PAGE, STYLE, new_figure
from .titles import figure_title

__all__ = ["plot_map", "Cells", "cells", "cell_edges", "relative_half_width", "TO_SCALE_MIN"]

#: a numeric axis with at least this many values is drawn to scale (fewer: one cell each)
TO_SCALE_MIN = 3
#: the "not computed" background: white, hatched in light grey
ABSENT_HATCH, ABSENT_EDGE = "////", "0.7"
#: a failed point's cell; in the CI panel, a present point without a CI
FAILED_GREY, NO_CI_GREY, NO_CI = "0.55", "0.85", "no CI"


def cell_edges(values) -> tuple[np.ndarray, np.ndarray]:
    """(cell centres, edges) tiling one axis: edges at the midpoints, outer edges half a
    spacing beyond (one value: +-0.5, or +-5 % of a non-zero value); names at 0, 1, ....
    The studies' own maps use it; :func:`plot_map` draws :func:`cells`."""
    v = np.asarray(values)
    if v.dtype.kind not in "iuf":
        c = np.arange(len(v), dtype=float)
        return c, np.arange(len(v) + 1, dtype=float) - 0.5
    c = v.astype(float)
    if len(c) == 1:
        h = 0.05 * abs(c[0]) or 0.5
        return c, np.array([c[0] - h, c[0] + h])
    mid = (c[1:] + c[:-1]) / 2
    return c, np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


@dataclass(frozen=True)
class Cells:
    """One axis of a map: each value's position ``centres`` and its cell ``lo``..``hi`` (in
    the axis's unit, or in cell numbers 0, 1, ... where ``to_scale`` is False), the mesh's
    ``edges`` and the mesh column of each value (``index``: columns between them are gaps,
    nothing computed there)."""
    centres: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    edges: np.ndarray
    index: np.ndarray
    to_scale: bool


def cells(values) -> Cells:
    """The cells of one axis (module docstring: to scale from :data:`TO_SCALE_MIN` numeric
    values on, reaching at most the median spacing from the value; else one cell per
    value)."""
    v = np.asarray(values)
    if v.dtype.kind not in "iuf" or len(v) < TO_SCALE_MIN:
        c = np.arange(len(v), dtype=float)
        return Cells(c, c - 0.5, c + 0.5, np.arange(len(v) + 1) - 0.5, np.arange(len(v)), False)
    c = v.astype(float)
    half = float(np.median(np.diff(c)))
    mid = (c[1:] + c[:-1]) / 2
    lo = np.maximum(c - half, np.concatenate([[-np.inf], mid]))
    hi = np.minimum(c + half, np.concatenate([mid, [np.inf]]))
    edges, index = [lo[0]], []
    for a, b in zip(lo, hi, strict=True):
        if a > edges[-1]:
            edges.append(a)  # a gap column: no value computed there
        index.append(len(edges) - 1)
        edges.append(b)
    return Cells(c, lo, hi, np.asarray(edges), np.asarray(index), True)


def relative_half_width(ds: xr.Dataset, var: str) -> xr.DataArray:
    """(``var``_hi - ``var``_lo) / 2 / |``var``|, dimensionless; NaN where a bound or
    ``var`` is NaN, or ``var`` is 0."""
    d = ds[var]
    return ((ds[f"{var}_hi"] - ds[f"{var}_lo"]) / 2 / abs(d).where(d != 0)).rename(
        f"{var}_rel_ci")


def plot_map(ds: xr.Dataset, x: str = "frequency", y: str = "alpha", var: str = "D", *,
             ax: Axes | None = None, ci_ax: Axes | None = None,
             contours: str | Callable[[xr.Dataset], xr.DataArray] | None = None,
             contour_levels=None, ci: bool = True, cmap: str | None = None) -> Figure:
    """Draw ``ds[var]`` over (``x``, ``y``) as a heat map (module docstring: cells, flags,
    absent and failed points, contours), with a colorbar labelled with its unit.

    ax       -- the Axes of the map; None: a new page-wide Figure, titled, with the map and,
                if ``ci`` and ``<var>_lo`` / ``<var>_hi`` exist, the CI panel beside it
    ci_ax    -- with ``ax`` given: the Axes of the CI panel (None: no CI panel)
    contours -- a variable of ``ds`` over (x, y), or a callable ``(ds) -> DataArray`` over
                them; its lines are drawn in white (black on a diverging map) and labelled
                (``contour_levels``: matplotlib's ``levels``, None: its own choice)
    cmap     -- None: the scale's (:mod:`pipeline.plot.scales`)

    Returns the Figure drawn on (``ax.figure`` when ``ax`` is given).  Raises ValueError if
    ``var`` varies along a dimension besides ``x`` and ``y`` (select one value first:
    ``ds.sel(beta=0.5)``).
    """
    extra = [d for d in ds[var].dims if d not in (x, y)]
    if extra or x not in ds[var].dims or y not in ds[var].dims:
        raise ValueError(f"{var} is over {list(ds[var].dims)}: a map needs exactly "
                         f"({x!r}, {y!r}); select one value of the others (ds.sel(...))")
    ds = ds.sortby([a for a in (x, y) if ds[a].dtype.kind in "iuf"])
    with_ci = ci and f"{var}_lo" in ds and f"{var}_hi" in ds
    with rc_context(STYLE):
        own = ax is None
        if own:
            size = (PAGE, 0.45 * PAGE) if with_ci else (0.55 * PAGE, 0.5 * PAGE)
            fig = new_figure(f"map_{var}_{x}-{y}", size, layout="constrained")
            axes = fig.subplots(1, 2) if with_ci else [fig.add_subplot()]
            ax, ci_ax = axes[0], (axes[1] if with_ci else None)
        _draw_map(ds, x, y, var, ax, cmap, contours, contour_levels)
        if ci_ax is not None and with_ci:
            _draw_ci(ds, x, y, var, ci_ax)
        if own:
            note = DRIFT_NOTE if var == "D" and "D_drift" in ds.data_vars else ""
            ax.figure.suptitle(figure_title(ds, ds[var], skip=(x, y), note=note))
    return ax.figure


def _mesh(ds: xr.Dataset, x: str, y: str, ax: Axes) -> tuple[Cells, Cells]:
    cx, cy = cells(ds[x].values), cells(ds[y].values)
    for axis, a, c in ((ax.xaxis, x, cx), (ax.yaxis, y, cy)):
        if not c.to_scale:
            values = ds[a].values
            axis.set_ticks(c.centres, [str(v) if isinstance(v, str) else f"{float(v):g}"
                                       for v in values])
    ax.set_xlabel(axis_label(ds, x))
    ax.set_ylabel(axis_label(ds, y))
    ax.set_xlim(cx.edges[0], cx.edges[-1])
    ax.set_ylim(cy.edges[0], cy.edges[-1])
    ax.add_patch(Rectangle((0, 0), 1, 1, transform=ax.transAxes, facecolor="white",
                           edgecolor=ABSENT_EDGE, hatch=ABSENT_HATCH, lw=0, zorder=-1,
                           gid="absent"))
    return cx, cy


def _on_mesh(values: np.ndarray, cx: Cells, cy: Cells, fill) -> np.ndarray:
    """``values`` over (y, x) placed on the mesh's columns (gap columns ``fill``)."""
    out = np.full((len(cy.edges) - 1, len(cx.edges) - 1), fill, dtype=values.dtype)
    out[np.ix_(cy.index, cx.index)] = values
    return out


def _draw_map(ds, x, y, var, ax, cmap, contours, contour_levels) -> None:
    cx, cy = _mesh(ds, x, y, ax)
    z = ds[var].transpose(y, x)
    gone = absent(ds, var).transpose(y, x).values
    values = z.values.astype(float)
    shown = ~gone & np.isfinite(values)
    scale = value_scale(var, values[shown])
    hide = _on_mesh(~shown, cx, cy, True)
    mesh = ax.pcolormesh(cx.edges, cy.edges, np.ma.masked_where(hide, _on_mesh(values, cx, cy, 0.0)),
                         cmap=cmap or scale.cmap, norm=scale.norm(values[shown]), gid="map")
    ax.figure.colorbar(mesh, ax=ax, label=axis_label(ds, var))
    lost = failed(ds, var).transpose(y, x).values
    if lost.any():
        ax.pcolormesh(cx.edges, cy.edges, np.ma.masked_where(~_on_mesh(lost, cx, cy, False),
                                                             np.ones(hide.shape)),
                      cmap=ListedColormap([FAILED_GREY]), gid="failed")
    handles = [Patch(facecolor=FAILED_GREY, edgecolor="0.3", lw=0.4, label=FAILED)] \
        if lost.any() else []
    if gone.any() or len(cx.edges) > len(cx.centres) + 1 or len(cy.edges) > len(cy.centres) + 1:
        handles.append(Patch(facecolor="white", edgecolor=ABSENT_EDGE, hatch=ABSENT_HATCH,
                             lw=0.4, label=NOT_COMPUTED))
    marks = {f: flagged(ds, f, z).values & ~gone for f in FLAGS}
    count = sum(m.astype(int) for m in marks.values())
    seen = np.zeros_like(count)
    for f, m in marks.items():
        if not m.any():
            continue
        js, is_ = np.nonzero(m)
        k = seen[js, is_] + 1
        seen[js, is_] += 1
        frac = k / (count[js, is_] + 1)
        px = cx.lo[is_] + frac * (cx.hi[is_] - cx.lo[is_])
        ax.plot(px, cy.centres[js], ls="none", marker=f.marker, ms=4.5, mfc="black",
                mec="white", mew=0.6, gid=f"flag:{f.var}")
        handles.append(Line2D([], [], ls="none", marker=f.marker, ms=4.5, mfc="black",
                              mec="white", mew=0.6, label=f.meaning))
    if contours is not None:
        c = (contours(ds) if callable(contours) else ds[contours]).transpose(y, x)
        lines = ax.contour(cx.centres, cy.centres, c.values.astype(float), levels=contour_levels,
                           colors="black" if scale.signed else "white", linewidths=0.6)
        lines.set_gid("contours")
        ax.clabel(lines, fmt="%g", fontsize=6)
    if handles:
        ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.01),
                  ncols=min(len(handles), 2), borderaxespad=0.0, handlelength=1.5,
                  columnspacing=1.0)


def _draw_ci(ds, x, y, var, ax) -> None:
    """The relative CI half-width; a present point without one (a bound unknown: v of an
    accelerating point, D_hi where no particle moved) in light grey, legend "no CI"."""
    cx, cy = _mesh(ds, x, y, ax)
    r = 100 * relative_half_width(ds, var).transpose(y, x).values.astype(float)
    top = float(np.nanmax(r)) if np.isfinite(r).any() else 1.0
    grid = _on_mesh(r, cx, cy, np.nan)
    mesh = ax.pcolormesh(cx.edges, cy.edges, np.ma.masked_invalid(grid), cmap="magma_r", vmin=0,
                         vmax=min(top, 100.0), gid="ci")
    ax.figure.colorbar(mesh, ax=ax, extend="max" if top > 100 else "neither",
                       label=f"CI half-width / {symbol(var)} (%)")
    unknown = ~absent(ds, var).transpose(y, x).values & ~np.isfinite(r)
    if unknown.any():
        ax.pcolormesh(cx.edges, cy.edges,
                      np.ma.masked_where(~_on_mesh(unknown, cx, cy, False), np.ones(grid.shape)),
                      cmap=ListedColormap([NO_CI_GREY]), gid="no_ci")
        ax.legend(handles=[Patch(facecolor=NO_CI_GREY, edgecolor="0.3", lw=0.4, label=NO_CI)],
                  loc="lower left", bbox_to_anchor=(0.0, 1.01), borderaxespad=0.0,
                  handlelength=1.5)
