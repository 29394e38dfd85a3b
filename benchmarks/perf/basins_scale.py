"""The basin scene at scale: `bbb plan`'s predicted wall time and efficiency at 2 / 64 / 256
workers, and the chunk size that keeps 256 workers at >= 90 %.

    python -m benchmarks.perf.basins_scale [--scene pipeline/studies/basins/scenes/basins.toml]

Prints (commit as benchmarks/results/plan-basins-<date>.txt): the plan's table on this machine
(pipeline/execute/plan.py, from a pilot of 8 particles per (frequency, family), cached in
runs/plan-cache), the scaling table at 2, 64 and 256 workers on this machine's kind of worker
and as SLURM jobs of 32 single-core workers (pipeline/execute/scale_plan.py with the measured
overheads ``MEASURED``), and a chunk-size sweep at 256 workers.  Pure computation once the
pilot is cached: the machine's load enters only the pilot's rates.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import sys
from dataclasses import replace

from benchmarks.common import cpu_name
from pipeline.execute.pilot import plan_rates
from pipeline.execute.scale_plan import (
    chunk_size_sweep,
    plan_report,
    scaling_table,
    sweep_table,
    units_of,
)
from pipeline.workflow.load import load_workflow

WORKERS = [2, 64, 256]
SIZES = [16, 32, 64, 128, 256, 512, 1024]
#: chunk sizes swept for the larger variants (the small ones are serial-bound already)
BIG_SIZES = [128, 256, 512]
#: chunk sizes whose scaling is shown in full
CHOSEN = (64, 256)  # the scene ships 256
#: MB per particle of the recording a task holds (40000 rows x 6 float64)
MB_PER_PARTICLE = 40000 * 6 * 8 / 1e6


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="pipeline/studies/basins/scenes/basins.toml")
    a = ap.parse_args(argv)
    study = load_workflow(a.scene)
    rates = plan_rates(study, 8, "auto", None, echo=lambda m: print(m, file=sys.stderr))
    load = os.getloadavg()[0]
    print(f"# bbb plan of {a.scene} at {', '.join(map(str, WORKERS))} workers, "
          f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC, {cpu_name()}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}, load average "
          f"{load:.2f} (the pilot's rates only)")
    print(f"# command: python -m benchmarks.perf.basins_scale --scene {a.scene}")
    print("\n## this machine's kind of worker (bbb plan --workers 2,64,256)\n")
    print(plan_report(study, rates, WORKERS, kind="local", cores=os.cpu_count() or 1))
    print("\n## SLURM jobs of 32 single-core workers, warm kernel cache\n")
    print(plan_report(study, rates, WORKERS, kind="slurm", cores=os.cpu_count() or 1,
                      per_job=32).split("\n\n", 1)[1])
    print()
    print(sweep_table(chunk_size_sweep(study, rates, 256, SIZES, kind="slurm",
                                       cores=os.cpu_count() or 1, per_job=32), 256))
    for size in CHOSEN:
        sized = replace(study, accuracy=replace(study.accuracy, chunk_size=size))
        print(f"\n## chunk_size {size} ({size * MB_PER_PARTICLE:.0f} MB of recorded collisions "
              "per task), SLURM jobs of 32\n")
        print(scaling_table(units_of(sized, rates), WORKERS, kind="slurm",
                            cores=os.cpu_count() or 1, per_job=32))
    for k in (2, 4):
        big = replace(study, accuracy=replace(study.accuracy, n_particles=k * study.accuracy.n_particles))
        print(f"\n## the same scene with {k} x the cells (what 256 workers need to reach 90 %)\n")
        print(sweep_table(chunk_size_sweep(big, rates, 256, BIG_SIZES, kind="slurm",
                                           cores=os.cpu_count() or 1, per_job=32), 256))
    return 0


if __name__ == "__main__":
    sys.exit(main())
