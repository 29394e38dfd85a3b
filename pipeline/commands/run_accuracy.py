"""``bbb run`` (a workflow into its store, resumed if partial) and ``bbb accuracy`` (the
speed/accuracy study).

``bbb run WORKFLOW --frequencies 60,72`` runs only those frequencies of the workflow, into a
store of their own (default ``runs/<name>-60Hz-72Hz.zarr``); chunk seeds are keyed by the
frequency's value (pipeline/workflow/study.py), so its chunks are those of the whole sweep, bit
for bit.  ``bbb run`` stopped by Ctrl-C exits with status 130, by SIGTERM (``kill``, a batch
system ending the job it runs in) with 143; both end the run alike: the store's lock is
released and, with ``--cluster``, every job cancelled.
"""

from __future__ import annotations

from contextlib import nullcontext
from pathlib import Path

from ..execute.interrupt import sigterm_as_interrupt
from ..store.layout import default_store_path
from ..workflow.identity import f_key
from .common import (
    EXIT_FAILED,
    WORKFLOW_HELP,
    UsageError,
    error,
    frequency_list,
    jobs,
    load,
    positive_int,
)

__all__ = ["add_parsers", "cmd_run", "cmd_accuracy"]


def add_parsers(sub) -> None:
    r = sub.add_parser("run", help="run a workflow into its Zarr store (resumes a partial one)")
    r.add_argument("workflow", metavar="WORKFLOW", help=WORKFLOW_HELP)
    r.add_argument("--store", metavar="PATH",
                   help="store path or fsspec URL (default: runs/<workflow name>.zarr)")
    r.add_argument("--scheduler", metavar="ADDR",
                   help="existing Dask scheduler, e.g. tcp://host:8786 (default: a LocalCluster)")
    r.add_argument("--workers", metavar="N", type=positive_int,
                   help="LocalCluster worker processes (default: number of cores)")
    r.add_argument("--cluster", choices=("slurm",),
                   help="submit Dask workers as batch jobs (dask-jobqueue, configured in dask's "
                        "config files; docs/cluster.md)")
    r.add_argument("--jobs", metavar="N|MIN:MAX", type=jobs,
                   help="with --cluster: N jobs at once (default: 1), or MIN:MAX for elastic "
                        "workers, one per chunk queued, between MIN and MAX jobs")
    r.add_argument("--frequencies", metavar="F1,F2,...", type=frequency_list,
                   help="only these frequencies of the workflow (Hz), into their own store "
                        "(default: runs/<name>-F1Hz-F2Hz.zarr); same seeds, so the same chunks "
                        "as the whole sweep")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(handler=cmd_run)

    a = sub.add_parser("accuracy", help="the measured speed/accuracy trade: every preset and "
                                        "knob against a reference run (docs/accuracy.md)")
    a.add_argument("workflow", metavar="WORKFLOW", nargs="?", default="accuracy",
                   help="the reference scene (default: the shipped scene accuracy)")
    a.add_argument("--out", metavar="DIR", default="runs/accuracy",
                   help="tables and one store per variant (default: runs/accuracy)")
    a.add_argument("--figure", metavar="PNG", default="figures/accuracy.png",
                   help="error-versus-cost plot (default: figures/accuracy.png)")
    a.add_argument("--scheduler", metavar="ADDR", help="existing Dask scheduler")
    a.add_argument("--workers", metavar="N", type=positive_int,
                   help="LocalCluster worker processes (default: number of cores)")
    a.add_argument("--quick", action="store_true", help="draft and two knobs only")
    a.set_defaults(handler=cmd_accuracy)


def cmd_run(args) -> int:
    from ..execute.run import RunFailed, run_study

    if args.scheduler and args.workers:
        raise UsageError("--workers sizes a LocalCluster; with --scheduler the cluster's own "
                         "workers run the tasks (allowed: one of the two)")
    if args.cluster and (args.scheduler or args.workers):
        raise UsageError(f"--cluster {args.cluster} starts its own scheduler and workers "
                         "(allowed: one of --cluster, --scheduler, --workers)")
    if args.jobs and not args.cluster:
        raise UsageError("--jobs counts batch jobs of a --cluster (allowed: --cluster slurm "
                         "--jobs N)")
    study = load(args.workflow)
    name = study.name
    if args.frequencies:
        study = frequency_subset(study, args.frequencies, args.workflow)
        name += "".join(f"-{f:g}Hz" for f in study.frequencies)
    store = args.store or default_store_path(name)
    if "://" not in store:
        parent = Path(store).resolve().parent
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise UsageError(f"--store {store}: cannot create {parent} ({e.strerror}); "
                             "allowed: a path whose parent is or can be made a directory") from None
    try:
        with sigterm_as_interrupt(), _cluster(args, study, store) as scheduler:
            run_study(study, store, scheduler=scheduler, workers=args.workers,
                      progress=not args.no_progress)
    except RunFailed as e:
        error(str(e))
        error("finished chunks stay done; re-run the same command to resume")
        return EXIT_FAILED
    except ValueError as e:  # e.g. a malformed BBB_FAIL_CHUNKS, a --cluster misconfigured
        raise UsageError(str(e)) from None
    return 0


def frequency_subset(study, wanted: tuple[float, ...], workflow: str):
    """The study at the frequencies asked for, each of which must be one of the workflow's."""
    have = set(study.f_mhz)
    missing = [f for f in wanted if f_key(f) not in have]
    if missing:
        fs = study.frequencies
        listing = (", ".join(f"{f:g}" for f in fs) if len(fs) <= 8
                   else f"{len(fs)} from {fs[0]:g} to {fs[-1]:g}")
        raise UsageError(f"--frequencies: {', '.join(f'{f:g}' for f in missing)} Hz not in "
                         f"{workflow}; allowed: its frequencies ({listing} Hz)")
    return study.with_frequencies(wanted)


def _cluster(args, study, store: str):
    """The scheduler address to use: --scheduler, a --cluster started here, or None."""
    if not args.cluster:
        return nullcontext(args.scheduler)
    from ..execute.cluster import check_slurm, slurm_cluster, work_left

    check_slurm()  # a bad configuration is a usage error, found before anything runs
    if not work_left(study, store):  # nor is a job submitted for a refused or finished store
        return nullcontext(None)
    return slurm_cluster(args.jobs or 1, study, store=store)


def cmd_accuracy(args) -> int:
    from ..studies.accuracy.study import run_accuracy_study
    from ..workflow.scenes import workflow_file

    if args.scheduler and args.workers:
        raise UsageError("--workers sizes a LocalCluster; with --scheduler the cluster's own "
                         "workers run the tasks (allowed: one of the two)")
    run_accuracy_study(workflow_file(args.workflow), args.out, quick=args.quick,
                       workers=args.workers, scheduler=args.scheduler, figure=args.figure)
    return 0
