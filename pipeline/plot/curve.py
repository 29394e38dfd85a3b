"""1-D cuts of a reduced Dataset: one variable against one dimension (D against f, by
default) with its confidence interval, one line per value of the remaining dimension.

The CI is read from ``<var>_lo`` / ``<var>_hi`` (same unit as ``var``) and drawn as a band
(``ci="band"``, default: many close points stay readable) or as error bars (``ci="bars"``:
sparse points); a bound that is NaN (D_hi where no particle moved) leaves a gap.  Flagged
points (:data:`pipeline.plot.flags.FLAGS`: non-ergodic, non-stationary, not diffusive) get an
open marker of their flag in the line's colour, one legend entry per flag present saying what
it means.  A point whose estimator failed (``var`` NaN where the point has a row) is not drawn
as a value: a small ``x`` on the lower edge of the axes marks its abscissa instead (legend
"estimator failed").  A point the map does not have (:func:`pipeline.plot.flags.absent`:
``present`` False) is drawn as nothing -- a gap in its line, legend "not computed (gap)" --
and a line none of whose points is present (mu = 0.3 under stick) is not drawn at all.
The value axis follows :mod:`pipeline.plot.scales` (log where D spans more than two decades,
linear with a line at 0 for a signed quantity such as v); a figure made here is titled with the
scene, what it fixes and the cut it shows (:func:`pipeline.plot.titles.figure_title`).
Artists carry a ``gid`` (``"line:<hue>"``, ``"band:<hue>"``, ``"flag:<flag>:<hue>"``,
``"failed"``, ``"zero"``) so they can be found again.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps, rc_context
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.transforms import blended_transform_factory

from .flags import FAILED, FLAGS, NOT_COMPUTED, absent, failed, flagged
from .labels import DRIFT_NOTE, axis_label, value_label
from .scales import set_axis_scale, value_scale
from .style import COLUMN, STYLE, family_color, new_figure
from .titles import figure_title

__all__ = ["plot_curve", "hue_colors"]


def hue_colors(ds: xr.Dataset, hue: str | None, values) -> list:
    """One colour per value of ``hue``: the house colours of the families; a sequential map
    (viridis) over a numeric grid axis; tab10 over named values (contact models)."""
    values = list(values)
    if hue == "family":
        return [family_color(str(v), i) for i, v in enumerate(values)]
    if len(values) <= 1:
        return ["black"]
    if all(isinstance(v, int | float | np.number) for v in values):
        cmap = colormaps["viridis"]
        return [cmap(0.9 * i / (len(values) - 1)) for i in range(len(values))]
    cmap = colormaps["tab10"]
    return [cmap(i % 10) for i in range(len(values))]


def _hue_of(da: xr.DataArray, along: str, hue: str | None) -> str | None:
    rest = [d for d in da.dims if d != along]
    if hue is None and len(rest) == 1:
        return rest[0]
    if hue is not None and hue not in rest:
        raise ValueError(f"hue={hue!r}: not a dimension of {da.name} besides {along!r} "
                         f"(its dims: {list(da.dims)})")
    others = [d for d in rest if d != hue]
    if others:
        raise ValueError(f"{da.name} also varies along {others}: select one value of each "
                         f"(ds.sel({others[0]}=...)) or name one as hue")
    return hue


def plot_curve(ds: xr.Dataset, along: str = "frequency", var: str = "D", *,
               ax: Axes | None = None, hue: str | None = None, ci: str = "band") -> Figure:
    """Draw ``ds[var]`` against the dimension ``along`` with its CI, one line per value of
    ``hue`` (default: the one dimension left besides ``along``, e.g. ``family`` for
    ``D_family`` or a grid axis such as ``alpha``; none left: one line); flags and failed
    points as in the module docstring.  Axis labels carry units (``"f (Hz)"``,
    ``"D (mm²/s)"``).

    ax -- the Axes to draw on; None: a new column-wide Figure in the house style
    ci -- ``"band"`` (shaded lo..hi), ``"bars"`` (error bars) or ``"none"``

    A Figure made here (``ax`` None) is titled (module docstring).
    Returns the Figure drawn on (``ax.figure`` when ``ax`` is given), as every figure
    function of the package does: it is what is saved, and ``fig.axes`` holds the Axes.
    Raises ValueError if ``var`` varies along a dimension that is neither ``along`` nor
    ``hue``.
    """
    if ci not in ("band", "bars", "none"):
        raise ValueError(f"ci={ci!r}; allowed: 'band', 'bars', 'none'")
    with rc_context(STYLE):
        own = ax is None
        if own:
            fig = new_figure(f"curve_{var}_vs_{along}", (1.5 * COLUMN, 0.8 * COLUMN),
                             layout="constrained")
            ax = fig.add_subplot()
        hue = _draw(ds.sortby(along), along, var, ax, hue, ci)
        if own:
            note = DRIFT_NOTE if var in ("D", "D_family") and "D_drift" in ds.data_vars else ""
            ax.figure.suptitle(figure_title(ds, ds[var], skip=(along, hue), note=note))
    return ax.figure


def _draw(ds: xr.Dataset, along: str, var: str, ax: Axes, hue: str | None,
          ci: str) -> str | None:
    """Draw the curves; returns the hue dimension used (None: one line)."""
    da = ds[var]
    hue = _hue_of(da, along, hue)
    values = list(ds[hue].values) if hue else [None]
    colors = hue_colors(ds, hue, values)
    x = ds[along].values
    bad = failed(ds, var)
    gone = absent(ds, var)
    flags = {f: flagged(ds, f, da) for f in FLAGS}
    shown, gaps, drawn = set(), False, []
    for value, color in zip(values, colors, strict=True):
        pick = {hue: value} if hue else {}
        tag = "" if hue is None else str(value)
        off = gone.sel(pick).values
        if off.all():
            continue  # the map has no point on this line
        gaps = gaps or bool(off.any())
        y = np.where(off, np.nan, da.sel(pick).values.astype(float))
        drawn.append(y)
        label = value_label(ds, hue, value) if hue else None
        ax.plot(x, y, "-", marker=".", ms=3, color=color, label=label, gid=f"line:{tag}")
        lo, hi = (ds[f"{var}{s}"].sel(pick).values.astype(float) if f"{var}{s}" in ds else None
                  for s in ("_lo", "_hi"))
        if lo is not None and hi is not None and ci == "band":
            ax.fill_between(x, lo, hi, color=color, alpha=0.25, lw=0, gid=f"band:{tag}")
        elif lo is not None and hi is not None and ci == "bars":
            err = np.vstack([y - lo, hi - y])
            ax.errorbar(x, y, yerr=np.where(np.isfinite(err), err, 0.0), fmt="none",
                        ecolor=color, elinewidth=0.6, capsize=1.5, gid=f"bars:{tag}")
        for f, mask in flags.items():
            m = mask.sel(pick).values & np.isfinite(y)
            if m.any():
                shown.add(f)
                ax.plot(x[m], y[m], ls="none", marker=f.marker, ms=5, mfc="none", mew=0.7,
                        color=color, gid=f"flag:{f.var}:{tag}")
    handles, labels = ax.get_legend_handles_labels()
    for f in (f for f in FLAGS if f in shown):
        handles.append(Line2D([], [], ls="none", marker=f.marker, ms=5, mfc="none", mew=0.7,
                              color="0.3"))
        labels.append(f.meaning)
    lost = bad.any([d for d in bad.dims if d != along]).values if bad.ndim > 1 else bad.values
    if lost.any():
        ax.plot(x[lost], np.full(lost.sum(), 0.02), ls="none", marker="x", ms=4, color="0.3",
                transform=blended_transform_factory(ax.transData, ax.transAxes), gid="failed",
                clip_on=False)
        handles.append(Line2D([], [], ls="none", marker="x", ms=4, color="0.3"))
        labels.append(FAILED)
    if gaps:
        handles.append(Line2D([], [], ls="none"))
        labels.append(f"{NOT_COMPUTED} (gap)")
    scale = value_scale(var, np.concatenate(drawn) if drawn else [])
    set_axis_scale(ax, "y", scale)
    if scale.signed:
        ax.axhline(0.0, color="0.5", lw=0.5, ls=":", zorder=0, gid="zero")
    ax.set_xlabel(axis_label(ds, along))
    ax.set_ylabel(axis_label(ds, var))
    if handles:
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                  borderaxespad=0.0)
    return hue
