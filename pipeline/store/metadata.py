"""A store's metadata files: which ``zarr.json`` is damaged, and the layout a workflow makes,
held in memory, to rebuild them from.

A study store is one Zarr v3 group: the root ``zarr.json`` (the group, its attributes -- the
workflow, the fingerprint, the kernel -- and the consolidated copy of every array's metadata)
and one folder per array, holding the array's own ``zarr.json`` and its chunk files under
``c/``.  :func:`inspect_metadata` reads every one of these ``zarr.json`` files (the root and one
per folder; a few kB each) and names each that is missing, not JSON, or not the Zarr node it
should be; the chunks are not read.  Every command that opens a store looks first
(:class:`pipeline.store.study_store.MetadataDamaged`), so a damaged file is named, not met as a
decoding error deep inside Zarr.

:func:`expected_files` is what ``create_layout`` writes for a workflow -- each array's
``zarr.json`` and the coordinates' chunks -- as bytes, and :func:`staged_array` reads chunk
files of the store on disk through those metadata, without writing anything: what
``bbb run`` needs to check that a damaged store's chunks are the workflow's before it rewrites
the damaged files (:mod:`pipeline.execute.repair`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import zarr
from zarr.core.buffer import cpu
from zarr.storage import MemoryStore

from ..workflow.study import Study
from .layout import create_layout

__all__ = ["Damage", "MetadataReport", "inspect_metadata", "expected_files", "staged_array", "memory_array",
           "decisive_difference", "values_equal", "DECISIVE", "store_fs"]

#: the keys of an array's zarr.json that decide where its chunks are and how they decode
DECISIVE = ("shape", "data_type", "chunk_grid", "chunk_key_encoding", "fill_value", "codecs",
            "dimension_names")


@dataclass(frozen=True)
class Damage:
    """One damaged metadata file: ``file`` relative to the store (``zarr.json``,
    ``done/zarr.json``), ``what`` is wrong with it."""

    file: str
    what: str


@dataclass
class MetadataReport:
    """What :func:`inspect_metadata` found: the damaged files, the root's document if it is
    sound, and the sound arrays' documents ({name: zarr.json as a dict})."""

    damaged: list[Damage] = field(default_factory=list)
    root: dict[str, Any] | None = None
    arrays: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def root_damaged(self) -> bool:
        return self.root is None


def store_fs(path: str):
    """(fsspec filesystem, path on it) of a store path or URL."""
    import fsspec

    return fsspec.core.url_to_fs(path)


def inspect_metadata(path: str) -> MetadataReport | None:
    """Read the root ``zarr.json`` and every array folder's; None if ``path`` is no directory
    (nothing there, or a file: not a store to repair)."""
    fs, root = store_fs(path)
    if not fs.isdir(root):
        return None
    report = MetadataReport()
    doc, what = _read(fs, f"{root}/zarr.json", "group")
    if what is None:
        report.root = doc
    else:
        report.damaged.append(Damage("zarr.json", what))
    for sub in sorted(fs.ls(root, detail=True), key=lambda e: e["name"]):
        if sub["type"] != "directory":
            continue
        name = sub["name"].rstrip("/").rsplit("/", 1)[-1]
        doc, what = _read(fs, f"{root}/{name}/zarr.json", "array")
        if what is None:
            report.arrays[name] = doc
        else:
            report.damaged.append(Damage(f"{name}/zarr.json", what))
    return report


def _read(fs, file: str, node: str) -> tuple[dict | None, str | None]:
    """(document, None) of a sound zarr.json of a Zarr v3 ``node``, else (None, what is wrong)."""
    try:
        raw = fs.cat_file(file)
    except FileNotFoundError:
        return None, "missing"
    except OSError as e:
        return None, f"unreadable ({e.strerror or e})"
    if not raw.strip():
        return None, "empty"
    try:
        doc = json.loads(raw)
    except ValueError as e:
        return None, f"not JSON ({e}; truncated or overwritten?)"
    if not isinstance(doc, dict) or doc.get("zarr_format") != 3 or doc.get("node_type") != node:
        return None, f"not the metadata of a Zarr v3 {node}"
    return doc, None


def expected_files(study: Study) -> dict[str, bytes]:
    """What ``create_layout(study)`` writes, as {key relative to the store: bytes}: the root
    group's ``zarr.json`` (no attributes), every array's, and the coordinates' chunks."""
    d: dict[str, Any] = {}
    create_layout(zarr.open_group(MemoryStore(d), mode="w"), study)
    return {k: v.to_bytes() for k, v in d.items()}


def memory_array(files: dict[str, bytes], name: str) -> zarr.Array:
    """Array ``name`` of ``files`` ({key: bytes}, as :func:`expected_files`), read-only."""
    d = {k: cpu.Buffer.from_bytes(v) for k, v in files.items()
         if k == "zarr.json" or k.startswith(f"{name}/")}
    return zarr.open_array(MemoryStore(d, read_only=True), path=name, mode="r")


def staged_array(expected: dict[str, bytes], path: str, name: str, prefix: str = "") -> zarr.Array:
    """Array ``name`` as the expected metadata describe it, holding the store's chunk files of
    it under ``name/c/`` + ``prefix`` (all of them by default): read-only, in memory; the
    store is only read."""
    fs, root = store_fs(path)
    files = {k: v for k, v in expected.items() if k in ("zarr.json", f"{name}/zarr.json")}
    base = f"{root}/{name}/c/{prefix}".rstrip("/")
    found = [base] if fs.isfile(base) else (fs.find(base) if fs.isdir(base) else [])
    for file, data in (fs.cat(found) if found else {}).items():
        files[file[len(root) + 1:]] = data
    return memory_array(files, name)


def decisive_difference(have: dict, want: dict) -> str | None:
    """The first :data:`DECISIVE` key in which two array documents differ, as text; None."""
    for key in DECISIVE:
        if have.get(key) != want.get(key):
            return f"{key} {json.dumps(have.get(key))}; the workflow's {json.dumps(want.get(key))}"
    return None


def values_equal(a: np.ndarray, b: np.ndarray) -> bool:
    """Same shape and values (NaN equal to NaN)."""
    if a.shape != b.shape:
        return False
    if a.dtype.kind == "f" and b.dtype.kind == "f":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))
