"""Heat maps of a reduced Dataset: one variable over two dimensions (D over frequency x a grid
axis, by default ``alpha``), on the grid as it is (possibly non-uniform: cell edges at the
midpoints between neighbouring values, the outer edges half a spacing beyond; a named axis
such as ``contact`` one cell per name).

What a cell shows:

* its value on a colour scale, the colorbar labelled with the unit (``"D (mm²/s)"``);
* blank (the axes' background) where the point is absent -- the map does not have it
  (:func:`pipeline.plot.flags.absent`: ``present`` False), legend "not computed" -- and
  light grey where the point is present but ``var`` is NaN, legend "estimator failed";
* hatched where the point is flagged (:data:`pipeline.plot.flags.FLAGS`: ``////``
  non-ergodic, ``\\\\`` non-stationary, ``..`` not diffusive; a cell with two flags carries
  both), a legend above the map saying which hatch means what;
* optionally contour lines of another variable, or of a callable ``(ds) -> DataArray`` (the
  integer locking ratio k, ...), labelled with their values.

The CI is shown in a second panel beside the map: the relative half-width
(hi - lo) / 2 / |var| in %, where both bounds are known.  Masking cells above a threshold
was the other choice; it was not taken because the threshold would be arbitrary, it hides
what was measured, and near an onset (D -> 0) every relative CI is large, so masking would
blank exactly the region where D is known to be small.  A second panel shows where the map
can be trusted without hiding anything.  Artists carry a ``gid`` (``"map"``, ``"ci"``,
``"failed"``, ``"hatch:<flag>"``, ``"contours"``) so they can be found again.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import xarray as xr
from matplotlib import rc_context
from matplotlib.axes import Axes
from matplotlib.collections import PatchCollection
from matplotlib.figure import Figure
from matplotlib.patches import Patch, Rectangle

from .curve import fixed_coords
from .flags import FAILED, FLAGS, NOT_COMPUTED, absent, failed, flagged
from .labels import axis_label, symbol
from .style import PAGE, STYLE, new_figure

__all__ = ["plot_map", "cell_edges", "relative_half_width"]


def cell_edges(values) -> tuple[np.ndarray, np.ndarray]:
    """(cell centres, cell edges) of one axis: numbers as they are, edges at the midpoints
    (outer edges half a spacing beyond; one value: +-0.5, or +-5 % of a non-zero value);
    names (strings) at 0, 1, 2, ... with edges halfway."""
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


def relative_half_width(ds: xr.Dataset, var: str) -> xr.DataArray:
    """(``var``_hi - ``var``_lo) / 2 / |``var``|, dimensionless; NaN where a bound or
    ``var`` is NaN, or ``var`` is 0."""
    d = ds[var]
    return ((ds[f"{var}_hi"] - ds[f"{var}_lo"]) / 2 / abs(d).where(d != 0)).rename(
        f"{var}_rel_ci")


def plot_map(ds: xr.Dataset, x: str = "frequency", y: str = "alpha", var: str = "D", *,
             ax: Axes | None = None, ci_ax: Axes | None = None,
             contours: str | Callable[[xr.Dataset], xr.DataArray] | None = None,
             contour_levels=None, ci: bool = True, cmap: str = "viridis") -> Figure:
    """Draw ``ds[var]`` over (``x``, ``y``) as a heat map (module docstring: cells, flags,
    absent and failed points, contours), with a colorbar labelled with its unit.

    ax       -- the Axes of the map; None: a new page-wide Figure with the map and, if ``ci``
                and ``<var>_lo`` / ``<var>_hi`` exist, the CI panel beside it
    ci_ax    -- with ``ax`` given: the Axes of the CI panel (None: no CI panel)
    contours -- a variable of ``ds`` over (x, y), or a callable ``(ds) -> DataArray`` over
                them; its lines are drawn in white and labelled (``contour_levels``:
                matplotlib's ``levels``, None: its own choice)

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
        if ax is None:
            size = (PAGE, 0.4 * PAGE) if with_ci else (0.55 * PAGE, 0.45 * PAGE)
            fig = new_figure(f"map_{var}_{x}-{y}", size, layout="constrained")
            axes = fig.subplots(1, 2) if with_ci else [fig.add_subplot()]
            ax, ci_ax = axes[0], (axes[1] if with_ci else None)
        _draw_map(ds, x, y, var, ax, cmap, contours, contour_levels)
        if ci_ax is not None and with_ci:
            _draw_ci(ds, x, y, var, ci_ax)
    return ax.figure


def _mesh(ds: xr.Dataset, x: str, y: str, ax: Axes):
    (cx, ex), (cy, ey) = cell_edges(ds[x].values), cell_edges(ds[y].values)
    for axis, a, c in ((ax.xaxis, x, cx), (ax.yaxis, y, cy)):
        if ds[a].dtype.kind not in "iuf":
            axis.set_ticks(c, [str(v) for v in ds[a].values])
    ax.set_xlabel(axis_label(ds, x))
    ax.set_ylabel(axis_label(ds, y))
    return cx, ex, cy, ey


def _draw_map(ds, x, y, var, ax, cmap, contours, contour_levels) -> None:
    cx, ex, cy, ey = _mesh(ds, x, y, ax)
    z = ds[var].transpose(y, x)
    gone = absent(ds, var).transpose(y, x).values
    values = z.values.astype(float)
    mesh = ax.pcolormesh(ex, ey, np.ma.masked_where(gone | ~np.isfinite(values), values),
                         cmap=cmap, gid="map")
    label = axis_label(ds, var)
    where = fixed_coords(z, skip=(x, y))
    ax.figure.colorbar(mesh, ax=ax, label=f"{label}, {where}" if where else label)
    lost = failed(ds, var).transpose(y, x).values
    if lost.any():
        ax.pcolormesh(ex, ey, np.ma.masked_where(~lost, np.ones(lost.shape)), cmap="Greys",
                      vmin=0, vmax=4, gid="failed")
    handles = [Patch(facecolor="0.85", edgecolor="0.5", label=FAILED)] if lost.any() else []
    if gone.any():
        handles.append(Patch(facecolor=ax.get_facecolor(), edgecolor="0.5", lw=0.4,
                             label=NOT_COMPUTED))
    for f in FLAGS:
        cells = flagged(ds, f, z).values & ~gone
        if not cells.any():
            continue
        rects = [Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j])
                 for j, i in zip(*np.nonzero(cells), strict=True)]
        ax.add_collection(PatchCollection(rects, facecolor="none", edgecolor="0.15", lw=0,
                                          hatch=f.hatch, gid=f"hatch:{f.var}"))
        handles.append(Patch(facecolor="white", edgecolor="0.15", hatch=f.hatch, lw=0.4,
                             label=f.meaning))
    if contours is not None:
        c = (contours(ds) if callable(contours) else ds[contours]).transpose(y, x)
        lines = ax.contour(cx, cy, c.values.astype(float), levels=contour_levels,
                           colors="white", linewidths=0.6)
        lines.set_gid("contours")
        ax.clabel(lines, fmt="%g", fontsize=6)
    if handles:
        ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0.0, 1.01),
                  ncols=min(len(handles), 2), borderaxespad=0.0, handlelength=1.5, columnspacing=1.0)


def _draw_ci(ds, x, y, var, ax) -> None:
    _, ex, _, ey = _mesh(ds, x, y, ax)
    r = 100 * relative_half_width(ds, var).transpose(y, x).values.astype(float)
    top = float(np.nanmax(r)) if np.isfinite(r).any() else 1.0
    mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(r), cmap="magma_r", vmin=0,
                         vmax=min(top, 100.0), gid="ci")
    ax.figure.colorbar(mesh, ax=ax, extend="max" if top > 100 else "neither",
                       label=f"CI half-width / {symbol(var)} (%)")
