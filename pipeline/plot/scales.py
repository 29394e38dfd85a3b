"""How a quantity's values are put on an axis or a colour scale: the one rule every figure of
the package follows.

* A **signed** quantity (:data:`SIGNED`: the drift v and what is measured like it) is drawn
  on a linear axis, and on a map in a diverging colour map (:data:`DIVERGING`) centred at 0,
  symmetric about it, so that +15 mm/s and -15 mm/s are equally far from the white of 0.
* Any other quantity (D, D_drift, D per family, ...) is drawn on a **log** axis, and on a
  map with a log colour scale, where its values span more than :data:`LOG_DECADES` decades
  (largest / smallest positive value > 10^2): on a linear axis the small values would sit on
  the floor of the axis.  Where a value is 0 as well (no particle moved), the axis is
  symmetric-log, linear below the smallest positive value, so that 0 is drawn as 0 and not
  dropped.  Otherwise the axis is linear, in a sequential colour map (:data:`SEQUENTIAL`).

Only the values drawn (finite values at points the map has) decide; a CI bound does not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import CenteredNorm, LogNorm, Normalize, SymLogNorm

__all__ = ["SIGNED", "LOG_DECADES", "DIVERGING", "SEQUENTIAL", "Scale", "is_signed",
           "decades", "value_scale", "set_axis_scale"]

#: the quantities that take either sign (their "<name>_lo/_hi" follow them)
SIGNED = frozenset({"v", "dv", "a"})
#: a quantity spanning more decades than this is drawn on a log axis
LOG_DECADES = 2.0
DIVERGING, SEQUENTIAL = "RdBu_r", "viridis"


@dataclass(frozen=True)
class Scale:
    """How one quantity is drawn: ``kind`` "linear", "log" or "symlog" (``linthresh`` the
    symmetric-log's linear range, in the quantity's unit), ``signed``, and its colour map."""
    kind: str
    signed: bool = False
    linthresh: float | None = None

    @property
    def cmap(self) -> str:
        return DIVERGING if self.signed else SEQUENTIAL

    def norm(self, values) -> Normalize:
        """The colour normalisation of ``values`` (NaN ignored) under this scale: centred at
        0 for a signed quantity, log or symmetric-log where :func:`value_scale` says so."""
        v = np.asarray(values, dtype=float)
        v = v[np.isfinite(v)]
        if self.signed:
            half = float(np.max(np.abs(v))) if v.size and np.max(np.abs(v)) > 0 else 1.0
            return CenteredNorm(vcenter=0.0, halfrange=half)
        if self.kind == "log":
            return LogNorm(vmin=float(v.min()), vmax=float(v.max()))
        if self.kind == "symlog":
            return SymLogNorm(linthresh=self.linthresh, vmin=0.0, vmax=float(v.max()), base=10)
        return Normalize(vmin=float(v.min()) if v.size else 0.0,
                         vmax=float(v.max()) if v.size else 1.0)


def is_signed(name: str) -> bool:
    """True for a signed quantity (:data:`SIGNED`) and its CI bounds."""
    return name in SIGNED or name.removesuffix("_lo").removesuffix("_hi") in SIGNED


def decades(values) -> float:
    """log10(largest / smallest) of the positive finite ``values``; 0 with fewer than two."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    return float(np.log10(v.max() / v.min())) if v.size >= 2 else 0.0


def value_scale(name: str, values) -> Scale:
    """The scale of the quantity ``name`` whose drawn values are ``values`` (module
    docstring: the rule)."""
    if is_signed(name):
        return Scale("linear", signed=True)
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if decades(v) <= LOG_DECADES or (v < 0).any():
        return Scale("linear")
    if (v == 0).any():
        return Scale("symlog", linthresh=float(v[v > 0].min()))
    return Scale("log")


def set_axis_scale(ax: Axes, which: str, scale: Scale) -> None:
    """Put ``scale`` on the ``which`` ("x" or "y") axis of ``ax``."""
    setter = ax.set_xscale if which == "x" else ax.set_yscale
    if scale.kind == "symlog":
        setter("symlog", linthresh=scale.linthresh)
    else:
        setter(scale.kind)
