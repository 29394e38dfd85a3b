"""The title of every figure: the scene's name and what it fixes, then the cut the figure shows.

A reduced Dataset says which scene it holds in its attributes (:func:`scene_attrs`, written by
:func:`pipeline.api.reduced_dataset`): ``scene`` (the study's name), ``scene_preset`` (the
bbb.Params preset) and one ``fixed_<key>`` per ``[params]`` key the scene sets besides the
preset (a grid axis is not fixed; a grid axis of one value is).  The title reads::

    <scene> (<preset>): <key> = <value> <unit>, ..., N = <particles>, t_max = <s> s
    <axis> = <value>, ...          (the cut: a value of each axis the figure does not vary)

N is the number of particles analysed per point (all families), t_max the simulated time of
each, both read from the Dataset's ``n_particles`` and ``t_max`` at the points it has (a range
"32-128" where they differ, as a target-driven scene's do).  A Dataset without the attributes
(built by hand) gets the lines it has the numbers for.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..workflow.point import CONDITIONAL_AXES
from .labels import value_label
from .models import MERGED

__all__ = ["scene_attrs", "scene_line", "cut_line", "figure_title", "FIXED_PREFIX"]

FIXED_PREFIX = "fixed_"


def scene_attrs(study) -> dict[str, str | float]:
    """The attributes naming ``study`` (a :class:`pipeline.workflow.study.Study`) and what it
    fixes: netCDF-safe strings and numbers (module docstring)."""
    out: dict[str, str | float] = {"scene": study.name, "scene_preset": study.preset}
    axes = {a: v for a, v in study.grid}
    fixed = dict(study.overrides)  # [params] keys: a key is never in both it and [grid]
    # a grid axis of one value is fixed, unless it applies under some of another axis's
    # values only (mu under Coulomb): the models' names say it there
    fixed.update({a: v[0] for a, v in axes.items() if len(v) == 1
                  and CONDITIONAL_AXES.get(a, ("",))[0] not in axes})
    for k, v in fixed.items():
        out[FIXED_PREFIX + k] = v if isinstance(v, str) else float(v)
    return out


def _span(ds: xr.Dataset, name: str) -> str | None:
    if name not in ds.data_vars:
        return None
    v = np.asarray(ds[name].values, dtype=float)
    v = v[np.isfinite(v)]
    if not v.size:
        return None
    lo, hi = float(v.min()), float(v.max())
    return f"{lo:g}" if lo == hi else f"{lo:g}–{hi:g}"


def scene_line(ds: xr.Dataset) -> str:
    """``"<scene> (<preset>): tilt = 3°, throw = 45°, N = 64, t_max = 100 s"``: the scene,
    what it fixes, the particles per point and their simulated time ("" if nothing known)."""
    fixed = [value_label(ds, k.removeprefix(FIXED_PREFIX), v, named=True)
             for k, v in ds.attrs.items() if k.startswith(FIXED_PREFIX)]
    n, t = _span(ds, "n_particles"), _span(ds, "t_max")
    fixed += ([f"N = {n}"] if n else []) + ([f"$t_\\mathrm{{max}}$ = {t} s"] if t else [])
    head = str(ds.attrs.get("scene", ""))
    if head and ds.attrs.get("scene_preset"):
        head += f" ({ds.attrs['scene_preset']})"
    return ": ".join(p for p in (head, ", ".join(fixed)) if p)


def cut_line(da: xr.DataArray | xr.Dataset, skip=()) -> str:
    """The scalar coordinates a selection left (``ds.sel(mu=0.3)``), in words: ``"μ = 0.3"``;
    ``""`` if none.  A model's conditional value (μ of ``contact = coulomb, μ = 0.3``,
    :mod:`pipeline.plot.models`) is said by the model's name only."""
    return ", ".join(value_label(da, c, da[c].item(), named=True) for c in da.coords
                     if da[c].ndim == 0 and c not in skip and c not in da.dims
                     and MERGED not in da[c].attrs)


def figure_title(ds: xr.Dataset, da: xr.DataArray, skip=(), note: str = "") -> str:
    """The scene line, then the cut of ``da`` (its scalar coordinates besides ``skip`` and
    those the scene line names), then ``note``: each on its own line, empty ones left out."""
    named = {k.removeprefix(FIXED_PREFIX) for k in ds.attrs if k.startswith(FIXED_PREFIX)}
    return "\n".join(p for p in (scene_line(ds), cut_line(da, (*skip, *named)), note) if p)
