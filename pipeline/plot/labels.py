"""Axis labels with units: ``"f (Hz)"``, ``"D (mm²/s)"``, ``"α"`` (a dimensionless axis
carries no unit), and the words for one value of an axis (``"α = 0.5"``, ``"tilt = 3°"``,
``"rest"``) and for a file name (``"alpha=0.5"``).

One label per quantity, whatever Dataset it is drawn from: its symbol (:data:`SYMBOLS`) and
its unit from the one units map, :func:`pipeline.tables.units.unit` (``frequency`` read as the
tables' ``f``); only a name the map does not know (a study's own variable) takes its
``units`` attribute.  A unit of ``"1"`` or ``""`` is not shown.  D on a floor that drifts is
still D (the raw MSD's slope, which there includes the drift): the figures of such a Dataset
say so in a note (:data:`DRIFT_NOTE`), not in a second label for the same quantity.
"""

from __future__ import annotations

import re

import numpy as np
import xarray as xr

from ..tables.units import unit as table_unit

__all__ = ["SYMBOLS", "DRIFT_NOTE", "symbol", "pretty_unit", "unit_of", "axis_label",
           "value_label", "file_token"]

#: the symbol each known name is shown as (a bbb.Params key, a dimension, a variable); the
#: per-family D and its CI are shown as D, their family naming the line
SYMBOLS = {
    "frequency": "f", "alpha": "α", "beta": "β", "Gamma": "Γ", "mu": "μ", "R": "R", "S": "S",
    "A": "A", "tilt": "tilt", "throw": "throw", "contact": "contact", "family": "family",
    "floor": "floor", "depth": "depth", "peak": "peak",
    "D": "D", "D_family": "D", "v": "v", "D_drift": r"$D_\mathrm{drift}$",
}
#: said under the title of a D figure of a Dataset that also has D_drift (a tilted or thrown
#: floor)
DRIFT_NOTE = r"D: the raw MSD's slope, drift included; $D_\mathrm{drift}$: about the drift"
_SUPERSCRIPTS = {"2": "²", "3": "³", "-1": "⁻¹", "-2": "⁻²"}


def symbol(name: str) -> str:
    """How ``name`` is written on an axis: its :data:`SYMBOLS` entry, else the name itself."""
    return SYMBOLS.get(name, name)


def pretty_unit(u: str | None) -> str:
    """``"mm^2/s"`` -> ``"mm²/s"``; ``"degree"`` -> ``"°"``; ``"1"``, ``""`` and None ->
    ``""``."""
    if u is None or u.strip() in ("", "1"):
        return ""
    if u.strip() in ("degree", "degrees", "deg"):
        return "°"
    return re.sub(r"\^(-?\d)", lambda m: _SUPERSCRIPTS.get(m.group(1), "^" + m.group(1)), u)


def unit_of(ds: xr.Dataset | xr.DataArray, name: str) -> str | None:
    """The unit of ``name`` (module docstring: the units map, else ``ds``'s ``units``
    attribute of it), raw; None if neither knows."""
    found = table_unit({"frequency": "f", "D_family": "D"}.get(name, name))
    if found is not None:
        return found
    if name in ds.coords or (isinstance(ds, xr.Dataset) and name in ds.data_vars):
        u = ds[name].attrs.get("units")
        if u is not None:
            return str(u)
    return None


def axis_label(ds: xr.Dataset | xr.DataArray, name: str) -> str:
    """``"<symbol> (<unit>)"``, or the bare symbol for a dimensionless ``name``: the same
    for ``name`` in every Dataset whose units agree with the map."""
    u = pretty_unit(unit_of(ds, name))
    sym = symbol(name)
    return f"{sym} ({u})" if u else sym


def _number(value) -> str:
    if isinstance(value, str | np.str_):
        return str(value)
    if isinstance(value, bool | np.bool_):
        return str(bool(value))
    return f"{float(value):g}"


def value_label(ds: xr.Dataset | xr.DataArray, name: str, value, named: bool = False) -> str:
    """One value of the axis ``name`` in words: ``"α = 0.5"``, ``"R = 2.5 mm"``,
    ``"tilt = 3°"``; a family or a contact model by its own name (``"rest"``), or with
    ``named`` as ``"contact = slide"``."""
    if isinstance(value, str | np.str_):
        return f"{symbol(name)} = {value}" if named else str(value)
    u = pretty_unit(unit_of(ds, name))
    sep = "" if u == "°" else " "
    return f"{symbol(name)} = {_number(value)}" + (f"{sep}{u}" if u else "")


def file_token(name: str, value) -> str:
    """``name=value`` fit for a file name (``alpha=0.5``, ``contact=stick``): letters,
    digits and ``.=-`` only."""
    return re.sub(r"[^A-Za-z0-9.=-]+", "-", f"{name}={_number(value)}")
