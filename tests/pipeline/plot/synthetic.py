"""Synthetic reduced Datasets shaped as ``open_study(path, reduced=True)`` returns them with a
``[grid]`` (the contract of pipeline/plot/): dims ``frequency`` and grid axes, ``family`` for
the per-family variables, ``units`` / ``long_name`` on every variable and coordinate, every
point present (``present`` True): values with known answers for the drawing of values, CIs,
flags and failures.  Absent points are not made here: the tests that need them read a real
store's (tests/pipeline/figure_store.py, ``tiny_map``)."""

from __future__ import annotations

import numpy as np
import xarray as xr

D_UNITS = {"units": "mm^2/s", "long_name": "diffusion coefficient"}


def reduced(freqs=(50.0, 55.0, 62.0, 70.0, 80.0), alphas=(0.5, 0.6, 0.8),
            families=("rest", "launched"), velocity=False) -> xr.Dataset:
    """D(f, alpha) = 100 alpha (1 + sin(f / 5)) with a 10 % CI, every point present
    (``present`` True for every family), every flag True; per-family D 5 % apart;
    ``velocity``: v and D_drift too."""
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
    ds["present"] = (fdims, np.ones(fam.shape, dtype=bool), {"units": "", "long_name": "present"})
    if velocity:
        v = 3 * a[None, :] + 0.01 * f[:, None]
        vu = {"units": "mm/s", "long_name": "drift velocity"}
        ds["v"], ds["v_lo"], ds["v_hi"] = (dims, v, vu), (dims, v - 0.2, vu), (dims, v + 0.2, vu)
        ds["D_drift"] = (dims, 0.8 * d, D_UNITS)
        ds["D_drift_lo"] = (dims, 0.7 * d, D_UNITS)
        ds["D_drift_hi"] = (dims, 0.9 * d, D_UNITS)
    return ds


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
