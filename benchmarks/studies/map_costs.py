"""What each map cost against what ``bbb plan`` predicted: chunks and collisions (independent of
the machine's load) from the store, CPU time from the run's own measurement.

    python -m benchmarks.studies.map_costs [--runs runs] [--cpu NAME=SECONDS ...]

For every map scene below with a plan in ``benchmarks/results/plan-<name>-*.txt`` (the output of
``bbb plan``) and a store ``<runs>/<name>.zarr``: the plan's chunks, collisions and CPU-s in
tasks; the chunks and collisions the store holds at the points the workflow lists (a refined
map's added points are not priced by the plan, and are counted apart); and the CPU-s measured
for the run (``--cpu``: user + system time of the ``bbb run`` process tree, e.g. from
``/usr/bin/time -v``), when one was measured; the pilot's simulation CPU-s (the plan's
``pilot:`` line) and its share of the planned run.  Ratios are measured / planned.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import numpy as np

from benchmarks.common import RESULTS
from pipeline.store.study_store import StudyStore
from pipeline.workflow.identity import point_key
from pipeline.workflow.scenes import load_scene

#: {map scene: the plans of it (``bbb plan`` outputs in benchmarks/results/), one row each}:
#: the plan with bbb plan's defaults (pilot size by scene, --pilot-lines auto) first; for the two
#: target-driven maps also the same model with 8 pilot particles, the size a target scene piloted
#: before; the plans before the pilot model are in map-costs-2026-11-25.md
MAPS = {name: (f"plan-{name}-*-default.txt",) for name in (
    "dissipation", "dissipation_locking", "dissipation_r25", "protocol", "transport_reversal")}
for name in ("dissipation", "dissipation_r25"):
    MAPS[name] += (f"plan-{name}-*-pilot-model.txt",)


def planned(pattern: str) -> dict[str, float] | None:
    files = sorted(RESULTS.glob(pattern))
    if not files:
        return None
    text = files[-1].read_text(encoding="utf-8")
    total = re.search(r"^[#\s]*total\s+\d+\s+(\d+)\s+([\d.e+]+)\s+([\d.]+)", text, re.M)
    pilot = re.search(r"^pilot: ([\d.]+) CPU-s", text, re.M)
    return {"chunks": float(total.group(1)), "collisions": float(total.group(2)),
            "cpu_s": float(total.group(3)), "file": files[-1].name,
            "all": "--pilot-lines all" in text.splitlines()[0],
            "pilot_s": float(pilot.group(1)) if pilot else None,
            "every_line": "every line of the grid" in text,
            "particles": re.search(r"pilot (?:of )?(\d+) particles", text)}


def measured(runs: Path, name: str) -> dict[str, float]:
    st = StudyStore.open(str(runs / f"{name}.zarr"))
    listed = {point_key(p.f, p.grid) for p in load_scene(name).points}
    done = st.done()
    coll = np.asarray(st.group()["n_collisions"][...])
    per_point = np.where(done.any(axis=(1, 2)), coll.reshape(coll.shape[0], -1).sum(axis=1), 0)
    is_listed = np.array([point_key(p.f, p.grid) in listed for p in st.study.points])
    return {"points": len(st.study.points), "listed": int(is_listed.sum()),
            "chunks": float(done[is_listed].sum()), "collisions": float(per_point[is_listed].sum()),
            "chunks_added": float(done[~is_listed].sum()),
            "collisions_added": float(per_point[~is_listed].sum())}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", default="runs", type=Path)
    ap.add_argument("--cpu", action="append", default=[], metavar="NAME=SECONDS")
    a = ap.parse_args()
    cpu = {k: float(v) for k, v in (x.split("=", 1) for x in a.cpu)}
    print("| map | points (listed) | chunks planned / measured | collisions planned / measured "
          "| CPU-s planned / measured | pilot CPU-s | plan |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, patterns in MAPS.items():
        if not (a.runs / f"{name}.zarr").exists():
            continue
        m = measured(a.runs, name)
        added = (f"; refinement added {m['points'] - m['listed']} points, {m['chunks_added']:.0f} "
                 f"chunks, {m['collisions_added']:.3g} collisions, not planned"
                 if m["points"] > m["listed"] else "")
        for p in filter(None, map(planned, patterns)):
            c = cpu.get(name)
            cpu_text = (f"{p['cpu_s']:.0f} / {c:.0f} ({c / p['cpu_s']:.2f})" if c is not None
                        else f"{p['cpu_s']:.0f} / not measured")
            label = (f"`{name}`" + (" (every line piloted)" if p["every_line"] else "")
                     + (f" ({p['particles'].group(1)} pilot particles)" if p["particles"] else "")
                     + ("" if "-default" in p["file"] else " (not the default)"))
            pilot = (f"{p['pilot_s']:.1f} ({100 * p['pilot_s'] / p['cpu_s']:.1f} %)"
                     if p["pilot_s"] is not None else "-")
            print(f"| {label} | {m['points']} ({m['listed']}) | {p['chunks']:.0f} / "
                  f"{m['chunks']:.0f} ({m['chunks'] / p['chunks']:.2f}) | {p['collisions']:.3g} / "
                  f"{m['collisions']:.3g} ({m['collisions'] / p['collisions']:.2f}) | {cpu_text} | "
                  f"{pilot} | {p['file']}{added} |")

if __name__ == "__main__":
    main()
