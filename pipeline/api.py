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
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr
    from distributed import Client

    from .execute.run import RunReport
    from .workflow.study import Study

from .tables.units import UNITS

__all__ = ["open_study", "reduced", "run_study", "load_study", "attach_tables", "plot_store",
           "TABLE_UNITS"]

#: the units of the tables' columns by exact name: now the one map of every table,
#: :data:`pipeline.tables.units.UNITS` (families of columns and CI bounds:
#: :func:`pipeline.tables.units.unit`); this name kept for one release
TABLE_UNITS = UNITS


def load_study(workflow: str | os.PathLike | Study) -> Study:
    """A Study from a workflow file path, a scene name (``"smoke"``, ``"figure2"``: the
    workflows shipped with the package, see ``pipeline.workflow.scenes.scene_names()``), TOML
    text, or a Study (returned as is).  Bad input raises WorkflowError naming file, line, key."""
    from .workflow.load import Study, load_workflow, parse_workflow
    from .workflow.scenes import scene_label, scene_names, scene_path

    if isinstance(workflow, Study):
        return workflow
    if isinstance(workflow, str) and "\n" in workflow:
        return parse_workflow(workflow)
    if isinstance(workflow, str) and not Path(workflow).exists() and workflow in scene_names():
        return parse_workflow(scene_path(workflow).read_text(encoding="utf-8"),
                              source=scene_label(workflow))
    return load_workflow(workflow)


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


def open_study(path: str | os.PathLike, *, mask: bool = True, reduced: bool = False
               ) -> xr.Dataset:
    """The store at ``path`` as an :class:`xarray.Dataset` (lazy, dask-backed).

    Dimensions ``frequency`` (Hz), ``family``, ``particle``, ``chunk`` and, as recorded,
    ``time`` (s), ``collision`` and ``field``; each variable's ``units`` and ``long_name`` are in
    its attributes (positions in mm; collisions' fields t s, x mm, y mm, vx mm/s, vy mm/s).

    mask    -- True (default): every variable with a ``particle`` dimension is NaN for the
               particles of chunks not marked done (``ds.where(done)`` applied chunk by
               chunk; integer counters become floats), as ``bbb reduce`` reads only done
               chunks.  The per-particle mask is the coordinate ``particle_done``.  False:
               the raw arrays (a chunk not done may hold partial data or fill values).
    reduced -- True: also attach the tables of :func:`reduced` (computed now, with the
               bootstrap), every column a variable with its ``units``: D(f), mechanisms
               along ``frequency`` (``D``, ``D_lo``, ``D_hi``, ``ergodic``, ``D_inf``, ...),
               counters and contact along (``frequency``, ``family``)
               (:func:`attach_tables` names them).

    Root attributes are netCDF-safe: nested ones (workflow, params, numerics, accuracy) are
    JSON strings (``json.loads(ds.attrs["workflow"])``), so ``ds.to_netcdf`` can write them.
    """
    import numpy as np
    import xarray as xr

    from .store.study_store import StudyStore, normalize_path

    st = StudyStore.open(path)  # checks that it is a complete bbb store
    ds = xr.open_zarr(normalize_path(path), consolidated=None)
    ds.attrs = {k: json.dumps(v) if isinstance(v, dict | list) else v for k, v in ds.attrs.items()}
    # the per-particle mask in memory (F x M x N booleans): as a dask array indexed from
    # `done`'s one-element chunks it would split every variable into one chunk per particle
    chunk_of = np.arange(ds.sizes["particle"]) // st.study.accuracy.chunk_size
    done_p = np.asarray(ds["done"].values, dtype=bool)[:, :, chunk_of]
    ds = ds.assign_coords(particle_done=(("frequency", "family", "particle"), done_p, {
        "long_name": "the particle's chunk is marked done", "units": ""}))
    if mask:
        for name, var in ds.data_vars.items():
            if "particle" in var.dims:
                ds[name] = var.where(ds["particle_done"]).assign_attrs(var.attrs)
    if reduced:
        from .tables.catalog import tables

        ds = attach_tables(ds, tables(st))
    return ds


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


def attach_tables(ds: xr.Dataset, tables: dict[str, pd.DataFrame]) -> xr.Dataset:
    """``ds`` with every column of ``tables`` as a variable: along ``frequency`` for a table
    with a row per f, along (``frequency``, ``family``) for one with a row per (f, family).

    A variable is named as its column; a column already attached by an earlier table (the
    tables with a row per f come first) is left out where it holds the same values (Gamma,
    t_max of the counters), else attached as ``<table>_<column>`` (e.g.
    ``counters_n_particles``: per family, where the diffusion table's ``n_particles`` pools
    them).  Each variable's attributes: ``units``
    (:func:`pipeline.tables.units.column_unit`, as the Parquet metadata), ``source`` (``bbb
    reduce: <table> table``) and ``column``.  The label columns ``family`` and ``initial``
    are the Dataset's own coordinates."""
    import xarray as xr

    from .tables.catalog import index_of
    from .tables.units import column_unit

    out = ds.copy()
    # the tables with a row per f first: D(f)'s columns keep their plain names
    for name, df in sorted(tables.items(), key=lambda item: len(index_of(item[0]))):
        index = index_of(name)
        dims = tuple({"f": "frequency"}.get(c, c) for c in index)
        frame = df.rename(columns={"f": "frequency"}).set_index(list(dims))
        for col in [c for c in frame.columns if c not in ("family", "initial")]:
            series = frame[col]
            if len(dims) == 1:
                values = series.reindex(ds["frequency"].values).to_numpy()
            else:
                values = series.unstack("family").reindex(
                    index=ds["frequency"].values, columns=ds["family"].values).to_numpy()
            var = xr.Variable(dims, values, {"units": column_unit(col),
                                             "source": f"bbb reduce: {name} table",
                                             "column": col})
            if col in out.variables:
                if _same_values(out[col].variable, var):
                    continue
                col = f"{name}_{col}"
            out[col] = var
    return out


def plot_store(path: str | os.PathLike, out_dir: str | os.PathLike, *,
               formats: tuple[str, ...] = ("png", "pdf")) -> list[Path]:
    """Write the talk figures of the store at ``path`` to ``out_dir``: D(f) curves with their
    CIs and flags, per family, and heat maps over frequency x each grid axis
    (:func:`pipeline.plot.figures.plot_dataset` on ``open_study(path, reduced=True)``, whose
    docstring names the files); returns the files written.  Here, above the engine's layers,
    because the reduced Dataset is built here; the plot layer itself takes a Dataset."""
    from .plot.figures import plot_dataset

    return plot_dataset(open_study(path, reduced=True), out_dir, formats=formats)


def _same_values(a, b) -> bool:
    """Two variables hold the same values (broadcast against each other, NaN equal NaN)."""
    import xarray as xr

    try:
        x, y = xr.broadcast(xr.DataArray(a), xr.DataArray(b))
        return bool(x.equals(y))
    except (ValueError, TypeError):
        return False
