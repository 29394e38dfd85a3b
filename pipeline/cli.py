"""The ``bbb`` command line: ``bbb run``, ``bbb reduce``, ``bbb status``, ``bbb verify``,
``bbb plot``, ``bbb accuracy``, ``bbb plan``, ``bbb --version``.

``bbb run WORKFLOW --frequencies 60,72`` runs only those frequencies of the workflow, into a
store of their own (default ``runs/<name>-60Hz-72Hz.zarr``); chunk seeds are keyed by the
frequency's value (pipeline/workflow/study.py), so its chunks are those of the whole sweep, bit for bit.
``bbb reduce STORE --workflow W`` reduces with W's analysis settings ([analysis] and
``accuracy.n_resamples``) without re-running; W must otherwise describe the stored data.

Usage errors (bad arguments, a malformed workflow, a store of another workflow) print one line
``bbb: error: ...`` to stderr and exit with status 2, without a traceback.  A failed task exits
with status 1 and names the frequency, family and chunk.  ``bbb run`` stopped by Ctrl-C exits
with status 130, by SIGTERM (``kill``, a batch system ending the job it runs in) with 143; both
end the run alike: the store's lock is released and, with ``--cluster``, every job cancelled.
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import sys
from dataclasses import replace
from importlib import metadata
from pathlib import Path

from .execute.interrupt import Terminated, sigterm_as_interrupt
from .store.layout import default_store_path  # importable from here as before
from .workflow.identity import f_key

__all__ = ["main", "default_store_path"]

EXIT_USAGE = 2
EXIT_FAILED = 1
EXIT_TERMINATED = 128 + signal.SIGTERM


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # argparse prints usage + message; we want one line
        raise UsageError(f"{self.prog}: {message} (see {self.prog} --help)")


def _build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="bbb", description="Bouncing ball billiard study pipeline.")
    p.add_argument("--version", action="version", version=f"bbb {version()}")
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
    r.add_argument("--jobs", metavar="N|MIN:MAX", type=_jobs,
                   help="with --cluster: N jobs at once (default: 1), or MIN:MAX for elastic "
                        "workers, one per chunk queued, between MIN and MAX jobs")
    r.add_argument("--frequencies", metavar="F1,F2,...", type=_frequency_list,
                   help="only these frequencies of the workflow (Hz), into their own store "
                        "(default: runs/<name>-F1Hz-F2Hz.zarr); same seeds, so the same chunks "
                        "as the whole sweep")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")

    d = sub.add_parser("reduce", help="D(f) with bootstrap CIs and ergodicity verdicts")
    d.add_argument("store", metavar="STORE", help="a study store made by `bbb run`")
    d.add_argument("--out", metavar="DIR",
                   help="where diffusion.parquet/.csv go (default: beside the store, "
                        "in a folder named like it without .zarr)")
    d.add_argument("--workflow", metavar="WORKFLOW",
                   help="reduce with this workflow's [analysis] and accuracy.n_resamples "
                        "(its simulation settings must be the store's)")

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

    pl = sub.add_parser("plan", help="predict CPU and wall time of a workflow before it runs "
                                     "(a cached pilot of a few particles; pipeline/execute/pilot.py)")
    pl.add_argument("workflow", metavar="WORKFLOW", help="workflow TOML file")
    pl.add_argument("--workers", metavar="N[,N...]", type=_positive_ints,
                    help="worker counts, e.g. 2,8,64,256: the table at the first, and each "
                         "one's wall time simulated (default: number of cores)")
    pl.add_argument("--cluster", choices=("slurm",), help="for SLURM jobs (default: this machine)")
    pl.add_argument("--cores-per-job", metavar="K", type=_positive_int, default=32, help="SLURM job size")
    pl.add_argument("--pilot-lines", choices=("auto", "probes", "all"), default="auto",
                    help="a map: every line when that costs <= 5 %% of the run, else the "
                         "corner and centre lines, the others costed from them (auto, default); "
                         "the corner and centre lines (probes); every line (all)")
    pl.add_argument("--pilot-particles", metavar="N", type=_positive_int, default=8,
                    help="pilot particles per (frequency, family) (default: 8)")
    pl.add_argument("--kernel-rate", metavar="FILE",
                    help="take the kernel rate (collisions/s/core) from a kernel benchmark table "
                         "(benchmarks/results/kernel-*.txt) instead of the pilot's CPU time")

    s = sub.add_parser("status", help="done/total chunks per frequency and family")
    s.add_argument("store", metavar="STORE")

    v = sub.add_parser("verify", help="re-check every done chunk and the attributes of a store; "
                                      "exit 1 listing each inconsistency")
    v.add_argument("store", metavar="STORE")

    g = sub.add_parser("plot", help="figures of a store: D(f) (v, D_drift) with CIs and flags "
                                    "per family, heat maps over frequency x each grid axis")
    g.add_argument("store", metavar="STORE")
    g.add_argument("--out", metavar="DIR", help="where the figures go (default: STORE's name "
                                                "without .zarr, beside it, as bbb reduce)")
    g.add_argument("--format", dest="formats", action="append", choices=("png", "pdf", "svg"),
                   help="file format, repeatable (default: png and pdf)")
    return p


def version() -> str:
    """The installed package's version (importlib.metadata), as pip reports it."""
    try:
        return metadata.version("bbb")
    except metadata.PackageNotFoundError:  # a source tree on sys.path, never installed
        return "unknown (not installed)"


def _frequency_list(text: str) -> tuple[float, ...]:
    """'60,72.5' -> (60.0, 72.5): distinct finite frequencies > 0 Hz, multiples of 1 mHz."""
    allowed = "allowed: comma-separated frequencies in Hz, e.g. 60,72"
    out = []
    for item in text.split(","):
        try:
            f = float(item)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{item.strip()!r} is not a number; {allowed}") from None
        if not math.isfinite(f) or f <= 0 or abs(f * 1000 - f_key(f)) > 1e-6 * f:
            raise argparse.ArgumentTypeError(f"{item.strip()} is out of range; allowed: "
                                             "finite frequencies > 0 Hz, multiples of 0.001 Hz")
        if f_key(f) in {f_key(g) for g in out}:
            raise argparse.ArgumentTypeError(f"{item.strip()} is repeated; {allowed}")
        out.append(f)
    return tuple(out)


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"{n} is out of range; allowed: an integer >= 1")
    return n


def _jobs(text: str) -> int | tuple[int, int]:
    """'4' -> 4; '0:8' -> (0, 8): elastic, 0 <= MIN <= MAX, MAX >= 1."""
    lo, colon, hi = text.partition(":")
    if not colon:
        return _positive_int(text)
    if not (lo.isdigit() and hi.isdigit() and int(lo) <= int(hi) and int(hi) >= 1):
        raise argparse.ArgumentTypeError(f"{text!r}; allowed: N, or MIN:MAX, 0 <= MIN <= MAX >= 1")
    return int(lo), int(hi)


def _positive_ints(text: str) -> tuple[int, ...]:
    return tuple(_positive_int(x.strip()) for x in text.split(","))


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bbb`` script and of ``python -m pipeline``; returns the exit code."""
    try:
        return _main(argv)
    except SystemExit as e:  # --help, or argparse's own exits
        return int(e.code or 0) if isinstance(e.code, int) or e.code is None else EXIT_USAGE
    except UsageError as e:
        _error(str(e).removeprefix("bbb: "))
        return EXIT_USAGE
    except Terminated:
        _error("terminated (SIGTERM); re-run the same command to resume")
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        _error("interrupted; re-run the same command to resume")
        return 130


def _main(argv: list[str] | None) -> int:
    from .store.study_store import StoreError
    from .workflow.load import WorkflowError

    args = _build_parser().parse_args(argv)
    try:
        if args.command == "run":
            with sigterm_as_interrupt():
                return _cmd_run(args)
        if args.command == "reduce":
            return _cmd_reduce(args)
        if args.command == "accuracy":
            return _cmd_accuracy(args)
        if args.command == "verify":
            return _cmd_verify(args)
        if args.command == "plan":
            return _cmd_plan(args)
        if args.command == "plot":
            return _cmd_plot(args)
        return _cmd_status(args)
    except (WorkflowError, StoreError) as e:
        raise UsageError(str(e)) from None


def _cmd_run(args) -> int:
    from .execute.run import RunFailed, run_study
    from .workflow.load import load_workflow

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
    name = study.name
    if args.frequencies:
        study = _frequency_subset(study, args.frequencies, args.workflow)
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


def _frequency_subset(study, wanted: tuple[float, ...], workflow: str):
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
    from contextlib import nullcontext

    if not args.cluster:
        return nullcontext(args.scheduler)
    from .execute.cluster import check_slurm, slurm_cluster, work_left

    check_slurm()  # a bad configuration is a usage error, found before anything runs
    if not work_left(study, store):  # nor is a job submitted for a refused or finished store
        return nullcontext(None)
    return slurm_cluster(args.jobs or 1, study, store=store)


def _cmd_reduce(args) -> int:
    from .tables.reduce import reduce_store

    if args.out is not None:
        try:
            Path(args.out).mkdir(parents=True, exist_ok=True)
        except OSError as e:
            raise UsageError(f"--out {args.out}: cannot create the directory ({e.strerror}); "
                             "allowed: a directory path") from None
    store = args.store
    if args.workflow is not None:
        store = _store_with_analysis_of(args.store, args.workflow)
    reduce_store(store, args.out)
    return 0


def _store_with_analysis_of(path: str, workflow: str):
    """The store at ``path`` carrying the reduce settings of ``workflow``; refused (one line)
    if the workflow would have simulated other data."""
    from .store.study_store import StudyStore, fingerprint_difference
    from .workflow.load import load_workflow

    new = load_workflow(workflow)
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


def _cmd_accuracy(args) -> int:
    from .studies.accuracy.study import run_accuracy_study

    if args.scheduler and args.workers:
        raise UsageError("--workers sizes a LocalCluster; with --scheduler the cluster's own "
                         "workers run the tasks (allowed: one of the two)")
    if not Path(args.workflow).exists():
        raise UsageError(f"{args.workflow}: no such workflow file")
    run_accuracy_study(args.workflow, args.out, quick=args.quick, workers=args.workers,
                       scheduler=args.scheduler, figure=args.figure)
    return 0


def _cmd_plan(args) -> int:
    from .execute.pilot import plan_rates
    from .execute.scale_plan import plan_report
    from .workflow.load import load_workflow

    study = load_workflow(args.workflow)
    try:
        rates = plan_rates(study, args.pilot_particles, args.pilot_lines, args.kernel_rate,
                           echo=lambda m: print(m, file=sys.stderr))
    except ValueError as e:  # a --kernel-rate file that is no kernel benchmark table
        raise UsageError(str(e)) from None
    print(plan_report(study, rates, list(args.workers or (os.cpu_count() or 1,)),
                      kind=args.cluster or "local", cores=os.cpu_count() or 1,
                      per_job=args.cores_per_job))
    return 0


def _cmd_plot(args) -> int:
    from .api import plot_store
    from .store.study_store import StudyStore

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


def _cmd_status(args) -> int:
    from .store.status import status_text
    from .store.study_store import StudyStore

    store = StudyStore.open(args.store)
    print(status_text(store))
    return 0


def _cmd_verify(args) -> int:
    from .store.verify import verify_store

    report = verify_store(args.store)
    for problem in report.problems:
        print(problem)
    print(report.summary())
    if not report.ok:
        _error(f"{report.path}: {len(report.problems)} inconsistencies (listed above)")
        return EXIT_FAILED
    return 0


def _error(message: str) -> None:
    print(f"bbb: error: {message}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
