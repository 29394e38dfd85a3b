"""Is a done chunk what its task wrote?  The checks of a store's bytes, on every read.

Two layers (:mod:`pipeline.store.layout`): Zarr checks each chunk file's CRC-32C (the
``crc32c`` codec) as it decodes it, and a task records, before its done-marker, the CRC-32C of
the values it wrote into each data array (``digest``).  The first catches a flipped or cut
byte in any array; the second what the first cannot see -- a deleted chunk file (which Zarr
reads back as fill values) and values rewritten through Zarr (which carry a fresh codec CRC).

Functions here return :class:`Damage` records, never raise: :class:`~pipeline.store.study_store.
StudyStore` turns them into :class:`~pipeline.store.study_store.StoreDamaged` on a read,
``bbb verify`` lists them, ``bbb run`` recomputes their chunks.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import zarr

from ..workflow.observables.registry import growing_dims
from .layout import DIGEST_NONE, chunk_digest

__all__ = ["Damage", "read_markers", "read_checked", "scan", "checked_arrays", "runs"]

#: chunks read at once by :func:`scan` (bounds its memory: one run of chunks of one array)
SCAN_BATCH = 32


@dataclass(frozen=True)
class Damage:
    """One damaged chunk: ``array`` (a data array, ``done`` or ``digest``), its indices (point
    fi, family mi, chunk ci) and what is wrong (``why``, for a person)."""

    array: str
    fi: int
    mi: int
    ci: int
    why: str


def checked_arrays(g: zarr.Group) -> tuple[str, ...]:
    """The data arrays whose chunks ``digest`` covers, in its order (its coordinate)."""
    return tuple(str(v) for v in np.asarray(g["array"][...]))


def read_markers(g: zarr.Group) -> tuple[np.ndarray, list[Damage]]:
    """(done as bool (point, family, chunk), damaged markers).  A marker that cannot be
    decoded (an empty, cut or altered ``done`` chunk file) is reported and read as not done."""
    arr = g["done"]
    try:
        return np.asarray(arr[...], dtype=bool), []
    except Exception:  # codec errors differ by cause: find the markers one by one
        pass
    done = np.zeros(arr.shape, dtype=bool)
    damage = []
    for fi, mi, ci in np.ndindex(*arr.shape):
        try:
            done[fi, mi, ci] = bool(arr[fi, mi, ci])
        except Exception as e:
            damage.append(Damage("done", fi, mi, ci, f"done-marker unreadable: {_cause(e)}"))
    return done, damage


def read_checked(g: zarr.Group, name: str, fi: int, mi: int, chunks: np.ndarray, cs: int,
                 checked: tuple[str, ...], cache: dict | None = None
                 ) -> tuple[list[np.ndarray], list[Damage]]:
    """Array ``name`` at (point fi, family mi) for the chunks ``chunks`` (sorted indices,
    ``cs`` particles each; an array along ``chunk``, as ``chunk_seconds``, has one value a
    chunk): (one block per run of consecutive chunks, damaged chunks).  Each chunk of a data
    array (``checked``) is compared with its recorded digest; of another, its bytes only.
    ``cache``: digests read before, by (fi, mi, first chunk, end) of a run (the readers read
    one array after another over the same done chunks: their digests are read once)."""
    arr = g[name]
    k = checked.index(name) if name in checked else None
    if (arr.metadata.dimension_names or ())[2:3] != ("particle",):
        cs = 1
    blocks, damage = [], []
    for c0, c1 in runs(chunks):
        try:  # one read per run: Zarr fetches its chunks at once
            block = np.asarray(arr[fi, mi, c0 * cs: c1 * cs])
        except Exception:
            block = None
        if block is None or k is not None:
            block = _check_run(g, arr, name, k, fi, mi, c0, c1, cs, block, damage,
                               {} if cache is None else cache)
        blocks.append(block)
    return blocks, damage


def _check_run(g, arr, name, k, fi, mi, c0, c1, cs, block, damage: list[Damage],
               cache: dict) -> np.ndarray:
    if k is not None:
        rows = cache.get((fi, mi, c0, c1))
        if rows is None:
            try:
                rows = np.asarray(g["digest"][fi, mi, c0:c1])
                if (rows != DIGEST_NONE).all():  # else a chunk may be done since: read again
                    cache[(fi, mi, c0, c1)] = rows
            except Exception:  # a digest chunk itself damaged: which one?
                rows = None
        want = (rows[:, k] if rows is not None else
                np.array([_digest_of(g, fi, mi, ci, k, damage) for ci in range(c0, c1)]))
    parts = []
    fill = arr.fill_value
    trim = bool(growing_dims() & set(arr.metadata.dimension_names or ()))
    for ci in range(c0, c1):
        if block is not None:
            part = block[(ci - c0) * cs: (ci - c0 + 1) * cs]
        else:
            try:
                part = np.asarray(arr[fi, mi, ci * cs: (ci + 1) * cs])
            except Exception as e:
                damage.append(Damage(name, fi, mi, ci, f"unreadable: {_cause(e)}"))
                part = np.full((cs, *arr.shape[3:]), fill, dtype=arr.dtype)
                parts.append(part)
                continue
        parts.append(part)
        if k is None or want[ci - c0] is None:
            continue
        if int(want[ci - c0]) == DIGEST_NONE:
            damage.append(Damage(name, fi, mi, ci, "marked done but no digest was recorded"))
        elif chunk_digest(part, fill, trim) != int(want[ci - c0]):
            damage.append(Damage(name, fi, mi, ci, "values differ from those its task "
                                 "wrote (recorded digest): a deleted or rewritten chunk"))
    return np.concatenate(parts) if len(parts) > 1 else parts[0]


def _digest_of(g, fi, mi, ci, k, damage: list[Damage]) -> int | None:
    try:
        return int(g["digest"][fi, mi, ci, k])
    except Exception as e:
        if not any(d.array == "digest" and (d.fi, d.mi, d.ci) == (fi, mi, ci) for d in damage):
            damage.append(Damage("digest", fi, mi, ci, f"unreadable: {_cause(e)}"))
        return None


def scan(g: zarr.Group, done: np.ndarray, cs: int) -> list[Damage]:
    """Every damaged chunk among the ``done`` ones (bool (point, family, chunk)): each data
    array of each done chunk read and compared with its digest, and its ``chunk_seconds``
    decoded.  Reads the whole store."""
    checked = checked_arrays(g)
    damage: list[Damage] = []
    for fi, mi in zip(*np.nonzero(done.any(axis=2)), strict=True):
        chunks = np.flatnonzero(done[fi, mi])
        for name in (*checked, "chunk_seconds"):
            for batch in _batches(chunks):
                damage += read_checked(g, name, int(fi), int(mi), batch, cs, checked)[1]
    # a digest chunk damaged is found once per array: keep one line
    return list(dict.fromkeys(damage))


def runs(indices: np.ndarray) -> list[tuple[int, int]]:
    """[start, stop) of each run of consecutive integers in the sorted ``indices``."""
    if indices.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(indices) != 1) + 1
    return [(int(r[0]), int(r[-1]) + 1) for r in np.split(indices, breaks)]


def _batches(chunks: np.ndarray) -> Iterator[np.ndarray]:
    for i in range(0, chunks.size, SCAN_BATCH):
        yield chunks[i: i + SCAN_BATCH]


def _cause(e: Exception) -> str:
    """Why a chunk could not be decoded, for a person: Zarr's crc32c codec says "checksum do
    not match" for any changed byte, an empty or a cut file alike."""
    text = str(e).splitlines()[0] if str(e) else ""
    if "checksum do not match" in text:
        return "its bytes fail their CRC-32C: a flipped, cut, emptied or foreign chunk file"
    return f"cannot be decoded ({type(e).__name__}: {text[:100]})" if text else type(e).__name__
