"""A named grid axis and the axes that apply under one of its names only, drawn as one axis of
models.

A contact map is a grid of contact x mu, but mu applies under Coulomb friction only
(:data:`pipeline.workflow.point.CONDITIONAL_AXES`): the store has stick and slide at mu = 0 and
Coulomb at each mu, and the product contact x mu is mostly absent.  Cut per value of mu, a
comparison of the contact models falls apart into one figure per mu, none with every model.
:func:`merge_conditional` turns the two axes into one axis named after the named one
(``contact``) whose values are the lines the store has, in the grid's order, each labelled with
the conditional axis's value where it applies: ``stick``, ``slide``, ``coulomb, μ = 0.05``,
``coulomb, μ = 0.3``.  The conditional axis's value of each line stays as a coordinate along
it (``mu``, its attribute :data:`MERGED` naming the axis).  A line none of whose points is
present is left out; nothing else changes.
"""

from __future__ import annotations

import pandas as pd
import xarray as xr

from ..workflow.point import CONDITIONAL_AXES
from .labels import value_label

__all__ = ["merge_conditional", "MERGED"]

#: the attribute of a conditional axis's coordinate along the models: the axis it is merged
#: into (a cut at one model names the model, not the conditional axis's value as well)
MERGED = "merged_into"


def merge_conditional(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with each conditional axis (mu) merged into the named axis it depends on
    (contact) where both are dimensions of ``ds`` (module docstring); ``ds`` itself
    otherwise."""
    for axis, (on, when, _) in CONDITIONAL_AXES.items():
        if axis not in ds.dims or on not in ds.dims:
            continue
        present = ds["present"].astype(bool) if "present" in ds.data_vars else None
        pieces, labels, values = [], [], []
        for name in ds[on].values:
            for value in ds[axis].values:
                pick = {on: name, axis: value}
                if present is not None and not bool(present.sel(pick).any()):
                    continue
                pieces.append(ds.sel(pick, drop=True))
                applies = str(name) == when
                labels.append(f"{name}, {value_label(ds, axis, value)}" if applies else str(name))
                values.append(value)
        merged = xr.concat(pieces, dim=pd.Index(labels, name=on), coords="minimal",
                           compat="override", join="outer")
        merged[on].attrs = dict(ds[on].attrs)
        merged = merged.assign_coords({axis: (on, values, {**ds[axis].attrs, MERGED: on})})
        ds = merged
    return ds
