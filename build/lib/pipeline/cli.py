"""The ``bbb`` command line: ``bbb run``, ``bbb reduce``, ``bbb status``, ``bbb verify``.

Usage errors (bad arguments, a malformed workflow, a store of another workflow) print one line
``bbb: error: ...`` to stderr and exit with status 2, without a traceback.  A failed task exits
with status 1 and names the frequency, family and chunk.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

__all__ = ["main", "default_store_path"]

EXIT_USAGE = 2
EXIT_FAILED = 1


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # argparse prints usage + message; we want one line
        raise UsageError(f"{self.prog}: {message} (see {self.prog} --help)")


def default_store_path(name: str) -> str:
    """``runs/<name>.zarr`` relative to the current directory."""
    return os.path.join("runs", f"{name}.zarr")


def _build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="bbb", description="Bouncing ball billiard study pipeline.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    r = sub.add_parser("run", help="run a workflow into its Zarr store (resumes a partial one)")
    r.add_argument("workflow", metavar="WORKFLOW", help="workflow TOML file")
    r.add_argument("--store", metavar="PATH",
                   help="store path or fsspec URL (default: runs/<workflow name>.zarr)")
    r.add_argument("--scheduler", metavar="ADDR",
                   help="existing Dask scheduler, e.g. tcp://host:8786 (default: a LocalCluster)")
    r.add_argument("--workers", metavar="N", type=_positive_int,
                   help="LocalCluster worker processes (default: number of cores)")
    r.add_argument("--cluster", choices=("slurm",),
                   help="submit Dask workers as batch jobs (dask-jobqueue, configured in dask's "
                        "config files; docs/cluster.md)")
    r.add_argument("--jobs", metavar="N", type=_positive_int,
                   help="with --cluster: at most N jobs at once (default: 1)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")

    d = sub.add_parser("reduce", help="D(f) with bootstrap CIs and ergodicity verdicts")
    d.add_argument("store", metavar="STORE", help="a study store made by `bbb run`")
    d.add_argument("--out", metavar="DIR",
                   help="where diffusion.parquet/.csv go (default: beside the store, "
                        "in a folder named like it without .zarr)")

    a = sub.add_parser("accuracy", help="the measured speed/accuracy trade: every preset and "
                                        "knob against a reference run (docs/accuracy.md)")
    a.add_argument("workflow", metavar="WORKFLOW", nargs="?", default="workflows/accuracy.toml",
                   help="the reference scene (default: workflows/accuracy.toml)")
    a.add_argument("--out", metavar="DIR", default="runs/accuracy",
                   help="tables and one store per variant (default: runs/accuracy)")
    a.add_argument("--figure", metavar="PNG", default="figures/accuracy.png",
                   help="error-versus-cost plot (default: figures/accuracy.png)")
    a.add_argument("--scheduler", metavar="ADDR", help="existing Dask scheduler")
    a.add_argument("--workers", metavar="N", type=_positive_int,
                   help="LocalCluster worker processes (default: number of cores)")
    a.add_argument("--quick", action="store_true", help="draft and two knobs only")

    s = sub.add_parser("status", help="done/total chunks per frequency and family")
    s.add_argument("store", metavar="STORE")

    v = sub.add_parser("verify", help="re-check every done chunk and the attributes of a store; "
                                      "exit 1 listing each inconsistency")
    v.add_argument("store", metavar="STORE")
    return p


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"{n} is out of range; allowed: an integer >= 1")
    return n


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bbb`` script and of ``python -m pipeline``; returns the exit code."""
    try:
        return _main(argv)
    except SystemExit as e:  # --help, or argparse's own exits
        return int(e.code or 0) if isinstance(e.code, int) or e.code is None else EXIT_USAGE
    except UsageError as e:
        _error(str(e).removeprefix("bbb: "))
        return EXIT_USAGE
    except KeyboardInterrupt:
        _error("interrupted; re-run the same command to resume")
        return 130


def _main(argv: list[str] | None) -> int:
    from .store import StoreError
    from .workflow import WorkflowError

    args = _build_parser().parse_args(argv)
    try:
        if args.command == "run":
            return _cmd_run(args)
        if args.command == "reduce":
            return _cmd_reduce(args)
        if args.command == "accuracy":
            return _cmd_accuracy(args)
        if args.command == "verify":
            return _cmd_verify(args)
        return _cmd_status(args)
    except (WorkflowError, StoreError) as e:
        raise UsageError(str(e)) from None


def _cmd_run(args) -> int:
    from .run import RunFailed, run_study
    from .workflow import load_workflow

    if args.scheduler and args.workers:
        raise UsageError("--workers sizes a LocalCluster; with --scheduler the cluster's own "
                         "workers run the tasks (allowed: one of the two)")
    if args.cluster and (args.scheduler or args.workers):
        raise UsageError(f"--cluster {args.cluster} starts its own scheduler and workers "
                         "(allowed: one of --cluster, --scheduler, --workers)")
    if args.jobs and not args.cluster:
        raise UsageError("--jobs counts batch jobs of a --cluster (allowed: --cluster slurm "
                         "--jobs N)")
    study = load_workflow(args.workflow)
    store = args.store or default_store_path(study.name)
    if "://" not in store:
        parent = Path(store).resolve().parent
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise UsageError(f"--store {store}: cannot create {parent} ({e.strerror}); "
                             "allowed: a path whose parent is or can be made a directory") from None
    try:
        with _cluster(args, study, store) as scheduler:
            run_study(study, store, scheduler=scheduler, workers=args.workers,
                      progress=not args.no_progress)
    except RunFailed as e:
        _error(str(e))
        _error("finished chunks stay done; re-run the same command to resume")
        return EXIT_FAILED
    except ValueError as e:  # e.g. a malformed BBB_FAIL_CHUNKS, a --cluster misconfigured
        raise UsageError(str(e)) from None
    return 0


def _cluster(args, study, store: str):
    """The scheduler address to use: --scheduler, a --cluster started here, or None."""
    from contextlib import nullcontext

    if not args.cluster:
        return nullcontext(args.scheduler)
    from .cluster import check_slurm, slurm_cluster, work_left

    check_slurm()  # a bad configuration is a usage error, found before anything runs
    if not work_left(study, store):  # nor is a job submitted for a refused or finished store
        return nullcontext(None)
    return slurm_cluster(args.jobs or 1, study)


def _cmd_reduce(args) -> int:
    from .reduce import reduce_store

    if args.out is not None:
        try:
            Path(args.out).mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise UsageError(f"--out {args.out}: cannot create the directory ({e.strerror}); "
                             "allowed: a directory path") from None
    reduce_store(args.store, args.out)
    return 0


def _cmd_accuracy(args) -> int:
    from .accuracy_study import run_accuracy_study

    if args.scheduler and args.workers:
        raise UsageError("--workers sizes a LocalCluster; with --scheduler the cluster's own "
                         "workers run the tasks (allowed: one of the two)")
    if not Path(args.workflow).exists():
        raise UsageError(f"{args.workflow}: no such workflow file")
    run_accuracy_study(args.workflow, args.out, quick=args.quick, workers=args.workers,
                       scheduler=args.scheduler, figure=args.figure)
    return 0


def _cmd_status(args) -> int:
    from .store import StudyStore

    store = StudyStore.open(args.store)
    print(_status_text(store))
    return 0


def _cmd_verify(args) -> int:
    from .verify import verify_store

    report = verify_store(args.store)
    for problem in report.problems:
        print(problem)
    print(report.summary())
    if not report.ok:
        _error(f"{report.path}: {len(report.problems)} inconsistencies (listed above)")
        return EXIT_FAILED
    return 0


def _status_text(store) -> str:
    study = store.study
    done = store.done()
    lines = [f"{study.name}: {int(done.sum())}/{done.size} chunks done in {store.path} "
             f"({len(study.frequencies)} frequencies x {len(study.families)} families x "
             f"{study.accuracy.n_chunks} chunks of {study.accuracy.chunk_size} particles)"]
    names = [fam.name for fam in study.families]
    width = max(len(n) for n in names)
    lines.append("f (Hz)    " + "  ".join(n.rjust(max(width, 5)) for n in names))
    for fi, f in enumerate(study.frequencies):
        cells = [f"{int(done[fi, mi].sum())}/{done.shape[2]}".rjust(max(width, 5))
                 for mi in range(len(names))]
        lines.append(f"{f:<9g} " + "  ".join(cells))
    return "\n".join(lines)


def _error(message: str) -> None:
    print(f"bbb: error: {message}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
