"""``python -m pipeline.make_figures [--fast]``: run every study's scenes, reduce, draw, write
REPORT.md.

The studies are those of the registry (:mod:`pipeline.studies.registry`), in its order, each a
:class:`~pipeline.studies.interface.Study`: its scenes (``workflows/*.toml`` and the study's
``scenes/*.toml``, found by :mod:`pipeline.workflow.scenes`) are run, its tables made from
their stores, its figures drawn, its tables written beside the report and read back, and its
section of REPORT.md written from its claim records (:mod:`pipeline.studies.report`).

Each scene runs through :func:`pipeline.execute.run.run_study` into ``<runs>/<name>.zarr``, which
resumes a partial store (so ``bbb run workflows/figure2.toml`` beforehand is reused); all
scenes share one LocalCluster (unless ``--scheduler`` names one), started once.  The
``--fast`` switch (or ``FAST=1`` in the environment) runs every scene at draft accuracy into
``<runs>/draft/`` and writes to ``figures/draft/``: the same pictures in a few minutes.
``--list`` prints the studies and their scenes and runs nothing.

Outputs in the output folder: every figure as PNG and PDF, the tables the figures were drawn
and the claims judged from (CSV, :mod:`pipeline.tables.files`), ``run_log.json`` (wall times of
the runs that computed each store) and ``REPORT.md``; writing the repository's ``figures/``,
also the table of run times in docs/reproducing.md (:mod:`pipeline.studies.run_times`).  A
scene that this invocation only resumed (nothing left to compute) keeps the wall time logged by
the invocation that computed it, if ``run_log.json`` in the output folder has it for the same
store.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import sys
import time
from collections.abc import Callable, Iterator
from datetime import UTC, datetime
from pathlib import Path

from .studies.registry import studies as registered
from .workflow.scenes import ROOT, load_scene, scene_label

__all__ = ["scenes", "run_log_entry", "make_figures", "main"]


def scenes() -> tuple[str, ...]:
    """Every registered study's scenes, in the order make_figures runs them."""
    return tuple(n for s in registered() for n in s.scenes)



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
    from .claims.changes import changes_section, previous_report
    from .execute.run import run_study
    from .studies.report import section_headings, write_report
    from .studies.run_times import PAGE as RUN_TIMES_PAGE
    from .studies.run_times import update_readme

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
    studies = registered()
    names = tuple(n for s in studies for n in s.scenes)
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

    paths: list[Path] = []
    table_files: dict[str, str] = {}
    for s in studies:  # in the registry's order: a study may read a table an earlier one wrote
        t0 = time.perf_counter()
        tables = s.tables(stores, echo=echo)
        # the time to make a study's tables is logged on its first scene (the run times count it)
        log["scenes"][s.scenes[0]]["reduce_s"] = time.perf_counter() - t0
        echo(f"drawing the figures of {s.name} ...")
        paths += s.draw(tables, stores, out)  # may add tables read off the stores
        table_files.update((p.stem, str(p)) for p in s.write_tables(out, tables))
    log["this_invocation_s"] = time.perf_counter() - t_start
    log["wall_s"] = log.get("cluster_s", 0.0) + sum(
        e.get("wall_s", 0.0) for e in log["scenes"].values()) + sum(
        e.get("reduce_s", 0.0) for e in log["scenes"].values())
    log["written"] = datetime.now(UTC).isoformat(timespec="seconds")
    log["cpus"] = os.cpu_count()
    (out / "run_log.json").write_text(json.dumps(log, indent=2) + "\n")
    page = ROOT / RUN_TIMES_PAGE
    if out.resolve() == (ROOT / "figures").resolve() and page.is_file():
        update_readme(page, log)  # the committed figures: docs/reproducing.md's table of run times
    previous, against = previous_report(out, ROOT, section_headings(studies))
    # the report reads the tables back from their CSVs: REPORT.md is what they give
    report = write_report(out, stores=stores, tables={s.name: s.read_tables(out) for s in studies},
                          figures=paths, run_log=log, studies=studies)
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
    from .execute.run import connect

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
    ap.add_argument("--list", action="store_true", help="print the studies and their scenes")
    a = ap.parse_args(argv)
    if a.list:
        for s in registered():
            print(f"{s.name}: {', '.join(s.scenes)}")
        return 0
    make_figures(a.out, a.runs, fast=a.fast, workers=a.workers, scheduler=a.scheduler,
                 run=not a.no_run, progress=not a.no_progress)
    return 0


if __name__ == "__main__":
    sys.exit(main())
