"""A store's tables as one labelled xarray Dataset: the grid unstacked, ``family`` a dimension,
CF attributes on every variable.

Dimensions: ``frequency`` (Hz), then a grid's axes in the workflow's order (``alpha``,
``contact``, ...; absent without a grid), and ``family`` for what is per family.  NaN where a
point is absent (a grid point left out as invalid, or not computed yet).

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
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from .units import column_unit

__all__ = ["LONG_NAMES", "FAMILY_STEMS", "CONVENTIONS", "tables_dataset", "long_name",
           "same_values"]

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
    (module docstring).  ``axes`` as {axis: values}: each axis has every one of its values,
    those no row has too (NaN), e.g. a value whose every point was left out as invalid."""
    out = xr.Dataset(attrs={"Conventions": CONVENTIONS,
                            "title": "bbb reduce: the tables of a study store",
                            "source": "bbb", **(attrs or {})})
    per_point = sorted(tables.items(), key=lambda item: "family" in item[1].columns)
    for name, df in per_point:
        for var, values in _variables(name, df, list(axes), list(families)):
            if var in out.variables:
                if same_values(out[var], values):
                    continue
                var = f"{name}_{var}"
            out[var] = values
    if isinstance(axes, Mapping):
        out = out.reindex({a: sorted(set(out[a].values.tolist()) | set(v))
                           for a, v in axes.items() if a in out.dims})
    for dim in ("frequency", *axes, "family"):
        if dim in out.coords:
            out[dim].attrs.update(units=column_unit("f" if dim == "frequency" else dim),
                                  long_name=long_name(dim))
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
