"""Axis labels with units, read off a Dataset's attributes: ``"f (Hz)"``, ``"D (mm²/s)"``,
``"α"`` (a dimensionless axis carries no unit), and the words for one value of an axis
(``"α = 0.5"``, ``"rest"``) and for a file name (``"alpha=0.5"``).

A name's unit is its ``units`` attribute; without one, :func:`pipeline.tables.units.unit`
(``frequency`` read as the tables' ``f``); a unit of ``"1"`` or ``""`` is not shown.
"""

from __future__ import annotations

import re

import numpy as np
import xarray as xr

from ..tables.units import unit as table_unit

__all__ = ["SYMBOLS", "symbol", "pretty_unit", "unit_of", "axis_label", "value_label",
           "file_token"]

#: the symbol each known name is shown as (a bbb.Params key, a dimension, a variable); the
#: per-family D and its CI are shown as D, their family naming the line
SYMBOLS = {
    "frequency": "f", "alpha": "α", "beta": "β", "Gamma": "Γ", "mu": "μ", "R": "R", "S": "S",
    "A": "A", "tilt": "tilt", "throw": "throw", "contact": "contact", "family": "family",
    "floor": "floor", "depth": "depth", "peak": "peak",
    "D": "D", "D_family": "D", "v": "v", "D_drift": r"$D_\mathrm{drift}$",
}
_SUPERSCRIPTS = {"2": "²", "3": "³", "-1": "⁻¹", "-2": "⁻²"}


def symbol(name: str) -> str:
    """How ``name`` is written on an axis: its :data:`SYMBOLS` entry, else the name itself."""
    return SYMBOLS.get(name, name)


def pretty_unit(u: str | None) -> str:
    """``"mm^2/s"`` -> ``"mm²/s"``; ``"deg"`` stays; ``"1"``, ``""`` and None -> ``""``."""
    if u is None or u.strip() in ("", "1"):
        return ""
    return re.sub(r"\^(-?\d)", lambda m: _SUPERSCRIPTS.get(m.group(1), "^" + m.group(1)), u)


def unit_of(ds: xr.Dataset | xr.DataArray, name: str) -> str | None:
    """The unit of the variable or coordinate ``name`` of ``ds`` (module docstring), raw."""
    if name in ds.coords or (isinstance(ds, xr.Dataset) and name in ds.data_vars):
        u = ds[name].attrs.get("units")
        if u is not None:
            return str(u)
    return table_unit({"frequency": "f"}.get(name, name))


def axis_label(ds: xr.Dataset | xr.DataArray, name: str) -> str:
    """``"<symbol> (<unit>)"``, or the bare symbol for a dimensionless ``name``; D of a
    Dataset that also has D_drift (a tilted or thrown floor, where D is the raw MSD's slope)
    reads ``"D, drift included (mm²/s)"``."""
    u = pretty_unit(unit_of(ds, name))
    sym = symbol(name)
    if name == "D" and isinstance(ds, xr.Dataset) and "D_drift" in ds.data_vars:
        sym += ", drift included"
    return f"{sym} ({u})" if u else sym


def _number(value) -> str:
    if isinstance(value, str | np.str_):
        return str(value)
    if isinstance(value, bool | np.bool_):
        return str(bool(value))
    return f"{float(value):g}"


def value_label(ds: xr.Dataset | xr.DataArray, name: str, value) -> str:
    """One value of the axis ``name`` in words: ``"α = 0.5"``, ``"R = 2.5 mm"``; a family or
    a contact model by its own name (``"rest"``)."""
    if isinstance(value, str | np.str_):
        return str(value)
    u = pretty_unit(unit_of(ds, name))
    return f"{symbol(name)} = {_number(value)}" + (f" {u}" if u else "")


def file_token(name: str, value) -> str:
    """``name=value`` fit for a file name (``alpha=0.5``, ``contact=stick``): letters,
    digits and ``.=-`` only."""
    return re.sub(r"[^A-Za-z0-9.=-]+", "-", f"{name}={_number(value)}")
