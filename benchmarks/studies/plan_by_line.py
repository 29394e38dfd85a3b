"""A map's plan against its store, line by line: which grid lines does `bbb plan` price well?

    python -m benchmarks.studies.plan_by_line WORKFLOW STORE [--pilot-lines probes|all]

For every grid value of the map's first axis, the collisions the plan predicts at the listed
points against those the store holds there (measured / planned), and the same per frequency
band.  A plan pilots the probe lines (corners and centre) and costs the others by an
inverse-square-distance mean: this shows how far that guess is from the lines it did not pilot.
"""

from __future__ import annotations

import argparse
import collections

import numpy as np

from pipeline.execute.pilot import pilot_rates
from pipeline.execute.plan import BAND_EDGES, predict
from pipeline.store.study_store import StudyStore
from pipeline.workflow.identity import point_key
from pipeline.workflow.load import load_workflow


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("workflow")
    ap.add_argument("store")
    ap.add_argument("--pilot-lines", default="probes", choices=("probes", "all"))
    a = ap.parse_args()
    study = load_workflow(a.workflow)
    rates = pilot_rates(study, particles=8, lines=a.pilot_lines, echo=lambda m: None)
    plan = predict(study, rates, 2)
    st = StudyStore.open(a.store)
    coll = np.asarray(st.group()["n_collisions"][...])
    per_point = coll.reshape(coll.shape[0], -1).sum(axis=1)
    index = {point_key(p.f, p.grid): i for i, p in enumerate(st.study.points)}
    axis = study.grid[0][0]
    probed = {dict(k[2]).get(axis) for k in rates.cells if len(k) > 2}
    by_line, by_band = collections.defaultdict(lambda: [0.0, 0.0]), collections.defaultdict(
        lambda: [0.0, 0.0])
    for r in plan.rows:
        m = float(per_point[index[point_key(r.f, r.grid)]])
        value = dict(r.grid)[axis]
        band = max((e for e in BAND_EDGES if e <= r.f), default=0.0)
        for box, key in ((by_line, value), (by_band, band)):
            box[key][0] += r.collisions
            box[key][1] += m
    print(f"{study.name}: plan with --pilot-lines {a.pilot_lines}; probed {axis} = "
          f"{', '.join(f'{v:g}' for v in sorted(probed))}")
    print(f"{axis:>8} {'planned':>10} {'measured':>10} {'ratio':>6}")
    for key, (p, m) in sorted(by_line.items()):
        mark = " probed" if key in probed else ""
        print(f"{key:>8g} {p:>10.3g} {m:>10.3g} {m / p if p else float('nan'):>6.2f}{mark}")
    print(f"{'band from':>8} {'planned':>10} {'measured':>10} {'ratio':>6}")
    for key, (p, m) in sorted(by_band.items()):
        print(f"{key:>8g} {p:>10.3g} {m:>10.3g} {m / p if p else float('nan'):>6.2f}")


if __name__ == "__main__":
    main()
