"""A store's tables as one labelled xarray Dataset: the grid unstacked, ``family`` a dimension,
CF attributes on every variable.

Dimensions: ``frequency`` (Hz), then a grid's axes in the workflow's order (``alpha``,
``contact``, ...; absent without a grid), and ``family`` for what is per family; each axis's
values where :func:`pipeline.workflow.point.map_coords` puts them (mu = 0 of a stick point
among mu's values, as the store and the tables record it).

Absent points: a cell of the map that no point holds (mu = 0.3 under stick, a point skipped
as invalid, a cell ``[grid.refine]`` did not add) or a point without a done chunk is absent,
and an absent point looks the same in every view of a store (``open_study``, with or without
``reduced=True``, :func:`pipeline.api.reduced_dataset`, the figures): every variable NaN
there (text ``""``), and the boolean variable ``present`` (:func:`presence`, over
``frequency``, the axes and ``family``) False.  NaN where ``present`` is True is a value
that was computed and failed (D where its estimator failed), never an absent point.

* Columns of a table with a row per point (``diffusion``, ``mechanisms``) are variables over
  the point dimensions; the per-family columns among them (``D_<family>``,
  ``D_<family>_lo``/``_hi``, ``EB_<family>``, ``EB_decay_<family>``) become one variable each
  with a ``family`` dimension: ``D_family``, ``D_family_lo``, ``D_family_hi``, ``EB_family``,
  ``EB_decay_family``.
* Columns of a table with a row per (point, family) (``counters``, ``contact``, ``locking``)
  are variables over the point dimensions and ``family``; a column two tables share keeps
  its plain name where the values agree, else it is ``<table>_<column>``.
* Every variable has ``units`` (:mod:`pipeline.tables.units`) and ``long_name``
  (:data:`LONG_NAMES`, else what the column is called in its table), ``source``, ``table``
  and ``column``; flag
  columns (True/False/unknown) are floats 1/0/NaN and text columns strings ("" where
  absent), so ``to_netcdf`` writes the Dataset as it is.  Dataset attributes: ``Conventions``
  (CF-1.10), ``title``, ``source`` and what the caller adds (the store's fingerprint).
* The scene's fixed parameters (every ``[params]`` key that is not an axis of the grid and
  holds one value at every point: ``tilt``, ``throw``, ``contact``, ``alpha``, ``R``, ...)
  are scalar coordinates with ``units`` and ``long_name`` (:func:`fixed_params`), so a
  Dataset written to netCDF says where it was computed, and Datasets of two scenes
  concatenate along any of them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd
import xarray as xr

from ..workflow.point import map_coords
from .units import column_unit

if TYPE_CHECKING:
    from ..workflow.study import Study

__all__ = ["LONG_NAMES", "FAMILY_STEMS", "CONVENTIONS", "PRESENT_ATTRS", "tables_dataset", "fixed_params",
           "long_name", "same_values", "presence", "mask_absent"]

CONVENTIONS = "CF-1.10"

#: per-family column stems of the tables with a row per point: ``<stem>_<family><suffix>``
FAMILY_STEMS = ("D", "EB", "EB_decay")
_SUFFIXES = ("", "_lo", "_hi")

#: long names of the columns people read first (others: their table's column name)
LONG_NAMES: dict[str, str] = {
    "frequency": "floor frequency f",
    "family": "initial-condition family",
    "Gamma": "peak floor acceleration A (2 pi f)^2 / g",
    "D": "diffusion coefficient, all families pooled",
    "D_lo": "lower bound of the confidence interval of D",
    "D_hi": "upper bound of the confidence interval of D",
    "D_family": "diffusion coefficient of the family",
    "D_family_lo": "lower bound of the confidence interval of the family's D",
    "D_family_hi": "upper bound of the confidence interval of the family's D",
    "D_status": "what the confidence interval of D means",
    "D_last": "single-origin MSD(t_end) / (2 t_end)",
    "EB": "ergodicity-breaking parameter, all families pooled",
    "EB_family": "ergodicity-breaking parameter of the family",
    "EB_decay_family": "EB of the first half over EB of the whole run, of the family",
    "ergodic": "ergodic under the verdict rule (1 true, 0 false)",
    "stationary": "D independent of the run length (1 true, 0 false)",
    "diffusive": "MSD about the drift linear over the fit lags (1 true, 0 false)",
    "v": "drift velocity",
    "v_lo": "lower bound of the confidence interval of v",
    "v_hi": "upper bound of the confidence interval of v",
    "D_drift": "diffusion coefficient about the drift",
    "D_drift_lo": "lower bound of the confidence interval of D_drift",
    "D_drift_hi": "upper bound of the confidence interval of D_drift",
    "n_particles": "particles analysed",
    "t_max": "simulated time",
}

#: the attributes of the presence mask ``present`` (CF flag attributes; stored as 0/1 by
#: ``to_netcdf``)
PRESENT_ATTRS = {
    "units": "",
    "long_name": "the map has the point and the family has data there (a chunk done)",
    "flag_values": [0, 1],
    "flag_meanings": "absent present",
    "comment": "absent: no point of the map at these values (a conditional axis such as mu "
               "away from its condition, a point skipped as invalid, a cell a refined map "
               "did not add) or no chunk done there; every variable is NaN (text empty) "
               "there. NaN where present is a value that failed (an estimator failure).",
}


def long_name(column: str, table: str = "") -> str:
    """The CF long name of ``column`` (:data:`LONG_NAMES`, else named after its table)."""
    if column in LONG_NAMES:
        return LONG_NAMES[column]
    return f"{column} ({table} table of bbb reduce)" if table else column


def tables_dataset(tables: Mapping[str, pd.DataFrame],
                   axes: Sequence[str] | Mapping[str, Sequence] = (),
                   families: Sequence[str] = (), attrs: Mapping[str, str] | None = None
                   ) -> xr.Dataset:
    """The Dataset of ``tables`` ({name: DataFrame} as :func:`pipeline.tables.catalog.tables`
    gives them) of a study whose grid has ``axes`` and whose families are ``families``
    (module docstring).  ``axes`` as {axis: values} (``frequency`` may be among them, as
    :func:`pipeline.workflow.point.map_coords` gives them): each axis has these values in
    this order, those no row has too (NaN), e.g. a value whose every point was left out as
    invalid; ``family`` is in the order of ``families``.  Nothing is masked here: absent
    points as the tables have them (:func:`mask_absent` and :func:`presence` make the
    store's mask)."""
    out = xr.Dataset(attrs={"Conventions": CONVENTIONS,
                            "title": "bbb reduce: the tables of a study store",
                            "source": "bbb", **(attrs or {})})
    names = [a for a in axes if a != "frequency"]
    per_point = sorted(tables.items(), key=lambda item: "family" in item[1].columns)
    for name, df in per_point:
        for var, values in _variables(name, df, names, list(families)):
            if var in out.variables:
                if same_values(out[var], values):
                    continue
                var = f"{name}_{var}"
            out[var] = values
    order = dict(axes) if isinstance(axes, Mapping) else {}
    if families:
        order["family"] = families
    out = _filled(out.reindex({a: _ordered(v, out[a].values) for a, v in order.items()
                               if a in out.dims}))
    for dim in ("frequency", *names, "family"):
        if dim in out.coords:
            out[dim].attrs.update(units=column_unit("f" if dim == "frequency" else dim),
                                  long_name=long_name(dim))
    return out


def _ordered(listed: Sequence, have) -> list:
    """``listed`` in its order, then any value of ``have`` it lacks (sorted)."""
    listed = list(listed)
    return listed + sorted(set(np.asarray(have).tolist()) - set(listed))


def _filled(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with its text variables' missing values ``""`` (a reindex leaves NaN)."""
    for name, var in ds.data_vars.items():
        if var.dtype == object:
            ds[name] = var.fillna("").astype(str).assign_attrs(var.attrs)
    return ds


def fixed_params(study: Study) -> dict[str, xr.DataArray]:
    """{key: scalar coordinate} of every ``[params]`` key (:data:`~pipeline.workflow.keys.
    GRID_AXES`) that is not one of the study's grid axes and has one value at all its
    points (the bbb.Params each point resolves to; A is left out where ``Gamma`` sets it per
    frequency, Gamma itself is a column of the tables), with ``units`` and ``long_name``
    from the workflow's maps."""
    from ..workflow.keys import GRID_AXES, PARAM_LONG_NAMES, PARAM_UNITS

    axes = {a for a, _ in study.grid}
    out: dict[str, xr.DataArray] = {}
    for key in GRID_AXES:
        if key in axes or not study.points:
            continue
        values = {getattr(p.params, key, None) for p in study.points}
        if len(values) != 1 or None in values:
            continue
        (value,) = values
        out[key] = xr.DataArray(value, attrs={"units": PARAM_UNITS.get(key, ""),
                                              "long_name": PARAM_LONG_NAMES.get(key, key)})
    return out


def presence(study: Study, done: np.ndarray) -> xr.DataArray:
    """The presence mask ``present`` of a store of ``study`` whose done markers are ``done``
    (bool (point, family, chunk), :meth:`pipeline.store.study_store.StudyStore.done`): over
    ``frequency``, the grid's axes (:func:`pipeline.workflow.point.map_coords`) and
    ``family``, True where the store holds the point and the family has a chunk done there,
    False at every other cell (module docstring).  Attributes :data:`PRESENT_ATTRS`."""
    coords = map_coords(study.grid, study.points)
    families = [f.name for f in study.families]
    where = {d: {v: i for i, v in enumerate(vs)} for d, vs in coords.items()}
    mask = np.zeros([len(v) for v in coords.values()] + [len(families)], dtype=bool)
    has = np.asarray(done, dtype=bool).any(axis=2)
    for pi, p in enumerate(study.points):
        at = dict(p.grid, frequency=float(p.f))
        mask[tuple(where[d][at[d]] for d in coords)] = has[pi]
    return xr.DataArray(mask, dims=[*coords, "family"],
                        coords={**{d: list(v) for d, v in coords.items()}, "family": families},
                        name="present", attrs=dict(PRESENT_ATTRS))


def mask_absent(ds: xr.Dataset, present: xr.DataArray) -> xr.Dataset:
    """``ds`` with every variable over ``present``'s dimensions (or some of them) NaN, text
    ``""``, where the point is absent: where ``present`` is False, for a variable without
    ``family`` where it is False for every family."""
    out = ds.copy()
    for name, var in ds.data_vars.items():
        if name == "present" or not var.dims or not set(var.dims) <= set(present.dims):
            continue
        here = present.any([d for d in present.dims if d not in var.dims])
        if var.dtype.kind in "UO":
            out[name] = var.where(here, "").fillna("").astype(str).assign_attrs(var.attrs)
        else:
            out[name] = var.where(here).assign_attrs(var.attrs)
    return out


def _variables(name: str, df: pd.DataFrame, axes: list[str], families: list[str]):
    """(variable name, DataArray) of every column of one table."""
    frame = df.rename(columns={"f": "frequency"})
    index = ["frequency", *axes] + (["family"] if "family" in frame.columns else [])
    frame = frame.drop(columns=[c for c in ("initial",) if c in frame.columns])
    frame = frame.set_index(index)
    if "family" in index:
        for col in frame.columns:
            yield col, _array(frame[col], col, name)
        return
    grouped = _family_columns(frame.columns, families)
    for col in frame.columns:
        if col in grouped:
            continue
        yield col, _array(frame[col], col, name)
    by_var: dict[str, dict[str, str]] = {}
    for col, (var, fam) in grouped.items():
        by_var.setdefault(var, {})[fam] = col
    for var, cols in by_var.items():
        long = frame[list(cols.values())].rename(columns={c: f for f, c in cols.items()})
        long.columns.name = "family"
        series = long.stack(future_stack=True)
        unit_col = next(iter(cols.values()))
        da = _array(series, var, name, unit_of=unit_col)
        da.attrs["column"] = var.replace("_family", "_<family>")  # D_<family>_lo
        yield var, da


def _family_columns(columns, families: list[str]) -> dict[str, tuple[str, str]]:
    """{column: (variable, family)} of the per-family columns (``D_rest_lo`` ->
    (``D_family_lo``, ``rest``))."""
    out = {}
    for fam in families:
        for stem in FAMILY_STEMS:
            for suffix in _SUFFIXES:
                col = f"{stem}_{fam}{suffix}"
                if col in columns:
                    out[col] = (f"{stem}_family{suffix}", fam)
    return out


def _array(series: pd.Series, col: str, table: str, unit_of: str | None = None) -> xr.DataArray:
    """One column as a DataArray over its index levels (the product of their values: NaN
    where a combination has no row), with CF attributes and netCDF-safe values."""
    values = series
    if isinstance(values.dtype, pd.BooleanDtype) or values.dtype == bool:
        values = values.astype("Float64").astype(float)  # 1/0, NaN unknown
    elif values.dtype == object:
        if all(isinstance(v, str) or v is None or (isinstance(v, float) and np.isnan(v))
               for v in values):
            values = values.fillna("").astype(str)
        else:
            values = pd.to_numeric(values, errors="coerce")
    da = xr.DataArray.from_series(values)
    if da.dtype == object:
        da = da.fillna("").astype(str)
    unit = column_unit(unit_of or col)
    da.attrs = {"units": unit, "long_name": long_name(col, table),
                "source": f"bbb reduce: {table} table", "table": table,
                "column": unit_of or col}
    return da


def same_values(a: xr.DataArray, b: xr.DataArray) -> bool:
    """Two variables hold the same values: aligned on their coordinates and broadcast against
    each other, NaN equal to NaN."""
    try:
        x, y = xr.align(a, b, join="outer")
        x, y = xr.broadcast(x, y)
        return bool(x.variable.equals(y.variable))
    except (ValueError, TypeError):
        return False
