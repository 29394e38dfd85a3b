"""Synthetic reduced Datasets shaped as ``open_study(path, reduced=True)`` returns them with a
``[grid]`` (the contract of pipeline/plot/): dims ``frequency`` and grid axes, ``family`` for
the per-family variables, NaN where a point is absent, ``units`` / ``long_name`` on every
variable and coordinate."""

from __future__ import annotations

import numpy as np
import xarray as xr

D_UNITS = {"units": "mm^2/s", "long_name": "diffusion coefficient"}


def reduced(freqs=(50.0, 55.0, 62.0, 70.0, 80.0), alphas=(0.5, 0.6, 0.8),
            families=("rest", "launched"), velocity=False) -> xr.Dataset:
    """D(f, alpha) = 100 alpha (1 + sin(f / 5)) with a 10 % CI, every point present, every
    flag True; per-family D 5 % apart; ``velocity``: v and D_drift too."""
    f = np.asarray(freqs, float)
    a = np.asarray(alphas, float)
    d = 100 * a[None, :] * (1 + np.sin(f[:, None] / 5)) + 10
    dims = ("frequency", "alpha")
    ds = xr.Dataset(coords={
        "frequency": ("frequency", f, {"units": "Hz", "long_name": "floor frequency"}),
        "alpha": ("alpha", a, {"units": "1", "long_name": "normal restitution"}),
        "family": ("family", list(families), {"units": "", "long_name": "initial condition"}),
    })
    ds["D"] = (dims, d, D_UNITS)
    ds["D_lo"] = (dims, 0.9 * d, D_UNITS)
    ds["D_hi"] = (dims, 1.1 * d, D_UNITS)
    for flag in ("ergodic", "stationary", "diffusive"):
        ds[flag] = (dims, np.ones_like(d, dtype=bool), {"units": "", "long_name": flag})
    ds["Gamma"] = (dims, (2 * np.pi * f[:, None]) ** 2 * 0.1 / 9810 + 0 * a[None, :],
                   {"units": "1", "long_name": "dimensionless amplitude"})
    scale = 1 + 0.05 * np.arange(len(families))
    fam = d[:, :, None] * scale[None, None, :]
    fdims = (*dims, "family")
    ds["D_family"] = (fdims, fam, D_UNITS)
    ds["D_family_lo"] = (fdims, 0.9 * fam, D_UNITS)
    ds["D_family_hi"] = (fdims, 1.1 * fam, D_UNITS)
    if velocity:
        v = 3 * a[None, :] + 0.01 * f[:, None]
        vu = {"units": "mm/s", "long_name": "drift velocity"}
        ds["v"], ds["v_lo"], ds["v_hi"] = (dims, v, vu), (dims, v - 0.2, vu), (dims, v + 0.2, vu)
        ds["D_drift"] = (dims, 0.8 * d, D_UNITS)
        ds["D_drift_lo"] = (dims, 0.7 * d, D_UNITS)
        ds["D_drift_hi"] = (dims, 0.9 * d, D_UNITS)
    return ds


def absent(ds: xr.Dataset, **point) -> xr.Dataset:
    """``ds`` with the point ``point`` absent: NaN in every variable (flags become floats)."""
    out = ds.copy(deep=True)
    for name, var in out.data_vars.items():
        if set(point) <= set(var.dims):
            values = var.values.astype(float)
            idx = tuple(list(ds[d].values).index(point[d]) if d in point else slice(None)
                        for d in var.dims)
            values[idx] = np.nan
            out[name] = (var.dims, values, var.attrs)
    return out


def failed(ds: xr.Dataset, var: str = "D", **point) -> xr.Dataset:
    """``ds`` with ``var`` and its CI NaN at ``point`` (the estimator failed; the row stays)."""
    out = ds.copy(deep=True)
    for name in (var, f"{var}_lo", f"{var}_hi"):
        out[name].loc[point] = np.nan
    return out


def flag(ds: xr.Dataset, name: str, **point) -> xr.Dataset:
    """``ds`` with the flag ``name`` False (flagged) at ``point``."""
    out = ds.copy(deep=True)
    out[name].loc[point] = False
    return out
