"""`bbb plan` on a map against the measured run: the plan pilots the grid's probe lines (the
corners and the centre of its numeric axes) and prices every other line as the nearest probed
one; then the map runs on a LocalCluster of 2 workers and the predicted CPU (in tasks) and wall
time are compared with the measured ones.

    python -m benchmarks.studies.maps_plan [--alphas 0.5,0.6,0.7,0.8,0.9] [--particles 128] [--t-max 50]

Run it on a quiet machine (the pilot reads CPU time, the run wall time).  Prints a table;
commit the output under benchmarks/results/ with the date and the CPU."""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import shutil
import tempfile
from pathlib import Path

from benchmarks.common import cpu_name

SCENE = """\
[study]
name = "plan_map"
seed = 2004

[params]
preset = "klages2004"

[frequencies]
values = [54.0, 58.0, 60.0, 66.0, 72.0, 80.0]

[grid]
alpha = {alphas}

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"
launch_speed = [0.0, 200.0]

[accuracy]
preset = "draft"
n_particles = {n}
chunk_size = {cs}
t_max = {t_max}

[observables.positions]
"""


def main() -> None:
    from pipeline.execute.pilot import pilot_rates, probe_lines
    from pipeline.execute.plan import predict
    from pipeline.execute.run import run_study
    from pipeline.workflow.load import parse_workflow

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--alphas", default="0.5,0.6,0.7,0.8,0.9")
    ap.add_argument("--particles", type=int, default=128)
    ap.add_argument("--t-max", type=float, default=50.0)
    args = ap.parse_args()
    alphas = [float(a) for a in args.alphas.split(",")]
    text = SCENE.format(alphas=alphas, n=args.particles, cs=args.particles // 4,
                        t_max=args.t_max)
    study = parse_workflow(text, source="plan_map.toml")
    work = Path(tempfile.mkdtemp(prefix="bbb-maps-plan-"))
    load0 = os.getloadavg()[0]
    try:
        plans = {lines: predict(study, pilot_rates(study, cache_dir=work / "cache", lines=lines),
                                workers=2) for lines in ("probes", "all")}
        report = run_study(study, work / "map.zarr", workers=2, progress=False,
                           dashboard=False, echo=lambda s: None)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    probes = ", ".join("/".join(f"{a} = {v:g}" for a, v in line) for line in probe_lines(study))
    rows = [(f"{name} ({lines})", getattr(plan, attr), measured)
            for lines, plan in plans.items()
            for name, attr, measured in (("CPU in tasks, s", "cpu_s", report.task_seconds),
                                         ("wall, s", "wall_s", report.wall),
                                         ("collisions", "collisions", report.collisions))]
    out = [f"# bbb plan on a map vs the measured run, {datetime.date.today()}, {cpu_name()}, "
           f"{os.cpu_count()} cores, Python {platform.python_version()}, load average "
           f"{load0:.2f} before, {os.getloadavg()[0]:.2f} after",
           "",
           f"map: {len(study.points)} points ({len(alphas)} alpha x {len(study.frequencies)} f) x "
           f"2 families x {args.particles} particles x {args.t_max:g} s; probe lines: {probes}",
           "",
           "| | predicted | measured | measured / predicted |",
           "| --- | --- | --- | --- |"]
    for name, p, m in rows:
        out.append(f"| {name} | {p:.4g} | {m:.4g} | {m / p:.3f} |")
    out += ["", "probes: the plan pilots the probe lines and costs the others from them "
            "(inverse-square distance); all: `bbb plan --pilot-lines all` pilots every line",
            "target: every ratio within 0.70-1.30"]
    print("\n".join(out))


if __name__ == "__main__":
    main()
