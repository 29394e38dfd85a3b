"""The Dask task: one (point, family, chunk) simulated on a worker and written to its own
store chunk.

:func:`compute_chunk` is all a worker runs (besides :func:`warm_numba`): it checks that the
worker's kernel is the store's, simulates the chunk's particles from the chunk's seed
(:meth:`pipeline.workflow.study.Study.seed_sequence`) with what the scene's observables ask of
the run (sample times, recorded collisions), lets each observable compute its arrays from it
(:mod:`pipeline.workflow.observables`), and writes the chunk, marking it done last.  The
client side -- the cluster, which chunks to compute, resume, failures -- is
:mod:`pipeline.execute.run`.
"""

from __future__ import annotations

import dataclasses
import functools
import socket
import time
from dataclasses import dataclass

import numpy as np

from ..store.study_store import KERNEL_ATTRS, StudyStore
from ..workflow.identity import f_key
from ..workflow.observables.contract import Chunk
from ..workflow.observables.registry import selected
from ..workflow.study import Study

__all__ = ["ChunkResult", "InjectedFailure", "KernelMismatch", "compute_chunk", "warm_numba",
           "task_key", "is_failing", "store_argument", "point_arg",
           "FAIL_ENV"]

#: the environment variable of fault injection (read by the client, :mod:`pipeline.execute.run`)
FAIL_ENV = "BBB_FAIL_CHUNKS"
ChunkKey = tuple[float, str, int]  # (f in Hz, family name, chunk index)

class InjectedFailure(RuntimeError):
    """The failure asked for by BBB_FAIL_CHUNKS."""


@dataclass(frozen=True)
class ChunkResult:
    """What a task reports back: its key, collisions simulated, the wall time of the
    simulation and of the store writes (s), and the worker's host."""

    key: ChunkKey
    collisions: int
    seconds: float
    write_seconds: float
    host: str



def compute_chunk(store: StudyStore, fi: int, mi: int, ci: int, fail: bool = False,
                  point=None) -> ChunkResult:
    """The Dask task: simulate one chunk of particles of the point of store index fi (the
    frequency index without a grid) and write it to its own store chunk.  The chunk's seed is
    (study seed, f, family, chunk): the same at every point of f whatever its grid values.
    point: the point itself (:class:`pipeline.workflow.point.Point`), given by the client so
    that a worker never computes a map's every point (None: ``store.study.points[fi]``)."""
    from bbb.simulate import simulate

    t0 = time.perf_counter()
    study = store.study
    point = study.points[fi] if point is None else point
    fam = study.families[mi]
    f = point.f
    _check_kernel(store)
    acc, on = study.accuracy, selected(study)
    times = _sample_times(study, f, on)
    initial = _initial(study, point, fam, ci)
    run = simulate(
        point.params, acc.chunk_size, acc.t_max, study.seed_sequence(f, fam, ci),
        sample_times=times, record_collisions=max((o.rows(study) for o in on), default=0),
        record_from=max((o.rows_from(study) for o in on if o.rows(study)), default=0.0),
        numerics=acc.numerics(), **initial,
    )
    chunk = Chunk(study, point, fam, ci, run, times, initial)
    values = {name: v for o in on for name, v in o.compute(chunk).items()}
    seconds = time.perf_counter() - t0
    store.write_chunk(fi, mi, ci, values, seconds, mark_done=not fail)
    if fail:
        raise InjectedFailure(f"{FAIL_ENV} asked this chunk to fail after writing its data")
    return ChunkResult((f, fam.name, ci), int(run.counters["collisions"].sum()), seconds,
                       time.perf_counter() - t0 - seconds, socket.gethostname())


def _initial(study: Study, point, fam, ci: int) -> dict:
    """bbb.simulate's initial-condition keywords for one chunk of ``point``
    (:class:`pipeline.workflow.study.Point`): a lattice family's cells of the chunk
    (bbb.ensemble.lattice_state: particles ci·chunk_size …), the family's draw from the
    chunk's seed, or,
    with mirror pairs (Study.pairing), half of it followed by the partners
    (bbb.ensemble.mirror_pairs)."""
    kw = fam.simulate_kwargs()
    if fam.lattice is not None:
        from bbb.ensemble import lattice_state

        n = study.accuracy.chunk_size
        kw.pop("initial")
        return {"initial": lattice_state(point.params, fam.initial, np.arange(ci * n, (ci + 1) * n),
                                         fam.lattice, fam.offset or 0.0, **kw)}
    if study.pairing(fam, point) != "pairs":
        return kw
    from bbb.ensemble import mirror_pairs

    return {"initial": mirror_pairs(point.params, study.accuracy.chunk_size,
                                    study.seed_sequence(point.f, fam, ci), kw.pop("initial"),
                                    **kw)}


def _sample_times(study: Study, f: float, on) -> np.ndarray | None:
    """The sample times (s) of one chunk's simulation at ``f``: those every selected
    observable asks for, merged (None: none asks)."""
    asked = [t for t in (o.sample_times(study, f) for o in on) if t is not None]
    if len(asked) <= 1:
        return asked[0] if asked else None
    return functools.reduce(np.union1d, asked)


def store_argument(store: StudyStore) -> StudyStore:
    """What the tasks get as their store, sent with each task: the StudyStore itself for a
    scene without a grid; for a map the same store with a Study that has not computed its
    points (each task is given its own point, :func:`compute_chunk`): the Params of every
    point, 1.5 MB at 10^4 points, sent with each of 10^4 tasks made the scheduler the
    bottleneck (811 tasks in 9 min).  Not scattered: data scattered to workers is lost with
    them, and a run must survive losing any worker (a SLURM job cancelled)."""
    if not store.study.grid:
        return store
    return StudyStore(store.path, dataclasses.replace(store.study))  # no cached points


def point_arg(study: Study, fi: int):
    """The point compute_chunk is given for store index fi: a map's Point, None without a
    grid (the worker's Study has it at hand)."""
    return study.points[fi] if study.grid else None


def task_key(study: Study, fi: int, mi: int, ci: int, token: str) -> str:
    """The Dask key of the task of (point fi, family mi, chunk ci): readable on the
    dashboard, unique within a run (``token``); a grid point is named by its index too."""
    f, fam = study.points[fi].f, study.families[mi].name
    where = f"p{fi}-" if study.grid else ""
    return f"bbb-{where}{f_key(f)}mHz-{fam}-{ci}-{token}"


def is_failing(study: Study, fi: int, mi: int, ci: int, fails) -> bool:
    """Whether fault injection (``fails``, :func:`parse_fail_chunks`) names this chunk (F:
    every point of that frequency)."""
    return (f_key(study.points[fi].f), study.families[mi].name, ci) in fails


class KernelMismatch(RuntimeError):
    """This worker's kernel (bbb sources, numba, numpy) is not the one that made the store."""


def _check_kernel(store: StudyStore) -> None:
    # The client checked the store against its own kernel; a worker of a remote cluster may
    # run another installation of bbb.  Checked before anything is written.
    from bbb.provenance import kernel_identity

    attrs, mine = store.attrs(), kernel_identity()
    for key in KERNEL_ATTRS:
        if attrs.get(key) != mine[key]:
            raise KernelMismatch(f"worker {socket.gethostname()} runs another kernel ({key}: "
                                 f"worker {mine[key]}, store {attrs.get(key)}); allowed: workers "
                                 "with the same bbb, numba and numpy as the store's")


def warm_numba(study: Study) -> float:
    """Compile (or load from numba's on-disk cache) everything a task runs; returns seconds.

    One tiny simulate call per family with the study's observables, at one point of each
    kernel variant the points use (contact model, level floor or conveyor, floor shape), so that no task
    compiles and no two processes write the same cache entry at once (numba issue #4807).
    """
    import numpy as np

    from bbb.simulate import simulate

    t0 = time.perf_counter()
    on = selected(study)
    asks_times = any(o.sample_times(study, p.f) is not None for o in on for p in study.points[:1])
    records = any(o.rows(study) for o in on)
    t = min(0.05, study.accuracy.t_max)
    variants = {}
    for p in study.points:
        variants.setdefault((p.params.contact, p.params.transport, p.params.floor), p)
    for point in variants.values():
        for fam in study.families:
            simulate(point.params, 2, t, 0,
                     sample_times=np.array([0.0, t]) if asks_times else None,
                     record_collisions=2 if records else 0, record_from=0.0,
                     numerics=study.accuracy.numerics(), **fam.simulate_kwargs())
    return time.perf_counter() - t0
