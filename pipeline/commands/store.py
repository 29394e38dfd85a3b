"""The commands that read a store: ``bbb reduce`` (D(f) tables), ``bbb status`` (done chunks,
as text or ``--json``), ``bbb verify`` (re-check every done chunk), ``bbb plot`` (figures).

``bbb reduce STORE --workflow W`` reduces with W's analysis settings ([analysis] and
``accuracy.n_resamples``) without re-running; W must otherwise describe the stored data.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from ..workflow.identity import f_key
from .common import EXIT_FAILED, WORKFLOW_HELP, UsageError, error, load

__all__ = ["add_parsers", "cmd_reduce", "cmd_status", "cmd_verify", "cmd_plot",
           "store_with_analysis_of"]


def add_parsers(sub) -> None:
    d = sub.add_parser("reduce", help="D(f) with bootstrap CIs and ergodicity verdicts")
    d.add_argument("store", metavar="STORE", help="a study store made by `bbb run`")
    d.add_argument("--out", metavar="DIR",
                   help="where diffusion.parquet/.csv go (default: beside the store, "
                        "in a folder named like it without .zarr)")
    d.add_argument("--workflow", metavar="WORKFLOW",
                   help="reduce with this workflow's [analysis] and accuracy.n_resamples "
                        "(its simulation settings must be the store's); " + WORKFLOW_HELP)
    d.set_defaults(handler=cmd_reduce)

    s = sub.add_parser("status", help="done/total chunks per frequency and family")
    s.add_argument("store", metavar="STORE")
    s.add_argument("--json", action="store_true",
                   help="one JSON object instead of the table: keys name, path, chunks_done, "
                        "chunks_total, axes, families, points (f, grid, per family done/total "
                        "and stop), jobs (null, or the record and squeue's listing of a run's "
                        "batch jobs); pipeline/README.md")
    s.set_defaults(handler=cmd_status)

    v = sub.add_parser("verify", help="re-check every done chunk and the attributes of a store; "
                                      "exit 1 listing each inconsistency")
    v.add_argument("store", metavar="STORE")
    v.set_defaults(handler=cmd_verify)

    g = sub.add_parser("plot", help="figures of a store, titled with the scene and what it "
                                    "fixes: D(f) (v, D_drift) with CIs and flags per family, "
                                    "contact models in one figure, heat maps over frequency x "
                                    "each grid axis (docs/gallery.md)")
    g.add_argument("store", metavar="STORE")
    g.add_argument("--out", metavar="DIR", help="where the figures go (default: STORE's name "
                                                "without .zarr, beside it, as bbb reduce)")
    g.add_argument("--format", dest="formats", action="append", choices=("png", "pdf", "svg"),
                   help="file format, repeatable (default: png and pdf)")
    g.set_defaults(handler=cmd_plot)


def cmd_reduce(args) -> int:
    from ..tables.reduce import reduce_store

    if args.out is not None:
        try:
            Path(args.out).mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise UsageError(f"--out {args.out}: cannot create the directory ({e.strerror}); "
                             "allowed: a directory path") from None
    store = args.store
    if args.workflow is not None:
        store = store_with_analysis_of(args.store, args.workflow)
    reduce_store(store, args.out)
    return 0


def store_with_analysis_of(path: str, workflow: str):
    """The store at ``path`` carrying the reduce settings of ``workflow`` (a file or a
    scene's name); refused (one line) if the workflow would have simulated other data."""
    from ..store.study_store import StudyStore, fingerprint_difference

    new = load(workflow)
    store = StudyStore.open(path)
    old = store.study
    refuse = (f"{workflow}: simulation settings differ from the store {store.path} "
              "({}); allowed: a workflow that differs from the store's only in [analysis] "
              "and accuracy.n_resamples")
    extra = sorted({f_key(f) for f in old.base_frequencies} - set(new.f_mhz))
    if extra:
        raise UsageError(refuse.format(f"frequencies: store has {extra[0] / 1000:g} Hz, "
                                       "the workflow does not"))
    new_here = new.with_frequencies(old.base_frequencies)  # a store of a --frequencies subset
    if new_here.fingerprint() != old.fingerprint():
        raise UsageError(refuse.format(fingerprint_difference(old, new_here)))
    acc = replace(old.accuracy, n_resamples=new.accuracy.n_resamples)
    return replace(store, study=replace(old, analysis=new.analysis, accuracy=acc))


def cmd_plot(args) -> int:
    from ..api import plot_store
    from ..store.study_store import StudyStore

    store = StudyStore.open(args.store)  # a clear error for a path that is not a store
    out = args.out or str(Path(store.path).with_suffix(""))
    files = plot_store(store.path, out, formats=tuple(args.formats or ("png", "pdf")))
    if not files:
        print(f"{store.study.name}: nothing to plot (no diffusion table: the store records no "
              "positions)")
        return 0
    print(f"{store.study.name}: wrote {len(files)} figures to {out}: "
          + ", ".join(p.name for p in files[:6]) + (" ..." if len(files) > 6 else ""))
    return 0


def cmd_status(args) -> int:
    from ..store.status import status_dict, status_text
    from ..store.study_store import StudyStore

    store = StudyStore.open(args.store)
    print(json.dumps(status_dict(store), indent=1) if args.json else status_text(store))
    return 0


def cmd_verify(args) -> int:
    from ..store.verify import verify_store

    report = verify_store(args.store)
    for problem in report.problems:
        print(problem)
    print(report.summary())
    if not report.ok:
        error(f"{report.path}: {len(report.problems)} inconsistencies (listed above)")
        return EXIT_FAILED
    return 0
