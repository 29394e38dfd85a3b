"""The verdicts a point can be flagged by, and how each is drawn: a flag variable holds True
(passed), False (flagged) or NaN / None (unknown: not flagged).  And which points are there at
all: an absent point (:func:`absent`: the map does not have it, ``present`` False) is drawn as
nothing on a curve and hatched on a map, named "not computed" in the legend; a present point
whose value is NaN (:func:`failed`) is named "estimator failed".

=============  ===================  ===========================================
flag variable  said in the legend   its marker: open on a curve, black with a
                                    white edge on a map (shows on every colour)
=============  ===================  ===========================================
ergodic        non-ergodic          circle ``o``
stationary     non-stationary       square ``s``
diffusive      not diffusive        diamond ``D``
steady         accelerating         triangle ``^``
=============  ===================  ===========================================

``steady`` is False where a conveyor's drift accelerates (the table's v_status
"accelerating", :mod:`bbb.analysis.transport`): v there is a window's mean velocity, not a
drift, and the triangle says so on every curve and map of the point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

__all__ = ["Flag", "FLAGS", "flagged", "failed", "present", "absent", "NOT_COMPUTED", "FAILED"]


@dataclass(frozen=True)
class Flag:
    """One verdict: its variable, what a False means in words, and its marker."""
    var: str
    meaning: str
    marker: str


#: what the legend says of an absent point (the map does not have it: nothing drawn) and of a
#: present point whose value is NaN (its estimator failed)
NOT_COMPUTED, FAILED = "not computed", "estimator failed"

FLAGS = (Flag("ergodic", "non-ergodic", "o"),
         Flag("stationary", "non-stationary", "s"),
         Flag("diffusive", "not diffusive", "D"),
         Flag("steady", "accelerating", "^"))


def _is_false(x) -> bool:
    if x is None or (isinstance(x, float | np.floating) and math.isnan(x)):
        return False
    return not bool(x)


def flagged(ds: xr.Dataset, flag: Flag, like: xr.DataArray) -> xr.DataArray:
    """Booleans over ``like``'s dims: True where ``ds[flag.var]`` is False (broadcast over
    the dims the flag lacks, e.g. ``family``); all False if ``ds`` has no such variable."""
    if flag.var not in ds.data_vars:
        return xr.zeros_like(like, dtype=bool)
    v = ds[flag.var]
    out = xr.DataArray(np.vectorize(_is_false, otypes=[bool])(v.values), dims=v.dims,
                       coords=v.coords)
    return out.broadcast_like(like).transpose(*like.dims)


def present(ds: xr.Dataset, like: xr.DataArray) -> xr.DataArray:
    """True over ``like``'s dims where the map has the point: its presence mask ``present``
    (:func:`pipeline.tables.dataset.presence`, as every Dataset of a store carries it; any
    family for a variable without ``family``).  A Dataset without the mask (built by hand):
    where some number over those dims is not NaN or some text is not empty."""
    if "present" in ds.data_vars:
        p = ds["present"].astype(bool)
        p = p.any([d for d in p.dims if d not in like.dims])
        return p.broadcast_like(like).transpose(*like.dims)
    found = xr.zeros_like(like, dtype=bool)
    for v in ds.data_vars.values():
        if not set(v.dims) <= set(like.dims) | {"family"} or not v.dims:
            continue
        known = (v != "") if v.dtype.kind in "US" else v.notnull()
        if "family" in known.dims and "family" not in like.dims:
            known = known.any("family")
        found = found | known.broadcast_like(like)
    return found.transpose(*like.dims)


def absent(ds: xr.Dataset, var: str) -> xr.DataArray:
    """True where the map does not have the point of ``ds[var]`` (not computed): drawn as
    nothing, never as a failure."""
    return ~present(ds, ds[var])


def failed(ds: xr.Dataset, var: str) -> xr.DataArray:
    """True where the point is present but ``ds[var]`` is NaN: its estimator failed."""
    like = ds[var]
    return present(ds, like) & like.isnull()
