"""`bbb plan` against measured runs: every workflow in workflows/ and every scene in
pipeline/studies/*/scenes/ (issue 12, item 4).

    .venv/bin/python -m benchmarks.studies.plan > benchmarks/results/plan-DATE.txt

For each scene: the prediction on 2 workers with the kernel rate of today's pilot (the
default of `bbb plan`) and with the rate of the committed kernel benchmark of the day the
scenes were measured (benchmarks/results/kernel-2026-11-22.txt), beside the measured wall
time and task time of the committed `make figures` run (figures/run_log.json) and of the
2026-11-22 pipeline benchmark (Fig. 2 at draft and standard).  The pilots are cached in
runs/plan-cache, so a re-run only re-reads them.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import sys
from pathlib import Path

from benchmarks.common import ROOT, cpu_name
from pipeline.execute.pilot import benchmark_rate, pilot_rates
from pipeline.execute.plan import plan_table, predict
from pipeline.workflow.load import load_workflow, parse_workflow

KERNEL_TABLE = "benchmarks/results/kernel-2026-11-22.txt"
# Fig. 2 at draft and standard, measured end to end on 2 workers (pipeline-2026-11-22.txt):
# (wall s, task s); draft collisions = 3.32e6/s over the 27.2 s wall.
PIPELINE_BENCH = {"draft": (27.2, 50.4), "standard": (474.0, 934.0)}


def scenes():
    """(label, Study, measured (wall, task s) or None) for every scene."""
    log = json.loads((ROOT / "figures" / "run_log.json").read_text())["scenes"]
    measured = {e["workflow"]: (e["wall_s"], e["task_s"]) for e in log.values()}
    paths = sorted((ROOT / "workflows").glob("*.toml")) + sorted(
        (ROOT / "pipeline" / "studies").glob("*/scenes/*.toml"))
    for p in paths:
        rel = p.relative_to(ROOT).as_posix()
        yield rel, load_workflow(p), measured.get(rel)
        if p.stem == "figure2":
            text = p.read_text()
            for preset, m in PIPELINE_BENCH.items():
                study = parse_workflow(text.replace('preset = "paper"', f'preset = "{preset}"'),
                                       source=rel)
                yield f"{rel} at {preset}", study, m


def main() -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # no options: --help only
    os.chdir(ROOT)
    bench = benchmark_rate(KERNEL_TABLE)
    print(f"# bbb plan vs measured runs  {datetime.datetime.now():%Y-%m-%dT%H:%M:%S}")
    print(f"# CPU: {cpu_name()} ({os.cpu_count()} cores)  python {platform.python_version()}  "
          f"load {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print("# predicted on 2 workers; rate A = today's pilot (process CPU time x 0.82 in tasks),"
          f" rate B = {Path(KERNEL_TABLE).name} ({bench:.3g} coll/s/core, x 0.82)")
    print("# measured: figures/run_log.json (make figures, 2026-11-22) and "
          "pipeline-2026-11-22.txt (Fig. 2 draft, standard)")
    print()
    head = (f"{'scene':<46} {'collisions':>10} {'CPU A':>7} {'wall A':>7} {'CPU B':>7} "
            f"{'wall B':>7} {'CPU meas':>8} {'wall meas':>9} {'wall A/meas':>11} "
            f"{'wall B/meas':>11}")
    print(head)
    print("-" * len(head))
    tables = []
    for label, study, m in scenes():
        rates = pilot_rates(study, echo=lambda s: print(s, file=sys.stderr))
        a = predict(study, rates, workers=2)
        b = predict(study, rates.with_rate(bench, Path(KERNEL_TABLE).name), workers=2)
        meas = (f"{m[1]:>8.0f} {m[0]:>9.1f} {a.wall_s / m[0]:>11.2f} {b.wall_s / m[0]:>11.2f}"
                if m else f"{'-':>8} {'-':>9} {'not measured':>23}")
        print(f"{label:<46} {a.collisions:>10.3g} {a.cpu_s:>7.0f} {a.wall_s:>7.1f} "
              f"{b.cpu_s:>7.0f} {b.wall_s:>7.1f} {meas}")
        if label == "workflows/figure2.toml":
            tables += [plan_table(a), plan_table(b)]
    print()
    print("## Fig. 2 at paper, the table `bbb plan` prints (rate A, then rate B)")
    for t in tables:
        print()
        print(t)


if __name__ == "__main__":
    main()
