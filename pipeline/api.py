"""The study pipeline from Python (a notebook, a script): run a scene, open its store, reduce.

::

    from pipeline import open_study, reduced, run_study

    run_study("smoke")                       # workflows/smoke.toml -> runs/smoke.zarr, as `bbb run`
    ds = open_study("runs/smoke.zarr")       # xarray.Dataset, chunks not done masked
    ds.positions.sel(frequency=60.0, family="rest")      # x (mm) of every particle against time (s)
    tables = reduced("runs/smoke.zarr")      # {"diffusion": D(f), "counters": ...} as `bbb reduce`
    ds = open_study("runs/smoke.zarr", reduced=True)     # ... and every table on the Dataset

A thin layer over :mod:`pipeline.execute.run`, :mod:`pipeline.tables.reduce` and
:mod:`pipeline.store.study_store`: the same tasks, seeds, store and tables as the command
line, so a store made here is the one ``bbb run`` makes, bit for bit, and resumes the same way.
"""

from __future__ import annotations

import json
import os
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr
    from distributed import Client

    from .execute.run import RunReport
    from .workflow.study import Study

__all__ = ["open_study", "reduced", "reduced_dataset", "run_study", "load_study",
           "attach_tables", "plot_store"]


def load_study(workflow: str | os.PathLike | Study) -> Study:
    """A Study from a workflow file path, a scene name (``"smoke"``, ``"figure2"``: the
    workflows shipped with the package, see ``pipeline.workflow.scenes.scene_names()``), TOML
    text, or a Study (returned as is).  Bad input raises WorkflowError naming file, line, key."""
    from .workflow.load import Study, parse_workflow
    from .workflow.scenes import load_named

    if isinstance(workflow, Study):
        return workflow
    if isinstance(workflow, str) and "\n" in workflow:
        return parse_workflow(workflow)
    return load_named(workflow)


def run_study(workflow: str | os.PathLike | Study, store: str | os.PathLike | None = None, *,
              client: Client | str | None = None, workers: int | None = None,
              progress: bool = False, echo: Callable[[str], None] = print) -> RunReport:
    """Run (or resume) a study, exactly as ``bbb run`` does; returns the run's RunReport.

    workflow -- a workflow file, a scene name, TOML text or a Study (:func:`load_study`)
    store    -- the Zarr store (default ``runs/<study name>.zarr`` below the current
                directory, as ``bbb run``); an existing store of the same workflow is resumed:
                only chunks not marked done are computed
    client   -- where the tasks run: None starts a LocalCluster of ``workers`` processes
                (default: the number of cores) for this call; a ``distributed.Client`` or a
                scheduler address (``tcp://host:8786``) uses that cluster's workers, which must
                see the store's path.  The store is the same bit for bit in every case.

    Raises RunFailed naming the chunk if a task fails (finished chunks stay done).
    """
    from .execute.run import run_study as _run
    from .store.layout import default_store_path

    study = load_study(workflow)
    if client is not None and workers is not None:
        raise ValueError("workers sizes a LocalCluster; with client the cluster's own workers "
                         "run the tasks (allowed: one of the two)")
    path = store if store is not None else default_store_path(study.name)
    if "://" not in os.fspath(path):
        Path(path).resolve().parent.mkdir(parents=True, exist_ok=True)
    return _run(study, path, scheduler=_address(client), workers=workers, progress=progress,
                dashboard=False, echo=echo)


def _address(client: Client | str | None) -> str | None:
    """The scheduler address of a Client (run.run_study connects its own client to it)."""
    if client is None or isinstance(client, str):
        return client
    try:
        return client.scheduler.address
    except AttributeError:
        raise TypeError(f"client: {type(client).__name__}; allowed: None, a distributed.Client "
                        "or a scheduler address") from None


def open_study(path: str | os.PathLike, *, mask: bool = True, reduced: bool = False,
               unstack: bool = True) -> xr.Dataset:
    """The store at ``path`` as an :class:`xarray.Dataset` (lazy, dask-backed).

    Dimensions ``frequency`` (Hz), a grid's axes (``alpha``, ``contact``, ... in the
    workflow's order; a store without ``[grid]`` has none), ``family``, ``particle``,
    ``chunk`` and, as recorded, ``time`` (s), ``collision`` and ``field``; each variable's
    ``units`` and ``long_name`` are in its attributes (positions in mm; collisions' fields t s,
    x mm, y mm, vx mm/s, vy mm/s).  Its dask chunks are whole chunks of the store: one task's
    ``chunk_size`` particles of one point and family (a grid's points in whole lines).  A
    grid is unstacked: one dimension per axis, each point at the values it holds
    (:func:`pipeline.workflow.point.map_coords`: mu = 0 of a stick point), NaN where a point
    is absent.  The boolean variable ``present`` (over the point
    dimensions and ``family``; :func:`pipeline.tables.dataset.presence`) is True where the
    store holds the point and the family has a chunk done there, False at an absent cell
    (no point there: a conditional axis away from its condition, left out as invalid, not
    added by refinement; or nothing done yet); :func:`reduced_dataset` carries the same.
    The scene's fixed parameters are in the attribute ``params`` (JSON) here, scalar
    coordinates in :func:`reduced_dataset` (the netCDF).

    mask    -- True (default): every variable with a ``particle`` dimension is NaN for the
               particles of chunks not marked done (``ds.where(done)`` applied chunk by
               chunk; integer counters become floats), as ``bbb reduce`` reads only done
               chunks.  The per-particle mask is the coordinate ``particle_done``.  False:
               the raw arrays (a chunk not done may hold partial data or fill values).
    reduced -- True: also attach the tables of :func:`reduced` (computed now, with the
               bootstrap), every column a variable with its ``units``
               (:func:`attach_tables`; :func:`reduced_dataset` gives them alone).
    unstack -- False: a grid store as stored, along one dimension ``point`` with the
               coordinates ``frequency`` and each axis.

    Root attributes are netCDF-safe: nested ones (workflow, params, numerics, accuracy) are
    JSON strings (``json.loads(ds.attrs["workflow"])``), so ``ds.to_netcdf`` can write them.
    """
    import numpy as np
    import xarray as xr

    from .store.study_store import StudyStore, normalize_path
    from .tables.dataset import presence

    st = StudyStore.open(path)  # checks that it is a complete bbb store
    study = st.study
    done = st.done()  # (point, family, chunk)
    # a grid's points are one Zarr chunk each: in dask, whole grid lines of them at once
    # (tens of points), or a map of 10^4 points makes graphs of 10^4 tasks a variable
    chunks = {"point": _line_chunk(study)} if study.grid else None
    with warnings.catch_warnings():  # the 1-D coordinates of points: read whole anyway
        warnings.filterwarnings("ignore", "The specified chunks separate", UserWarning)
        ds = xr.open_zarr(normalize_path(path), consolidated=None,
                          **({"chunks": chunks} if chunks else {}))
    ds.attrs = {k: json.dumps(v) if isinstance(v, dict | list) else v for k, v in ds.attrs.items()}
    # the per-particle mask
    if study.grid:  # lazily, in the dask chunks of the data (a map's done flags are many):
        # each chunk's flag repeated over its particles, so that the mask's dask chunks are
        # the store's (chunk_size particles; indexed by particle, a dask array of `done`'s
        # one-element chunks would split every masked variable into one chunk per particle)
        import dask.array as da

        done_p = da.repeat(ds["done"].data.astype(bool), study.accuracy.chunk_size, axis=2)
    else:  # in memory (F x M x N booleans)
        done_p = np.repeat(done, study.accuracy.chunk_size, axis=2)
    done_p = done_p[:, :, :ds.sizes["particle"]]
    ds = ds.assign_coords(particle_done=((study.point_dim, "family", "particle"), done_p, {
        "long_name": "the particle's chunk is marked done", "units": ""}))
    if mask:
        for name, var in ds.data_vars.items():
            if "particle" in var.dims:
                ds[name] = var.where(ds["particle_done"]).assign_attrs(var.attrs)
    if study.grid and unstack:
        ds = _unstack(ds, study)
    ds["present"] = _present_on(ds, presence(study, done))
    if reduced:
        from .tables.catalog import tables

        ds = attach_tables(ds, tables(st, done=done))
    return ds


def _present_on(ds: xr.Dataset, present: xr.DataArray) -> xr.DataArray:
    """The presence mask on ``ds``'s dimensions, in their order and with their coordinates'
    attributes: over an unstacked map or the frequencies of a store without a grid as it
    is; each point's along ``point`` (a grid as stored)."""
    if "point" in ds.dims:
        at = {c: ds[c] for c in present.dims if c != "family"}
        return present.sel(at).drop_vars(list(at)).assign_attrs(present.attrs)
    out = present.sel({d: ds[d].values for d in present.dims})
    return out.assign_coords({d: ds[d] for d in out.dims})


def _line_chunk(study: Study, points: int = 64) -> int:
    """Points per dask chunk of a grid store: whole grid lines (len(frequencies) points
    each), about ``points`` of them."""
    F = max(1, len(study.frequencies))
    return F * max(1, round(points / F))


def _unstack(ds: xr.Dataset, study: Study) -> xr.Dataset:
    """A grid store's ``point`` dimension as one dimension per axis and ``frequency``, with
    the coordinates of :func:`pipeline.workflow.point.map_coords` (where the tables put each
    point too: mu = 0 of a stick point; NaN where no point is).  A store whose points are the
    whole product of the workflow's values in its order (none skipped, none added, no
    conditional axis moved) is reshaped, lazily and at once; any other is unstacked by
    value."""
    import itertools

    from .workflow.identity import point_key
    from .workflow.point import map_coords

    coords = map_coords(study.grid, study.points)
    axes = [a for a, _ in study.grid]
    product = [point_key(f, tuple(zip(axes, combo, strict=True)))
               for combo in itertools.product(*(v for _, v in study.grid))
               for f in study.frequencies]
    if not study.stored_points and [p.key for p in study.points] == product:
        out = _reshape(ds, study)
        return out.isel({d: [list(out[d].values).index(v) for v in vs]
                         for d, vs in coords.items() if list(out[d].values) != list(vs)})
    attrs = {c: dict(ds[c].attrs) for c in coords}
    out = ds.drop_vars("point").set_index(point=["frequency", *axes]).unstack("point")
    out = out.reindex({d: list(vs) for d, vs in coords.items()})
    out = out.transpose("frequency", *axes, ...)
    for c, a in attrs.items():
        out[c].attrs.update(a)
    return out


def reduced(path: str | os.PathLike, names: list[str] | None = None
            ) -> dict[str, pd.DataFrame]:
    """The tables of ``bbb reduce`` computed in memory (nothing written): every table the
    store has (:func:`pipeline.tables.catalog.tables`: ``"counters"``, ``"diffusion"``,
    ``"contact"``, ``"mechanisms"`` as its observables give; ``names`` picks, e.g.
    ``["locking"]``); columns in their modules, units in :mod:`pipeline.tables.units`.
    Equal to the Parquet files ``bbb reduce`` writes."""
    from .store.study_store import StudyStore
    from .tables.catalog import tables

    return tables(StudyStore.open(path), names)


def _reshape(ds: xr.Dataset, study: Study) -> xr.Dataset:
    """:func:`_unstack` of a store holding the grid's whole product in axis order: every
    variable along ``point`` reshaped to (axes..., frequency), then frequency first."""
    import xarray as xr

    axes = [a for a, _ in study.grid]
    shape = [len(v) for _, v in study.grid] + [len(study.frequencies)]
    dims = [*axes, "frequency"]
    coords = {a: (a, list(v), dict(ds[a].attrs)) for a, v in study.grid}
    coords["frequency"] = ("frequency", list(study.frequencies), dict(ds["frequency"].attrs))
    out = ds.drop_vars(["point", "frequency", *axes])
    for name in list(out.variables):
        var = out.variables[name]
        if var.dims[:1] == ("point",):
            new = xr.Variable(dims + list(var.dims[1:]), var.data.reshape(*shape, *var.shape[1:]),
                              var.attrs)
            if name in out.coords:
                out = out.assign_coords({name: new})
            else:
                out[name] = new
    out = out.assign_coords(coords)
    return out.transpose("frequency", *axes, ...)


def reduced_dataset(path: str | os.PathLike, names: list[str] | None = None) -> xr.Dataset:
    """The tables of :func:`reduced` as one Dataset: dims ``frequency``, a grid's axes and
    ``family`` (the per-family ``D_<family>`` columns as ``D_family`` along ``family``), CF
    attributes (``Conventions``, ``units``, ``long_name``) on every variable; columns and
    names in :mod:`pipeline.tables.dataset`; the coordinates and the presence mask
    ``present`` of :func:`open_study` (every variable NaN, text ``""``, at an absent
    point), so the two agree value for value; the scene's fixed parameters (tilt, throw,
    contact, alpha, ... where not an axis) as scalar coordinates with their units
    (:func:`pipeline.tables.dataset.fixed_params`); the attributes ``scene``,
    ``scene_preset`` and ``fixed_<key>`` name the scene and what it fixes for the figures'
    titles (:func:`pipeline.plot.titles.scene_attrs`).  ``ds.to_netcdf(...)`` writes it
    (needs the ``netcdf`` extra: ``pip install bbb[netcdf]``)."""
    from .plot.titles import scene_attrs
    from .store.study_store import StudyStore
    from .tables.catalog import tables
    from .tables.dataset import fixed_params, mask_absent, presence, tables_dataset

    st = StudyStore.open(path)
    study, attrs, done = st.study, st.attrs(), st.done()
    present = presence(study, done)
    ds = tables_dataset(tables(st, names, done), {d: present[d].values for d in present.dims
                                                  if d != "family"},
                        [f.name for f in study.families],
                        {"title": f"bbb reduce: study {study.name}",
                         "store_fingerprint": attrs["fingerprint"],
                         "kernel_hash": attrs["kernel_hash"]})
    ds = mask_absent(ds, present)
    ds["present"] = _present_on(ds, present)
    ds.attrs.update(scene_attrs(study))  # the scene and what it fixes: the figures' titles
    return ds.assign_coords({k: v for k, v in fixed_params(study).items()
                             if k not in ds.variables})


def attach_tables(ds: xr.Dataset, tables: dict[str, pd.DataFrame]) -> xr.Dataset:
    """``ds`` with every column of ``tables`` as a variable
    (:func:`pipeline.tables.dataset.tables_dataset`: over ``frequency`` and a grid's axes,
    and ``family`` for a table with a row per (point, family); per-family columns of a table
    with a row per point as ``D_family`` etc. along ``family``); along ``point`` on a grid
    store opened with ``unstack=False``.

    A column already in ``ds`` (Gamma, t_max, ...) is left out where it holds the same
    values, else attached as ``<table>_<column>`` (e.g. ``counters_n_left_cell``: per family,
    where the store's ``n_left_cell`` is per particle).  Each variable's attributes: ``units``
    (:func:`pipeline.tables.units.column_unit`, as the Parquet metadata), ``long_name``,
    ``source`` (``bbb reduce: <table> table``), ``table`` and ``column``.  Where ``ds`` has
    the presence mask ``present`` (:func:`open_study` gives it), every attached variable is
    NaN (text ``""``) at an absent point, as in :func:`reduced_dataset`."""
    from .tables.dataset import mask_absent, same_values, tables_dataset

    axes = _grid_axes(ds)
    families = [str(f) for f in ds["family"].values] if "family" in ds.coords else []
    if "point" not in ds.dims:  # on ds's coordinates
        tds = tables_dataset(tables, {d: ds[d].values for d in ("frequency", *axes)}, families)
    else:  # a grid as stored: each point's row
        tds = tables_dataset(tables, axes, families)
        tds = tds.sel({c: ds[c] for c in ("frequency", *axes)})
        tds = tds.drop_vars([c for c in ("frequency", *axes) if c in tds.coords])
    if "present" in ds.data_vars:
        tds = mask_absent(tds, ds["present"])
    out = ds.copy()
    for name, var in tds.data_vars.items():
        if name in out.variables:
            if same_values(out[name], var):
                continue
            name = f"{var.attrs['table']}_{name}"
        out[name] = var
    return out


def _grid_axes(ds: xr.Dataset) -> list[str]:
    """The grid axes of a Dataset of :func:`open_study` (from its stored workflow)."""
    wf = ds.attrs.get("workflow")
    if not wf:
        return []
    wf = json.loads(wf) if isinstance(wf, str) else wf
    return [a for a, _ in wf.get("grid", ())]


def plot_store(path: str | os.PathLike, out_dir: str | os.PathLike, *,
               formats: tuple[str, ...] = ("png", "pdf")) -> list[Path]:
    """Write the talk figures of the store at ``path`` to ``out_dir``: D(f) curves with their
    CIs and flags, per family, and heat maps over frequency x each grid axis
    (:func:`pipeline.plot.figures.plot_dataset` on :func:`reduced_dataset`, whose
    docstring names the files); returns the files written.  Here, above the engine's layers,
    because the reduced Dataset is built here; the plot layer itself takes a Dataset."""
    from .plot.figures import plot_dataset

    return plot_dataset(reduced_dataset(path), out_dir, formats=formats)
