"""The study pipeline from Python (a notebook, a script): run a scene, open its store, reduce.

::

    from pipeline import open_study, reduced, run_study

    run_study("smoke")                       # workflows/smoke.toml -> runs/smoke.zarr, as `bbb run`
    ds = open_study("runs/smoke.zarr")       # xarray.Dataset, chunks not done masked
    ds.positions.sel(frequency=60.0, family="rest")      # x (mm) of every particle against time (s)
    tables = reduced("runs/smoke.zarr")      # {"diffusion": D(f), "counters": ...} as `bbb reduce`

A thin layer over :mod:`pipeline.execute.run`, :mod:`pipeline.tables.reduce` and
:mod:`pipeline.store.study_store`: the same tasks, seeds, store and tables as the command
line, so a store made here is the one ``bbb run`` makes, bit for bit, and resumes the same way.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr
    from distributed import Client

    from .execute.run import RunReport
    from .workflow.study import Study

__all__ = ["open_study", "reduced", "run_study", "load_study", "TABLE_UNITS"]

#: units of the D(f) and counters table columns attached by ``open_study(reduced=True)``
TABLE_UNITS = {
    "Gamma": "1", "D": "mm^2/s", "D_lo": "mm^2/s", "D_hi": "mm^2/s", "D_last": "mm^2/s",
    "t_max": "s", "fit_from": "s", "fit_to": "s", "eb_lag": "s", "EB": "1",
    "EB_threshold": "1", "EB_decay": "1", "EB_decay_threshold": "1",
    "collisions_per_s": "1/s", "sticks_per_s": "1/s", "liftoffs_per_s": "1/s",
    "anomalies_per_s": "1/s", "task_seconds": "s", "D_status": "", "D_cover": "1",
    "mover_share_hi": "1",
}


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
               bootstrap): D(f) columns as variables along ``frequency`` (``D``, ``D_lo``,
               ``D_hi``, ``ergodic``, ... with units) and the counters per (frequency, family).

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
        ds = _attach_tables(ds, _reduced(st))
    return ds


def reduced(path: str | os.PathLike) -> dict[str, pd.DataFrame]:
    """The tables of ``bbb reduce`` computed in memory (nothing written): ``"diffusion"``
    (one row per frequency, stores with positions) and ``"counters"`` (per frequency and
    family); columns and units in :mod:`pipeline.tables.reduce`.  Equal to the Parquet files
    ``bbb reduce`` writes."""
    from .store.study_store import StudyStore

    return _reduced(StudyStore.open(path))


def _reduced(st: Any) -> dict[str, pd.DataFrame]:
    from .tables.reduce import counters_table, diffusion_table

    done = st.done()
    tables = {"counters": counters_table(st, done)}
    if st.study.observables.positions:
        tables["diffusion"] = diffusion_table(st, done)
    return tables


def _attach_tables(ds: xr.Dataset, tables: dict[str, pd.DataFrame]) -> xr.Dataset:
    out = ds.copy()
    if "diffusion" in tables:
        d = tables["diffusion"].rename(columns={"f": "frequency"}).set_index("frequency")
        for col in d.columns:
            out[col] = ("frequency", d[col].reindex(ds["frequency"].values).to_numpy(),
                        {"units": TABLE_UNITS.get(col, "1" if col.startswith("EB") else
                                                  "mm^2/s" if col.startswith("D_") else ""),
                         "source": "bbb reduce: diffusion table"})
    c = tables["counters"].rename(columns={"f": "frequency"}).set_index(["frequency", "family"])
    for col in [x for x in c.columns if x.endswith("_per_s") or x == "task_seconds"]:
        grid = c[col].unstack("family").reindex(index=ds["frequency"].values,
                                               columns=ds["family"].values)
        out[col] = (("frequency", "family"), grid.to_numpy(),
                    {"units": TABLE_UNITS.get(col, "1/s"), "source": "bbb reduce: counters table"})
    return out
