"""Rebuild a store's damaged metadata files from its workflow, keeping every chunk: the first
thing ``bbb run`` does on a store some ``zarr.json`` of which is damaged (truncated,
overwritten, deleted; :func:`pipeline.store.metadata.inspect_metadata` names them).

- An array's own ``zarr.json`` damaged, the root sound: the root's stored workflow says what
  the array is; its ``zarr.json`` is written again as that workflow lays it out (a coordinate
  is written anew whole, values too: its chunking follows the store's history, its values
  the workflow).
- The root ``zarr.json`` damaged: the store's identity (workflow, fingerprint, kernel) is
  gone with it and is taken from the workflow given to ``bbb run``.  Before anything is
  written it is checked that the chunks are that workflow's: every sound array is an array of
  the workflow's layout, with the same shape, chunks (a coordinate's aside), dtype, fill value,
  codecs and dimension names; every sound coordinate (frequencies, families, ...) holds the
  workflow's values; and one done chunk, recomputed here in a temporary store, is
  bit-identical to the stored one (the seeds, the parameters and the kernel are not in the
  layout: only the numbers show them).  What the root held beside the workflow is rebuilt
  from the arrays: the frequencies refinement added (the ``frequency`` and ``refined``
  arrays), a map's points in store order (``point``'s coordinates).  The creation time cannot
  be: ``created`` is the rebuild's time, and ``metadata_rebuilt`` says so.

Either way the arrays' chunks -- data, done markers, stop records -- are never written, so a
re-run then computes only the chunks not done, as after any interruption.  When the store
cannot be rebuilt from the workflow the refusal (StoreError, one line) says why, and what to
do.  The root is written last: an interrupted rebuild leaves it damaged, and the next
``bbb run`` rebuilds again.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import tempfile
from collections.abc import Callable

import numpy as np
import zarr
from zarr.storage import MemoryStore

from ..store.attrs import read_attrs, root_attrs
from ..store.metadata import (
    MetadataReport,
    decisive_difference,
    expected_files,
    memory_array,
    staged_array,
    store_fs,
    values_equal,
)
from ..store.study_store import MetadataDamaged, StoreError, StudyStore, check_metadata
from ..workflow.study import Study

__all__ = ["repair_metadata"]

_DELETE = "allowed: the workflow that made the store, or delete the store (its chunks are lost)"


def repair_metadata(study: Study, path: str, echo: Callable[[str], None] = print) -> bool:
    """Rebuild the damaged metadata files of the store at ``path`` (normalized) from
    ``study``; False if none is damaged.  Raises StoreError saying why it cannot."""
    try:
        check_metadata(path)
    except MetadataDamaged as e:
        report = e.report
    else:
        return False
    damaged = [d.file for d in report.damaged]
    if report.root_damaged:
        here = _study_of_arrays(study, path, report)
    else:  # the store's own workflow says what its arrays are
        attrs = read_attrs(zarr.open_group(path, mode="r", use_consolidated=False))
        if "workflow" not in attrs:
            raise StoreError(f"{path}: its root zarr.json holds no bbb workflow, so the damaged "
                             f"{damaged[0]} cannot be rebuilt; {_DELETE}")
        here = Study.from_dict(attrs["workflow"], text=attrs.get("workflow_toml", ""))
    expected = expected_files(here)
    _check_layout(path, report, expected)
    checked = _check_a_done_chunk(here, path, expected) if report.root_damaged else None
    fs, root = store_fs(path)
    for d in report.damaged:  # the arrays first, the root last: it marks the store complete
        if d.file == "zarr.json":
            continue
        name = d.file.removesuffix("/zarr.json")
        if len(json.loads(expected[d.file])["shape"]) == 1:  # a coordinate: written anew whole
            if fs.exists(f"{root}/{name}/c"):
                fs.rm(f"{root}/{name}/c", recursive=True)
            for key, data in expected.items():
                if key.startswith(f"{name}/c/"):
                    fs.makedirs(f"{root}/{key}".rsplit("/", 1)[0], exist_ok=True)
                    fs.pipe_file(f"{root}/{key}", data)
        fs.pipe_file(f"{root}/{d.file}", expected[d.file])
    if report.root_damaged:
        now = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
        d: dict = {}
        zarr.open_group(MemoryStore(d), mode="w",
                        attributes={**root_attrs(here), "metadata_rebuilt": now})
        fs.pipe_file(f"{root}/zarr.json", d["zarr.json"].to_bytes())
    StudyStore(path, here).consolidate()
    done = staged_array(expected, path, "done")[...]
    what = ("from the workflow" if report.root_damaged else "from the store's own workflow")
    echo(f"{here.name}: rebuilt the damaged metadata of {path} ({', '.join(damaged)}) {what}; "
         f"{int(done.sum())} done chunks kept"
         + (f", {checked} recomputed bit-identical to the stored one" if checked else "")
         + ("; the creation time is lost (created: now, metadata_rebuilt)"
            if report.root_damaged else ""))
    return True


def _study_of_arrays(study: Study, path: str, report: MetadataReport) -> Study:
    """``study`` with what the lost root held beside it, read from the sound arrays: the
    frequencies refinement added, a map's points in store order."""
    def read(name: str) -> np.ndarray:
        if name not in report.arrays:
            raise StoreError(f"{path}: the root zarr.json is damaged and so is {name}/zarr.json "
                             f"(or {name} is gone), which alone records "
                             + ("the frequencies refinement added" if not study.grid
                                else "the map's points in store order")
                             + f"; the metadata cannot be rebuilt from the workflow; {_DELETE}")
        return np.asarray(zarr.open_array(store=path, path=name, mode="r")[...])

    if study.grid:
        f = read("frequency")
        axes = {a: read(a) for a, _ in study.grid}
        points = tuple((float(f[i]), tuple((a, _plain(axes[a][i])) for a, _ in study.grid))
                       for i in range(len(f)))
        here = study.with_stored_points(points)
        if len(here.points) != len(points):
            raise StoreError(f"{path}: the root zarr.json is damaged and the workflow has "
                             f"{len(here.points) - len(points)} points the store lacks; its "
                             "metadata can be rebuilt only by the workflow of exactly the "
                             f"store's {len(points)} points; {_DELETE}")
        return here
    if study.refine is not None:
        f, refined = read("frequency"), read("refined").astype(bool)
        return study.with_refined(tuple(float(x) for x in f[refined]))
    return study


def _plain(v):
    return str(v) if isinstance(v, str | np.str_) else float(v)


def _check_layout(path: str, report: MetadataReport, expected: dict[str, bytes]) -> None:
    """Every sound array is one of the workflow's layout, laid out alike, and its coordinates
    hold the workflow's values; every array of the layout is there (damaged or sound)."""
    names = {k.removesuffix("/zarr.json") for k in expected if k.endswith("/zarr.json")}
    there = set(report.arrays) | {d.file.removesuffix("/zarr.json") for d in report.damaged}
    for name in sorted(set(report.arrays) - names):
        raise StoreError(f"{path}/{name}: not an array of this workflow's layout; the "
                         f"metadata cannot be rebuilt from it; {_DELETE}")
    for name in sorted(names - there):
        raise StoreError(f"{path}/{name}: gone (the array, not only its metadata); the store "
                         f"cannot be rebuilt; {_DELETE}")
    for name, doc in sorted(report.arrays.items()):
        want = json.loads(expected[f"{name}/zarr.json"])
        if len(want["shape"]) == 1:  # a coordinate's chunks follow the store's history (a
            want = {**want, "chunk_grid": doc.get("chunk_grid")}  # grown map): values decide
        diff = decisive_difference(doc, want)
        if diff:
            raise StoreError(f"{path}/{name}/zarr.json: {diff}: not this workflow's store; "
                             f"{_DELETE}")
        if len(want["shape"]) == 1:  # a coordinate: the workflow's values
            have = np.asarray(zarr.open_array(store=path, path=name, mode="r")[...])
            if not values_equal(have, np.asarray(memory_array(expected, name)[...])):
                raise StoreError(f"{path}/{name}: values differ from the workflow's: not this "
                                 f"workflow's store; {_DELETE}")


def _check_a_done_chunk(study: Study, path: str, expected: dict[str, bytes]) -> str | None:
    """Recompute the first done chunk in a temporary store and compare it, bit for bit, with
    the stored one in every per-particle array; its label, or None if no chunk is done."""
    from .task import compute_chunk

    done = np.asarray(staged_array(expected, path, "done")[...], dtype=bool)
    if not done.any():
        return None
    fi, mi, ci = (int(i[0]) for i in np.nonzero(done))
    label = (f"chunk {ci} of {study.points[fi].label()}, family {study.families[mi].name}")
    with tempfile.TemporaryDirectory(prefix="bbb-check-") as tmp:
        fresh = StudyStore.create_or_open(os.path.join(tmp, "check.zarr"), study)
        compute_chunk(fresh, fi, mi, ci, point=study.points[fi])
        g = fresh.group()
        rows = fresh.chunk_particles(ci)
        for name, arr in sorted(g.arrays()):
            if list(arr.metadata.dimension_names or ())[1:3] != ["family", "particle"]:
                continue
            stored = np.asarray(staged_array(expected, path, name, f"{fi}/{mi}/{ci}")[fi, mi, rows])
            if stored.tobytes() != np.asarray(arr[fi, mi, rows]).tobytes():
                raise StoreError(
                    f"{path}: {name} of the done {label} is not what the workflow computes "
                    "(recomputed here): the store was made by another workflow (parameters, "
                    "seed) or another kernel, so its root metadata cannot be rebuilt from this "
                    f"workflow; {_DELETE}")
    return label
