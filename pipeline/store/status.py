"""``bbb status``: what a store holds, as text or as JSON (``--json``): its done chunks per
point and family, and the batch jobs of a run writing it (pipeline/store/jobs.py)."""

from __future__ import annotations

from ..workflow.identity import f_key
from .jobs import jobs_dict, jobs_text
from .layout import STOP_LEGEND
from .study_store import StudyStore

__all__ = ["status_text", "status_dict", "STATUS_KEYS"]

#: the keys of :func:`status_dict` (``bbb status --json``), each with its meaning
STATUS_KEYS = {
    "name": "the study's name",
    "path": "the store's path or URL",
    "chunks_done": "chunks done in the whole store",
    "chunks_total": "chunks the store holds (points x families x chunks per family)",
    "chunk_size": "particles per chunk",
    "axes": "the point's coordinates: [\"f\"] or the grid's axes with f",
    "families": "the families' names, in store order",
    "target_ci": "relative CI half-width of D a target-driven store stops at, else null",
    "points": "one object per point: f (Hz), grid ({axis: value}, {} without a grid), refined "
              "(added by refinement), families ({name: {done, total, stop}}; stop: why a "
              "target-driven family stopped -- open, target met, resolved to ±d_resolved, cap -- else null)",
    "jobs": "null, or the batch jobs of a run writing the store: record, run_alive, queue "
            "([{job_id, state, time, nodes_or_reason}] from squeue, or null), queue_error",
}


def status_text(store: StudyStore) -> str:
    """`bbb status`: done/total chunks of every point and family (and why each stopped, in
    a target-driven store), one line a point with its grid values."""
    study = store.study
    done = store.done()
    where = (f"{len(study.points)} points ({' x '.join(a for a, _ in study.axes)})"
             if study.grid else f"{len(study.frequencies)} frequencies")
    lines = [f"{study.name}: {int(done.sum())}/{done.size} chunks done in {store.path} "
             f"({where} x {len(study.families)} families x "
             f"{study.accuracy.n_chunks} chunks of {study.accuracy.chunk_size} particles)"]
    names = [fam.name for fam in study.families]
    width = max(len(n) for n in names)
    stops = store.stops()  # target_ci: chunks used and why each (f, family) stopped
    if stops is not None:
        width = max(width, 22)
        lines[0] += f"; target CI half-width {study.accuracy.target_ci:g} of D"
    refined = {f_key(f) for f in study.refined}
    axes = [a for a, _ in study.grid]
    aw = {a: max(len(a), *(len(_cell(dict(p.grid)[a])) for p in study.points)) for a in axes}
    lines.append("f (Hz)    " + "".join(f"{a:<{aw[a]}}  " for a in axes)
                 + "  ".join(n.rjust(max(width, 5)) for n in names))
    for fi, point in enumerate(study.points):
        f = point.f
        cells = [f"{int(done[fi, mi].sum())}/{done.shape[2]}" for mi in range(len(names))]
        if stops is not None:
            cells = [c + f" {STOP_LEGEND[int(stops[1][fi, mi])]}" for mi, c in enumerate(cells)]
        mark = "*" if f_key(f) in refined else " "
        values = "".join(f"{_cell(v):<{aw[a]}}  " for a, v in point.grid)
        lines.append(f"{f:<8g}{mark} " + values + "  ".join(c.rjust(max(width, 5)) for c in cells))
    if refined:
        lines.append(f"* added by refinement ({len(refined)} frequencies, to "
                     f"{study.refine.to:g} Hz)")
    jobs = jobs_text(store.path)  # a run on a batch system: its jobs, with squeue's states
    if jobs is not None:
        lines.append(jobs)
    return "\n".join(lines)


def status_dict(store: StudyStore) -> dict:
    """`bbb status --json`: what :func:`status_text` shows, as JSON-able data (keys: see
    :data:`STATUS_KEYS`)."""
    study = store.study
    done = store.done()
    stops = store.stops()
    refined = {f_key(f) for f in study.refined}
    names = [fam.name for fam in study.families]
    points = []
    for fi, point in enumerate(study.points):
        fams = {name: {"done": int(done[fi, mi].sum()), "total": int(done.shape[2]),
                       "stop": STOP_LEGEND[int(stops[1][fi, mi])] if stops is not None else None}
                for mi, name in enumerate(names)}
        grid = {a: v if isinstance(v, str) else float(v) for a, v in point.grid}
        points.append({"f": float(point.f), "grid": grid,
                       "refined": f_key(point.f) in refined, "families": fams})
    return {"name": study.name, "path": str(store.path), "chunks_done": int(done.sum()),
            "chunks_total": int(done.size), "chunk_size": study.accuracy.chunk_size,
            "axes": [a for a, _ in study.axes], "families": names,
            "target_ci": study.accuracy.target_ci, "points": points, "jobs": jobs_dict(store.path)}


def _cell(v) -> str:
    """A grid value as the status table writes it."""
    return v if isinstance(v, str) else f"{v:g}"
