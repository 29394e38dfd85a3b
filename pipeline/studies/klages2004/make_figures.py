"""``python -m pipeline.make_figures``: run the figure scenes, reduce, draw, write REPORT.md.

The Klages, Barna & Mátyás (2004) study.  Scenes (``workflows/*.toml`` and this study's
``scenes/*.toml``, found by :mod:`pipeline.workflow.scenes`):

=====================  ======================================================================
figure2                D(f), 124 frequencies, particles at rest           -> Fig. 2
ergodicity             D per initial-condition family near the onset        -> Fig. 2 (shading,
                                                                               other families)
figure3                post-collision states at Fig. 3's six frequencies   -> Fig. 3
locking                post-collision states on Fig. 2's grid, 2 families  -> Fig. 3 (a),
                                                                               k(f), Fig. 1's
                                                                               parameters
figure2_matyas2004     D(f) for R = 25, alpha = 0.5                        -> extra Fig. 2
locking_matyas2004     post-collision states for that set                  -> its k(f) panel
finescale              D(f) in 58-64 Hz refined to 0.05 Hz                 -> extrema per Hz
                                                                              vs resolution
=====================  ======================================================================

Each scene runs through :func:`pipeline.execute.run.run_study` into ``<runs>/<name>.zarr``, which
resumes a partial store (so ``bbb run workflows/figure2.toml`` beforehand is reused); all
scenes share one LocalCluster (unless ``--scheduler`` names one), started once.  The
``--fast`` switch (or ``FAST=1`` in the environment) runs every scene at draft accuracy into
``<runs>/draft/`` and writes to ``figures/draft/``: the same pictures in a few minutes.

Outputs in the output folder: every figure as PNG and PDF, the tables the figures were drawn
and the claims judged from (CSV, :mod:`.committed`), ``run_log.json`` (wall times of the runs
that computed each store) and ``REPORT.md``; writing the repository's ``figures/``, also the
README's table of run times (:mod:`.run_times`).  A scene that this invocation only resumed
(nothing left to compute) keeps the wall time logged by the invocation that computed it, if
``run_log.json`` in the output folder has it for the same store.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import os
import re
import sys
import time
from collections.abc import Callable, Iterator
from datetime import UTC, datetime
from pathlib import Path

from ...workflow.scenes import ROOT, load_scene, scene_label
from .scene_list import EXTRA_STUDIES, SCENES  # importable from here as before

__all__ = ["SCENES", "run_log_entry", "make_figures", "main"]



def run_log_entry(name: str, store: str) -> dict[str, str]:
    """A scene's paths as run_log.json records them: relative to the repository (a committed
    log holds no absolute path of the machine it ran on)."""
    return {"workflow": scene_label(name), "store": os.path.relpath(store, ROOT)}


def make_figures(out_dir: str | os.PathLike | None = None, runs_dir: str | os.PathLike = "runs",
                 *, fast: bool = False, workers: int | None = None, scheduler: str | None = None,
                 run: bool = True, progress: bool = True,
                 echo: Callable[[str], None] = print) -> dict:
    """Run (or resume) every scene, reduce, draw every figure and write REPORT.md.

    out_dir  -- default ``figures`` (``figures/draft`` with ``fast``)
    runs_dir -- where the stores live (``<runs_dir>/draft`` with ``fast``)
    run      -- False: only reduce and draw from the stores as they are
    Returns {"figures": [paths], "report": path, "tables": {name: path}, "stores": {...}}.
    """
    import pandas as pd

    from ...execute.run import run_study
    from ...tables.collisions import locking_table
    from ...tables.reduce import reduce_store
    from . import figures as fg
    from .changes import changes_section, previous_report
    from .committed import (
        CLAIMS_HEADING,
        TABLE_FILES,
        read_study_tables,
        read_tables,
        study_key,
        write_csv,
        write_study_tables,
    )
    from .finescale import figure_finescale
    from .finescale import write_table as write_finescale
    from .report import write_report
    from .run_times import update_readme

    t_start = time.perf_counter()
    out = Path(out_dir if out_dir is not None else ("figures/draft" if fast else "figures"))
    runs = Path(runs_dir) / ("draft" if fast else "")
    out.mkdir(parents=True, exist_ok=True)
    runs.mkdir(parents=True, exist_ok=True)
    log: dict = {"fast": fast, "scenes": {}}
    try:
        previous = json.loads((out / "run_log.json").read_text()).get("scenes", {})
    except (OSError, ValueError):
        previous = {}
    stores: dict[str, str] = {}
    extras = [importlib.import_module(f"pipeline.studies.{s}") for s in EXTRA_STUDIES]
    names = SCENES + tuple(n for m in extras for n in m.SCENES)
    with _one_cluster(run and scheduler is None, workers, log) as shared:
        for name in names:
            study = load_scene(name, fast)
            path = str((runs / f"{study.name}.zarr").resolve())
            stores[name] = path
            entry = run_log_entry(name, path)
            if run:
                rep = run_study(study, path, scheduler=scheduler or shared, workers=workers,
                                progress=progress, dashboard=False, echo=echo)
                entry.update(wall_s=rep.wall, computed=len(rep.computed), skipped=rep.skipped,
                             chunks=rep.n_chunks, workers=rep.workers, task_s=rep.task_seconds)
            old = previous.get(name, {})
            if (not entry.get("computed") and old.get("computed")
                    and old.get("store") == entry["store"] and "wall_s" in old):
                entry.update({k: old[k] for k in ("wall_s", "computed", "skipped", "chunks",
                                                  "workers", "task_s") if k in old},
                             earlier_invocation=True)
            elif not entry.get("computed") and (old.get("separate_run")
                                                or (run and not old.get("computed"))):
                # nothing to compute and no earlier invocation did it: a separate `bbb run`
                # filled the store, and its wall time is not this log's to know
                entry["separate_run"] = True
            log["scenes"][name] = entry

    tables: dict[str, pd.DataFrame] = {}
    table_files: dict[str, str] = {}
    for name in ("figure2", "ergodicity", "figure2_matyas2004", "finescale"):
        t0 = time.perf_counter()
        tables[name] = reduce_store(stores[name], echo=echo)["diffusion"]
        log["scenes"][name]["reduce_s"] = time.perf_counter() - t0
    for name in ("locking", "locking_matyas2004"):
        tables[name] = locking_table(stores[name])
    for name, df in tables.items():
        table_files[name] = str(write_csv(df, out / TABLE_FILES[name]))

    echo("drawing figures ...")
    figs = [
        fg.figure1(stores["locking"], None, out),
        fg.figure2(stores["figure2"], {"diffusion": tables["figure2"],
                                       "ergodicity": tables["ergodicity"]}, out),
        fg.figure3([stores["figure3"], stores["locking"]], None, out),
        fg.figure_locking(stores["locking"], {"locking": tables["locking"]}, out),
        fg.figure2(stores["figure2_matyas2004"],
                   {"diffusion": tables["figure2_matyas2004"],
                    "locking": tables["locking_matyas2004"]},
                   out, name="fig2_matyas2004", letters=None, inset=None,
                   legend_loc="upper left"),
        figure_finescale(tables["finescale"], out),
    ]
    table_files["finescale_extrema"] = str(write_finescale(tables["finescale"], out))
    paths = [p for fig in figs for p in fg.figure_files(out, fig.get_label())]
    extra_lines: list[str] = []
    captions: dict[str, str] = {}
    for m in extras:  # each scene's reduce tables, keyed by table name (and scene_table)
        t = {study_key(name, tname): df for name in m.SCENES
             for tname, df in reduce_store(stores[name], echo=echo).items()}
        paths += m.draw(t, stores, out)  # may add tables read off the stores (claim inputs)
        table_files.update((p.stem, str(p)) for p in write_study_tables(out, t, m.SCENES))
        # the report reads the tables back from their CSVs: REPORT.md is what they give
        extra_lines += m.report_lines(read_study_tables(out, m.SCENES))
        captions.update(getattr(m, "CAPTIONS", {}))  # a study's figure captions, if it has them
    log["this_invocation_s"] = time.perf_counter() - t_start
    log["wall_s"] = log.get("cluster_s", 0.0) + sum(
        e.get("wall_s", 0.0) for e in log["scenes"].values()) + sum(
        e.get("reduce_s", 0.0) for e in log["scenes"].values())
    log["written"] = datetime.now(UTC).isoformat(timespec="seconds")
    log["cpus"] = os.cpu_count()
    (out / "run_log.json").write_text(json.dumps(log, indent=2) + "\n")
    readme = ROOT / "README.md"
    if out.resolve() == (ROOT / "figures").resolve() and readme.is_file():
        update_readme(readme, log)  # the committed figures: the README's table of run times
    headings = [CLAIMS_HEADING] + [h for h in extra_lines if h.startswith("## ")]
    previous, against = previous_report(out, ROOT, headings)
    report = write_report(out, stores=stores, tables=read_tables(out), figures=paths,
                          run_log=log, captions=captions)
    if extra_lines:
        with open(report, "a", encoding="utf-8") as fh:
            fh.write("\n".join(extra_lines) + "\n")
    written = re.search(r"^Written (\S+) by", previous or "", re.M)
    changes = changes_section(previous, report.read_text(encoding="utf-8"),
                              written and written.group(1), against)
    with open(report, "a", encoding="utf-8") as fh:
        fh.write("\n".join(changes) + "\n")
    echo(f"figures: {', '.join(str(p) for p in paths if p.suffix == '.png')}")
    echo(f"tables:  {', '.join(table_files.values())}")
    echo(f"report:  {report}")
    echo(f"stores:  {', '.join(stores.values())}")
    echo(f"done in {time.perf_counter() - t_start:.0f} s")
    return {"figures": paths, "report": report, "tables": table_files, "stores": stores}


@contextlib.contextmanager
def _one_cluster(wanted: bool, workers: int | None, log: dict) -> Iterator[str | None]:
    """One LocalCluster for every scene (its scheduler address), or None if not ``wanted``.

    Each ``run_study`` without a scheduler starts and stops its own cluster, and its workers
    import bbb and load the numba cache again: ~2 s a scene, 25 scenes.  The start-up and
    shut-down are logged as ``cluster_s`` (and counted in the log's ``wall_s``)."""
    if not wanted:
        yield None
        return
    from ...execute.run import connect

    t0 = time.perf_counter()
    client, cluster = connect(None, workers, False)
    log["cluster_s"] = time.perf_counter() - t0
    try:
        yield cluster.scheduler_address
    finally:
        t0 = time.perf_counter()
        client.close()
        cluster.close()
        log["cluster_s"] += time.perf_counter() - t0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.make_figures", description=__doc__
                                 .split("\n")[0])
    ap.add_argument("--fast", action="store_true", default=os.environ.get("FAST", "") not in
                    ("", "0"), help="draft accuracy (also FAST=1): runs/draft, figures/draft")
    ap.add_argument("--out", metavar="DIR", help="output folder (default figures[/draft])")
    ap.add_argument("--runs", metavar="DIR", default="runs", help="store folder (default runs)")
    ap.add_argument("--workers", type=int, help="LocalCluster workers (default: cores)")
    ap.add_argument("--scheduler", metavar="ADDR", help="an existing Dask scheduler")
    ap.add_argument("--no-run", action="store_true", help="draw from the stores as they are")
    ap.add_argument("--no-progress", action="store_true", help="no progress bars")
    a = ap.parse_args(argv)
    make_figures(a.out, a.runs, fast=a.fast, workers=a.workers, scheduler=a.scheduler,
                 run=not a.no_run, progress=not a.no_progress)
    return 0


if __name__ == "__main__":
    sys.exit(main())
