"""The identity of a point and every seed derived from it, defined once.

A point of a study is its floor frequency f, Hz, and, in a scene with a ``[grid]``, one value of
each grid axis; its identity is :func:`point_key`, which without a grid is :func:`f_key`, f as an
integer number of mHz (workflows accept only multiples of 1 mHz, pipeline.workflow.load).  The
seeds below are keyed by f alone, never by a grid value: the points of a grid line that differ
only in a parameter share their chunks' random numbers (common random numbers, a paired design).  Every random
number of the pipeline comes from a :class:`numpy.random.SeedSequence` whose entropy is the
workflow's ``seed`` and whose ``spawn_key`` is built from values only -- the point's key, the
family's key (crc32 of its name, :func:`family_key`), a chunk index or the crc32 of a label
(:func:`label_key`) -- so a result never depends on worker count, task order, or which other
frequencies and families a workflow holds:

======================  ===================================================  ===============
seed                    spawn_key                                            used by
======================  ===================================================  ===============
:func:`chunk_seed`      (f_key, family_key, chunk)                           task, pilot
:func:`pilot_seed`      (f_key, family_key, PILOT_CHUNK = 2**31)             pilot
:func:`stop_seed`       (f_key, family_key, crc32("stop"), n chunks)         waves
:func:`reduce_seed`     (f_key, crc32("reduce"))                             reduce, waves
:func:`mechanisms_seed` (f_key, crc32("mechanisms"))                         mechanisms
:func:`table_seed`      (f_key, family_key, crc32(label))                    contact, locking
:func:`child_seed`      (*parent's spawn_key, crc32(label)), parent entropy  reduce
======================  ===================================================  ===============

These are the seeds of every committed table and store: changing any of them changes the
numbers (tests/pipeline/workflow/test_identity.py pins them to the expressions they replaced).
"""

from __future__ import annotations

import zlib
from typing import Any, Protocol

import numpy as np

__all__ = ["f_key", "f_keys", "point_key", "family_key", "label_key", "chunk_seed", "pilot_seed", "stop_seed",
           "reduce_seed", "mechanisms_seed", "table_seed", "child_seed", "PILOT_CHUNK", "SEEDING"]

#: the pilot's chunk index: above every chunk a store can hold, so the pilot's particles are
#: never a run's
PILOT_CHUNK = 2**31
#: how a chunk's seed is made, recorded in every store's attributes (pipeline.store.study_store, verify):
#: this exact text, so that stores written before this module keep their attributes
SEEDING = ("SeedSequence(workflow seed, spawn_key=(round(f * 1000), "
           "zlib.crc32(family name), chunk index))")


class _Named(Protocol):
    name: str


class _Seeded(Protocol):
    seed: int


def f_key(f: Any) -> int:
    """The integer key of a frequency f (Hz, or any value in Hz such as a grid step): f in mHz,
    rounded half to even (Python's ``round``)."""
    return int(round(f * 1000))


def point_key(f: Any, grid: Any = ()) -> int | tuple:
    """The key of a point: its frequency f (Hz) and its grid values ``grid``, (axis, value)
    pairs in the study's axis order (or a mapping in that order).  Without grid values it is
    :func:`f_key` (today's key of a frequency, so every store made before grids keeps its
    keys); with them, the tuple ``(f_key(f), (axis, value), ...)``, values as the workflow
    resolved them (floats, or a contact model's name)."""
    pairs = tuple(grid.items()) if hasattr(grid, "items") else tuple(tuple(p) for p in grid)
    if not pairs:
        return f_key(f)
    return (f_key(f), *((str(a), v) for a, v in pairs))


def f_keys(f: Any) -> np.ndarray:
    """:func:`f_key` of each of an array of frequencies (Hz), int64 mHz (``np.rint`` rounds half
    to even too)."""
    return np.rint(np.asarray(f, dtype=np.float64) * 1000).astype(np.int64)


def family_key(family: str | _Named) -> int:
    """The integer key of an initial-condition family (its name, or anything with ``.name``):
    crc32 of the UTF-8 name."""
    name = family if isinstance(family, str) else family.name
    return zlib.crc32(name.encode("utf-8"))


def label_key(label: str) -> int:
    """The integer key of a label that sets a derived seed apart ("reduce", "stop", ...):
    crc32 of its UTF-8 text."""
    return zlib.crc32(label.encode("utf-8"))


def _entropy(study: int | _Seeded) -> int:
    return study if isinstance(study, (int, np.integer)) else study.seed


def chunk_seed(study: int | _Seeded, f: float, family: str | _Named, chunk: int
               ) -> np.random.SeedSequence:
    """The seed of one chunk of particles at frequency f (Hz) of ``family``; ``study`` is a
    :class:`pipeline.workflow.study.Study` or its workflow seed."""
    return np.random.SeedSequence(_entropy(study), spawn_key=(f_key(f), family_key(family), chunk))


def pilot_seed(study: int | _Seeded, f: float, family: str | _Named) -> np.random.SeedSequence:
    """The seed of the pilot's particles at (f Hz, family): a chunk index no run reaches."""
    return chunk_seed(study, f, family, PILOT_CHUNK)


def stop_seed(study: int | _Seeded, f: float, family: str | _Named, n: int
              ) -> np.random.SeedSequence:
    """The bootstrap seed of D's CI at (f Hz, family) from its first n chunks (the stopping
    decision after them, and the table's CI when the family ends there)."""
    return np.random.SeedSequence(_entropy(study), spawn_key=(
        f_key(f), family_key(family), label_key("stop"), n))


def reduce_seed(study: int | _Seeded, f: float) -> np.random.SeedSequence:
    """The seed of the D(f) table's row at f (Hz): its pooled CI, and the parent of the row's
    :func:`child_seed` s ("stationarity", "transport")."""
    return np.random.SeedSequence(_entropy(study), spawn_key=(f_key(f), label_key("reduce")))


def mechanisms_seed(study: int | _Seeded, f: float) -> np.random.SeedSequence:
    """The seed of the mechanisms table's row at f (Hz) (pipeline.tables.mechanisms draws its numbers
    from its ``generate_state``)."""
    return np.random.SeedSequence(_entropy(study), spawn_key=(f_key(f), label_key("mechanisms")))


def table_seed(study: int | _Seeded, f: float, family: str | _Named, label: str
               ) -> np.random.SeedSequence:
    """The seed of one bootstrap of a per-(f Hz, family) table: ``label`` names the column
    (the contact table's "held_frac", ...) or the table ("locking")."""
    return np.random.SeedSequence(_entropy(study), spawn_key=(
        f_key(f), family_key(family), label_key(label)))


def child_seed(parent: np.random.SeedSequence, label: str) -> np.random.SeedSequence:
    """A seed set apart from ``parent`` by ``label`` (its entropy, its spawn_key extended by
    crc32(label)): the D(f) row's "stationarity" and "transport" bootstraps."""
    return np.random.SeedSequence(parent.entropy, spawn_key=(*parent.spawn_key, label_key(label)))
