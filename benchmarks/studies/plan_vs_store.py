"""What one map cost against its ``bbb plan``, refinement counted: the plan prices the points the
scene lists; refinement's points are measured apart and added to the total.

    python -m benchmarks.studies.plan_vs_store PLAN.txt STORE SCENE.toml [--cpu SECONDS] [--label TEXT]

PLAN.txt is the output of ``bbb plan`` (its ``total`` row: chunks, collisions, CPU-s in tasks);
STORE the map's store after ``bbb run`` (read only); SCENE the workflow whose listed points the
plan priced; ``--cpu`` the run's measured CPU-s (user + system of the ``bbb run`` process tree,
e.g. from ``/usr/bin/time -v``: the whole run, refinement included).  Chunks and collisions are
read from the store, so they do not depend on the machine's load.  Prints one Markdown row:
measured / planned at the listed points, refinement's points, chunks and collisions, and the
whole map (listed + refinement) / planned.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import numpy as np
import zarr

from pipeline.workflow.identity import point_key
from pipeline.workflow.load import load_workflow

HEADER = ("| map | points (listed) | chunks planned / listed / all | collisions planned / listed / all "
          "| CPU-s planned / all | refinement added |\n| --- | --- | --- | --- | --- | --- |")


def planned(text: str) -> tuple[float, float, float]:
    """(chunks, collisions, CPU-s in tasks) of a ``bbb plan`` output's ``total`` row."""
    m = re.search(r"^[#\s]*total\s+\d+\s+(\d+)\s+([\d.e+]+)\s+([\d.]+)", text, re.M)
    if m is None:
        raise SystemExit("no 'total' row in the plan: is it the output of bbb plan?")
    return float(m.group(1)), float(m.group(2)), float(m.group(3))


def measured(store: str, scene: str) -> dict[str, float]:
    """Points, done chunks and their collisions in the store, at the scene's listed points and
    in all.  Read with zarr alone (the arrays done, n_collisions and the points' coordinates),
    so a store of an earlier layout reads too."""
    study = load_workflow(scene)
    g = zarr.open_group(store, mode="r")
    done = np.asarray(g["done"][...])  # (point, family, chunk)
    coll = np.asarray(g["n_collisions"][...])  # (point, family, particle)
    P, M, C = done.shape
    coll = coll.reshape(P, M, C, -1).sum(axis=3) * done  # collisions of the done chunks
    axes = [name for name, _ in study.points[0].grid]
    coords = [np.asarray(g[name][...]) for name in ("frequency", *axes)]
    keys = [point_key(float(c[0][i]), tuple((a, float(v[i])) for a, v in zip(axes, c[1:], strict=True)))
            for i, c in ((i, coords) for i in range(P))]
    listed = {point_key(p.f, p.grid) for p in study.points}
    is_listed = np.array([k in listed for k in keys])
    if is_listed.sum() != len(listed):
        raise SystemExit(f"the store holds {is_listed.sum()} of the scene's {len(listed)} listed points")
    return {"points": P, "listed": int(is_listed.sum()),
            "chunks": float(done[is_listed].sum()), "collisions": float(coll[is_listed].sum()),
            "chunks_all": float(done.sum()), "collisions_all": float(coll.sum())}


def row(label: str, plan: tuple[float, float, float], m: dict[str, float], cpu: float | None) -> str:
    chunks, coll, cpu_s = plan
    cpu_text = (f"{cpu_s:.0f} / {cpu:.0f} ({cpu / cpu_s:.2f})" if cpu is not None
                else f"{cpu_s:.0f} / not measured")
    return (f"| {label} | {m['points']} ({m['listed']}) | {chunks:.0f} / {m['chunks']:.0f} "
            f"({m['chunks'] / chunks:.2f}) / {m['chunks_all']:.0f} ({m['chunks_all'] / chunks:.2f}) | "
            f"{coll:.3g} / {m['collisions']:.3g} ({m['collisions'] / coll:.2f}) / "
            f"{m['collisions_all']:.3g} ({m['collisions_all'] / coll:.2f}) | {cpu_text} | "
            f"{m['points'] - m['listed']} points, {m['chunks_all'] - m['chunks']:.0f} chunks, "
            f"{m['collisions_all'] - m['collisions']:.3g} collisions |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("plan", type=Path)
    ap.add_argument("store")
    ap.add_argument("scene")
    ap.add_argument("--cpu", type=float, default=None, help="the run's CPU-s (user + system)")
    ap.add_argument("--label", default=None)
    a = ap.parse_args()
    plan = planned(a.plan.read_text(encoding="utf-8"))
    m = measured(a.store, a.scene)
    print(HEADER)
    print(row(a.label or f"`{Path(a.scene).stem}`", plan, m, a.cpu))


if __name__ == "__main__":
    main()
