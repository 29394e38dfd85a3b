"""``bbb plan`` (what a workflow will cost on this machine, from a cached pilot) and ``bbb
scenes`` (the shipped scenes: name, study, description, and their cost where a pilot of
them is cached, or with ``--cost`` for every one)."""

from __future__ import annotations

import os
import sys

from ..execute.pilot import PILOT_MAX_SHARE, PILOT_PARTICLES, PILOT_PARTICLES_TARGET, PILOT_SHARE
from .common import WORKFLOW_HELP, UsageError, load, positive_int, positive_ints

__all__ = ["add_parsers", "cmd_plan", "cmd_scenes", "scene_cost", "study_cost"]


def add_parsers(sub) -> None:
    pl = sub.add_parser("plan", help="predict CPU and wall time of a workflow before it runs "
                                     "(a cached pilot of a few particles; pipeline/execute/pilot.py), "
                                     "and its wall time at this machine's load now")
    pl.add_argument("workflow", metavar="WORKFLOW", help=WORKFLOW_HELP)
    pl.add_argument("--workers", metavar="N[,N...]", type=positive_ints,
                    help="worker counts, e.g. 2,8,64,256: the table at the first, and each "
                         "one's wall time simulated (default: number of cores)")
    pl.add_argument("--cluster", choices=("slurm",), help="for SLURM jobs (default: this machine)")
    pl.add_argument("--cores-per-job", metavar="K", type=positive_int, default=32, help="SLURM job size")
    pl.add_argument("--pilot-lines", choices=("auto", "probes", "all"), default="auto",
                    help=f"a map: every line when that costs <= {PILOT_SHARE * 100:g} %% of the "
                         "run, else the corner and centre lines, the others costed from them "
                         "(auto, default); the corner and centre lines (probes); every line (all)")
    pl.add_argument("--pilot-particles", metavar="N", type=positive_int, default=None,
                    help=f"pilot particles per (frequency, family) (default: {PILOT_PARTICLES}, "
                         f"at most {100 * PILOT_MAX_SHARE:g} %% of the scene's particles -- none below "
                         f"{1 / PILOT_MAX_SHARE:g}: a scene cheaper than its pilot; "
                         f"{PILOT_PARTICLES_TARGET} for a scene with a CI target, whose cost "
                         "the particles' spread of D sets)")
    pl.add_argument("--kernel-rate", metavar="FILE",
                    help="take the kernel rate (collisions/s/core) from a kernel benchmark table "
                         "(benchmarks/results/kernel-*.txt) instead of the pilot's CPU time")
    pl.set_defaults(handler=cmd_plan)

    sc = sub.add_parser(
        "scenes", help="the shipped scenes (usable wherever a WORKFLOW is asked for): name, "
                       "study, the planned cost on this machine where a pilot is cached "
                       "(runs/plan-cache, by `bbb plan NAME`), description",
        description="One line per shipped scene: name, study, cost, description.  The cost "
                    "is `bbb plan NAME`'s prediction (CPU time, and wall time on this "
                    "machine's cores), read from the pilot cache runs/plan-cache below the "
                    "current directory; a scene without a cached pilot shows `bbb plan NAME`. "
                    "Listing takes 1 s, 3-4 s with every pilot cached (measured on a busy "
                    "2-core machine).  --cost pilots every scene not cached first: 5 CPU-min "
                    "for all of them (19 min wall measured at low priority on that machine).")
    sc.add_argument("--cost", action="store_true",
                    help="pilot every scene whose pilot is not cached first (5 CPU-min for all; "
                         "cached after)")
    sc.set_defaults(handler=cmd_scenes)


def cmd_plan(args) -> int:
    from ..execute.machine_load import loaded_wall
    from ..execute.pilot import cheaper_than_pilot, machine_share, plan_rates
    from ..execute.plan import predict
    from ..execute.scale_plan import plan_report

    study = load(args.workflow)
    why = cheaper_than_pilot(study) if args.pilot_particles is None else None
    if why is not None:
        print(why)
        return 0
    try:
        rates = plan_rates(study, args.pilot_particles, args.pilot_lines, args.kernel_rate,
                           echo=lambda m: print(m, file=sys.stderr))
    except ValueError as e:  # a --kernel-rate file that is no kernel benchmark table
        raise UsageError(str(e)) from None
    workers = list(args.workers or (os.cpu_count() or 1,))
    cores = os.cpu_count() or 1
    print(plan_report(study, rates, workers, kind=args.cluster or "local", cores=cores,
                      per_job=args.cores_per_job))
    if args.cluster is None:
        plan = predict(study, rates, workers[0])
        print(loaded_wall(plan, machine_share(rates.busy), cores))
    return 0


def scene_cost(name: str, measure: bool = False, echo=None) -> str:
    """The planned cost of shipped scene ``name`` as `bbb scenes` shows it (:func:`study_cost`)."""
    from ..workflow.scenes import load_scene

    return study_cost(load_scene(name), measure, echo, hint=f"bbb plan {name}")


def study_cost(study, measure: bool = False, echo=None, hint: str = "bbb plan") -> str:
    """A study's planned cost on this machine's cores, e.g. "CPU 12 min, wall 6.5 min on 2
    cores": `bbb plan`'s prediction from its default pilot, read from the pilot cache
    (runs/plan-cache below the current directory; the pilot run first if ``measure``), else
    "? (HINT)".  "+" marks a scene whose refinement adds points the plan does not price."""
    from ..execute.pilot import pilot_rates
    from ..execute.plan import predict

    rates = pilot_rates(study, echo=echo, cached_only=not measure)
    if rates is None:
        return f"? ({hint})"
    cores = os.cpu_count() or 1
    plan = predict(study, rates, cores)
    more = "+" if study.refine is not None or study.grid_refine is not None else ""
    return (f"CPU {_duration(plan.cpu_s)}{more}, wall {_duration(plan.wall_s)}{more} "
            f"on {cores} cores")


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.1f} min"
    return f"{s / 3600:.1f} h"


def cmd_scenes(args) -> int:
    from ..workflow.scenes import scene_description, scene_names, scene_study

    names = scene_names()
    studies = {n: scene_study(n) for n in names}
    wn, ws = max(map(len, names)), max(map(len, studies.values()))
    echo = (lambda m: print(m, file=sys.stderr)) if args.cost else None
    costs = {n: scene_cost(n, measure=args.cost, echo=echo) for n in names}
    wc = max(map(len, costs.values()))
    for name in names:
        print(f"{name:<{wn}}  {studies[name]:<{ws}}  {costs[name]:<{wc}}  "
              f"{scene_description(name)}")
    print("a scene's name works wherever a WORKFLOW is asked for (bbb run NAME, bbb plan "
          "NAME, ...); cost: `bbb plan NAME`'s prediction on this machine (+: refinement adds "
          "points, not priced)", file=sys.stderr)
    return 0
