"""``bbb status``: what a store holds, as text: its done chunks per point and family, and the
batch jobs of a run writing it (pipeline/store/jobs.py)."""

from __future__ import annotations

from ..workflow.identity import f_key
from .jobs import jobs_text
from .layout import STOP_LEGEND
from .study_store import StudyStore

__all__ = ["status_text"]


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


def _cell(v) -> str:
    """A grid value as the status table writes it."""
    return v if isinstance(v, str) else f"{v:g}"
