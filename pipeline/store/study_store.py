"""The Zarr v3 store of one study: opening, resume checks, growth along points,
chunk-aligned writes and done-markers.  Which arrays it holds is :mod:`pipeline.store.layout`;
its root attributes and fingerprint, :mod:`pipeline.store.attrs`; how a read knows a chunk is
the one written, :mod:`pipeline.store.integrity`.

One Dask task computes one (point, family, chunk) -- a point is a frequency without a grid --
and writes exactly one chunk of every data array, whole (it never decodes what a chunk file
held before), then the chunk's ``digest`` (the CRC-32C of each array's values), then ``done``.
With Zarr v3's ``write_empty_chunks=False`` a chunk's presence proves nothing (an all-NaN or
all-zero chunk is never written); the digest is what tells a deleted chunk from an empty one.
Every read of a done chunk is checked against it: a damaged chunk raises
:class:`StoreDamaged` naming it, and ``bbb run`` recomputes it.  Opening the store with a
workflow of another fingerprint, or with another kernel, is refused; a grid store is
opened by any workflow of the same axes and settings, and grows by the points it lacks
(:meth:`StudyStore.add_points`), never rewriting a done chunk.

Root attributes are netCDF-safe (``xr.open_zarr(store).to_netcdf(...)`` works): flat strings
and numbers; the nested ones (:data:`JSON_ATTRS`) are JSON strings, decoded by
:func:`read_attrs`.

Size: over 400 lines while opening, resume checks and the checked reads of one store stay
together; the damage records themselves live in :mod:`pipeline.store.integrity` and the
metadata checks in :mod:`pipeline.store.metadata`.
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import zarr

from bbb.provenance import kernel_identity
from bbb.record import COLLISION_FIELDS

from ..workflow.identity import SEEDING  # noqa: F401  (importable from here, as before)
from ..workflow.observables.counters import COUNTERS  # noqa: F401  (importable from here)
from ..workflow.observables.registry import growing_dims, selected
from ..workflow.study import Study
from .attrs import (  # importable from here as before the split
    JSON_ATTRS,
    KERNEL_ATTRS,
    LAYOUT_VERSION,
    OLDER_LAYOUTS,
    fingerprint_difference,
    json_attr,
    jsonable,
    package_version,
    read_attrs,
    root_attrs,
    store_fingerprint,
)
from .integrity import Damage, checked_arrays, read_checked, read_markers, scan
from .layout import (  # importable from here as before the split
    DIGEST_NONE,
    chunk_digest,
    create_layout,
)
from .metadata import MetadataReport, inspect_metadata

__all__ = ["StoreError", "StoreNotFound", "StoreDamaged", "missing_store", "MetadataDamaged",
           "check_metadata", "StudyStore",
           "normalize_path", "COLLISION_FIELDS", "LAYOUT_VERSION",
           "package_version", "read_attrs", "store_fingerprint", "JSON_ATTRS", "KERNEL_ATTRS",
           # of pipeline.store.layout and the counters observable, importable from here too
           "COUNTERS", "create_layout"]

class StoreError(ValueError):
    """A store that cannot be used as asked (wrong workflow, not a bbb store, unwritable)."""


class StoreNotFound(StoreError, FileNotFoundError):
    """No store at the path: a FileNotFoundError (what Python says of a missing file) and a
    StoreError (what the command line reports in one line)."""


def missing_store(path: str, given: str | os.PathLike | None = None) -> StoreError:
    """The error for a path where no store is: a scene (a TOML file, or a shipped scene's
    name) given where a store was asked for says so and names the scene's store; anything
    else is :class:`StoreNotFound`.  ``given``: the path as the caller wrote it."""
    given = os.fspath(given if given is not None else path)
    store = _scene_store(path, given)
    if store is not None:
        return StoreError(f"{given}: a scene, not a store; allowed: a store made by `bbb run` "
                          f"(`bbb run {given}` writes {store})")
    return StoreNotFound(f"{path}: no such store; allowed: a store made by `bbb run`")


def _scene_store(path: str, given: str) -> str | None:
    """The default store of the scene at ``path`` (a TOML file) or named ``given`` (a shipped
    scene), e.g. ``runs/smoke.zarr``; None if it is neither."""
    import tomllib

    from ..workflow.scenes import scene_names, scene_path

    if is_local(path) and os.path.isfile(path):
        try:
            with open(path, "rb") as fh:
                doc = tomllib.load(fh)
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            return None
        if not isinstance(doc, dict) or not {"frequencies", "observables"} & set(doc):
            return None
        stem = os.path.basename(path).removesuffix(".toml")
    elif not os.path.exists(path) and given in scene_names():
        doc, stem = tomllib.loads(scene_path(given).read_text(encoding="utf-8")), given
    else:
        return None
    study = doc.get("study")
    name = study.get("name") if isinstance(study, dict) else None
    return f"runs/{name if isinstance(name, str) else stem}.zarr"


class MetadataDamaged(StoreError):
    """A store whose metadata files (a ``zarr.json``) are damaged: the message names the first
    (and how many more), says whether the chunks are there, and how to rebuild them.
    ``report``: what :func:`pipeline.store.metadata.inspect_metadata` found."""

    def __init__(self, path: str, report: MetadataReport):
        self.path, self.report = path, report
        first, more = report.damaged[0], report.damaged[1:]
        also = (f" (and {len(more)} more: {', '.join(d.file for d in more[:3])}"
                + (", ..." if len(more) > 3 else "") + ")") if more else ""
        super().__init__(
            f"{path.rstrip('/')}/{first.file}: {first.what}{also}; the store's metadata are "
            f"damaged, its chunks untouched: `bbb run WORKFLOW --store {path}`, with the "
            "workflow that made the store, rebuilds the metadata from it and keeps every "
            "chunk (or says why it cannot)")


def check_metadata(path: str) -> None:
    """Raise :class:`MetadataDamaged` if a metadata file of the store at ``path`` is damaged
    (nothing if there is no store there, or one whose layout was never finished)."""
    report = inspect_metadata(path)
    if report is None or not report.damaged:
        return
    if report.root_damaged and not report.arrays and report.damaged[0].what == "missing":
        return  # a folder without a single sound zarr.json: not a store (said by the caller)
    if report.root is not None and report.root.get("attributes", {}).get("bbb_creating"):
        return  # the layout's creation was interrupted: no data yet, `bbb run` lays it out anew
    raise MetadataDamaged(path, report)


class StoreDamaged(StoreError):
    """A done chunk whose bytes are not those its task wrote (deleted, cut, altered, or its
    done-marker unreadable).  ``array``: the array read (``done`` for a marker); ``point``:
    the point as a person reads it (``f = 60 Hz, alpha = 0.5``); ``family``; ``chunk``: the
    chunk's index; ``more``: how many other damaged chunks the same read met.  The message
    says how to repair: ``bbb run`` recomputes exactly the damaged chunks."""

    def __init__(self, path: str, array: str, point: str, family: str, chunk: int, why: str,
                 more: int = 0):
        self.path, self.array, self.point, self.family, self.chunk = path, array, point, family, chunk
        self.why, self.more = why, more
        others = f" (and {more} more damaged chunks)" if more else ""
        super().__init__(f"{path}: {array}[{point}, family {family}, chunk {chunk}] is damaged: "
                         f"{why}{others}; run `bbb run` with its workflow on this store to "
                         "recompute the damaged chunks (`bbb verify` lists them)")


def normalize_path(path: str | os.PathLike) -> str:
    """A store path as used everywhere: ``file://`` URLs become plain local paths, and local
    paths absolute (workers may run in another directory); other URLs are kept."""
    path = os.fspath(path)
    if path.startswith("file://"):
        path = path.removeprefix("file://")
    return path if "://" in path else os.path.abspath(path)


def is_local(path: str) -> bool:
    """Whether a store path is on the local filesystem (no ``scheme://``)."""
    return "://" not in path


@dataclass(frozen=True)
class StudyStore:
    """A handle on one study's store: its path (local or fsspec URL) and its Study."""

    path: str
    study: Study

    # -- opening ---------------------------------------------------------------------------
    @classmethod
    def create_or_open(cls, path: str | os.PathLike, study: Study) -> StudyStore:
        """Create the whole layout, or reopen an existing store made by the same workflow (a
        grid store also by a workflow of the same grid axes with other values: its new points
        are added, :meth:`add_points`)."""
        path = normalize_path(path)
        existing = _open_group(path, eager=True)
        if existing is not None:
            attrs = read_attrs(existing)
            if "fingerprint" not in attrs:
                if attrs.get("bbb_creating"):  # layout creation was interrupted: no data yet
                    return cls._create(path, study, overwrite=True)
                raise StoreError(f"{path}: exists and is not a bbb study store; "
                                 "allowed: a new path or a store made by the same workflow")
            _check_layout_version(path, attrs)
            kernel = kernel_identity()
            for key in KERNEL_ATTRS:
                if attrs.get(key) != kernel[key]:
                    raise StoreError(f"{path}: made by another kernel ({key}: store "
                                     f"{attrs.get(key)}, this bbb {kernel[key]}); resuming would "
                                     "mix chunks of two kernels; allowed: a store made by this "
                                     "kernel, or another --store (the store is left unchanged)")
            if attrs.get("workflow_fingerprint") != study.fingerprint():
                old = Study.from_dict(attrs["workflow"])
                raise StoreError(f"{path}: made by a different workflow "
                                 f"({fingerprint_difference(old, study)}); "
                                 "allowed: the same workflow, or another --store")
            if attrs["fingerprint"] != store_fingerprint(study.fingerprint(), kernel):
                raise StoreError(f"{path}: its fingerprint does not match its own workflow and "
                                 "kernel attributes (altered?); run `bbb verify` on it")
            stored = Study.from_dict(attrs["workflow"])
            if stored.refined:  # frequencies an earlier run added by refinement
                study = study.with_refined(stored.refined)
            if study.grid:  # the store's points first, in its order; then the workflow's new
                study = study.with_stored_points(tuple((p.f, p.grid) for p in stored.points))
                if len(study.points) > len(stored.points):
                    return cls(path, stored.with_stored_points(study.stored_points)
                               ).add_points(study)
            store = cls(path, study)
            store._update_reduce_settings(existing, study)
            return store
        if is_local(path) and os.path.exists(path):
            raise StoreError(f"{path}: exists and is not a Zarr store; allowed: a new path or a "
                             "store made by the same workflow")
        return cls._create(path, study, overwrite=False)

    @classmethod
    def open(cls, path: str | os.PathLike) -> StudyStore:
        """Open an existing store read-only, with the Study it was made by.  No store at
        ``path``: :class:`StoreNotFound` (a FileNotFoundError), or a StoreError saying that a
        scene was given (a TOML file, a shipped scene's name) where a store is asked for."""
        given, path = path, normalize_path(path)
        if is_local(path) and os.path.isfile(path):
            raise missing_store(path, given)
        g = _open_group(path, eager=True)
        if g is None:
            raise missing_store(path, given)
        attrs = read_attrs(g)
        if "fingerprint" not in attrs:
            raise StoreError(f"{path}: not a (complete) bbb study store")
        _check_layout_version(path, attrs)
        return cls(path, Study.from_dict(attrs["workflow"], text=attrs.get("workflow_toml", "")))

    @classmethod
    def _create(cls, path: str, study: Study, overwrite: bool) -> StudyStore:
        _ = study.points  # every point's Params first: one bbb.Params refuses leaves no store
        try:
            g = zarr.open_group(path, mode="w" if overwrite else "w-",
                                attributes={"bbb_creating": True})
            create_layout(g, study)
            # The fingerprint goes last: a store without it was never completely laid out.
            g.attrs.update(root_attrs(study))
            del g.attrs["bbb_creating"]
        except (OSError, zarr.errors.ContainsGroupError, zarr.errors.ContainsArrayError) as e:
            raise StoreError(f"{path}: cannot create the store ({e}); "
                             "allowed: a writable, new path") from None
        return cls(path, study)

    def _update_reduce_settings(self, g: zarr.Group, study: Study) -> None:
        # Same data, possibly new reduce settings (analysis, bootstrap resamples, name): the
        # stored numbers stay valid, so the workflow recorded for `bbb reduce` is updated.
        if read_attrs(g).get("workflow") != jsonable(study.to_dict()):
            g = zarr.open_group(self.path, mode="r+")
            g.attrs.update({"workflow": json_attr(study.to_dict()), "workflow_toml": study.text})

    # -- reading ---------------------------------------------------------------------------
    def group(self, mode: str = "r") -> zarr.Group:
        return zarr.open_group(self.path, mode=mode)

    def attrs(self) -> dict[str, Any]:
        """The root attributes, JSON strings (:data:`JSON_ATTRS`) decoded."""
        return read_attrs(self.group())

    def done(self) -> np.ndarray:
        """bool (point, family, chunk): chunks whose data are completely written (the point
        index is the frequency index without a grid).  Raises StoreDamaged naming an
        unreadable done-marker."""
        done, damage = read_markers(self.group())
        if damage:
            raise self.damaged(damage)
        return done

    def chunk_particles(self, chunk: int) -> slice:
        c = self.study.accuracy.chunk_size
        return slice(chunk * c, (chunk + 1) * c)

    @cached_property
    def checked(self) -> tuple[str, ...]:
        """The data arrays whose chunks carry a digest (the ``array`` coordinate)."""
        return checked_arrays(self.group())

    def read_done(self, name: str, fi: int, mi: int, done_fm: np.ndarray | None = None
                  ) -> np.ndarray:
        """Array ``name`` at (frequency index fi, family index mi) for the particles of the
        done chunks only, in particle order: shape (particles of done chunks, ...); an array
        along ``chunk`` (``chunk_seconds``): one value per done chunk.

        Chunks not marked done are never read, so a half-written or damaged chunk of an
        interrupted run cannot break a reduction.  Each done chunk is checked as it is read
        (its file's CRC-32C, its values' digest): a damaged one raises StoreDamaged naming it.
        """
        g = self.group()
        if done_fm is None:
            done_fm = self.done()[fi, mi]
        # One read per run of consecutive done chunks (an adaptive store's done chunks are one
        # run, its first n): Zarr then fetches the run's chunks at once, where one read per
        # chunk made `bbb reduce` spend half its time in per-call overhead.
        parts, damage = read_checked(g, name, fi, mi, np.flatnonzero(done_fm),
                                     self.study.accuracy.chunk_size, self.checked,
                                     self._digests)
        if damage:
            raise self.damaged(damage)
        if parts:
            return np.concatenate(parts) if len(parts) > 1 else parts[0]
        arr = g[name]
        return np.zeros((0, *arr.shape[3:]), dtype=arr.dtype)

    @cached_property
    def _digests(self) -> dict:
        """Digests of the done chunks read so far (:func:`read_checked`'s cache); a done
        chunk's digest never changes (a repair rewrites the same)."""
        return {}

    def __getstate__(self) -> dict:
        # sent to every Dask task: without the digests this process has read
        return {k: v for k, v in self.__dict__.items() if k != "_digests"}

    def damage(self) -> list[Damage]:
        """Every damaged chunk of the store: unreadable done-markers, and each done chunk of
        each data array whose bytes or values are not those written (reads the whole
        store's done data)."""
        g = self.group()
        done, damage = read_markers(g)
        return damage + scan(g, done, self.study.accuracy.chunk_size)

    def damaged(self, damage: list[Damage]) -> StoreDamaged:
        """The error naming the first of ``damage`` (and how many chunks more)."""
        d = damage[0]
        n = len({(x.fi, x.mi, x.ci) for x in damage})
        return StoreDamaged(self.path, d.array, self.study.points[d.fi].label(),
                            self.study.families[d.mi].name, d.ci, d.why, n - 1)

    # -- writing ---------------------------------------------------------------------------
    def write_chunk(self, fi: int, mi: int, ci: int, values: dict[str, np.ndarray],
                    seconds: float, mark_done: bool = True) -> None:
        """Write one task's results into its own chunk of every data array, then its digest,
        then mark it done.  Indices: fi point, mi family, ci chunk; values: {array name: values
        of the chunk's particles} (what the observables computed,
        :func:`pipeline.workflow.observables.registry.chunk_values`; a shorter leading axis
        fills the chunk's first particles, an absent array is fill); seconds: its simulation
        time.

        Idempotent: Dask may run a task twice, and a rerun writes the same bytes.  Every data
        array's chunk is written whole (fill where the task has no value), so a damaged chunk
        file is overwritten, never decoded.
        mark_done=False leaves a written chunk unfinished (fault injection in tests).
        """
        g = self.group("r+")
        sl = self.chunk_particles(ci)
        growing = growing_dims()
        digests = np.full(len(self.checked), DIGEST_NONE, dtype=np.int64)
        for k, name in enumerate(self.checked):
            arr = g[name]
            block = np.full((sl.stop - sl.start, *arr.shape[3:]), arr.fill_value, dtype=arr.dtype)
            a = values.get(name)
            if a is not None:
                a = np.asarray(a)
                block[(slice(0, a.shape[0]), *(slice(0, n) for n in a.shape[1:]))] = a
            arr[fi, mi, sl] = block
            digests[k] = chunk_digest(block, arr.fill_value, bool(growing & set(_dims(arr))))
        g["digest"][fi, mi, ci] = digests
        g["chunk_seconds"][fi, mi, ci] = seconds
        # Only now, after every data array and its digest: the chunk is complete.
        if mark_done:
            g["done"][fi, mi, ci] = True

    def write_stop(self, fi: int, mi: int, n_chunks: int, reason: int) -> None:
        """Record that (frequency fi, family mi) stopped after ``n_chunks`` chunks, and why
        (pipeline.store.layout.STOP_LEGEND).  The reason goes last: it marks the record final."""
        g = self.group("r+")
        g["n_chunks_used"][fi, mi] = n_chunks
        g["stop_reason"][fi, mi] = reason

    def stops(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(n_chunks_used, stop_reason), each (frequency, family), of a target_ci store."""
        g = self.group()
        if "stop_reason" not in g:
            return None
        return (np.asarray(g["n_chunks_used"][...]), np.asarray(g["stop_reason"][...]))

    def add_points(self, study: Study) -> StudyStore:
        """Grow a grid store along its points to those of ``study`` (the store's points
        first, in store order, then new ones); returns the handle on the grown store.  As
        :meth:`add_frequencies`: arrays resized, coordinates written, the stored workflow
        (whose point list is the store's truth) updated last, nothing done rewritten."""
        old, P = len(self.study.points), len(study.points)
        new = study.points[old:]
        if [p.key for p in study.points[:old]] != [p.key for p in self.study.points]:
            raise StoreError(f"{self.path}: cannot grow: the new points do not follow the "
                             "store's own")
        g = self.group("r+")
        # the observables' trailing axes that grow with the points (a higher frequency has
        # more floor periods in t_max), as the grown study lays them out
        grown = {a.name: dict(a.trailing) for o in selected(study) for a in o.arrays(study)}
        coords = {c.name: c for o in selected(study) for c in o.coords(study)}
        growing = growing_dims()
        for name, arr in g.arrays():
            dims = arr.metadata.dimension_names
            if not dims:
                continue
            shape = list(arr.shape)
            if dims[0] == "point":
                shape[0] = P
            for i, d in enumerate(dims):
                if d in growing and name in grown:
                    shape[i] = max(shape[i], grown[name][d])
                elif d in growing and name == d:
                    shape[i] = max(shape[i], len(coords[d].values))
            if tuple(shape) != arr.shape:
                arr.resize(tuple(shape))
        g = zarr.open_group(self.path, mode="r+", use_consolidated=False)  # the new shapes
        for d in growing & set(coords):
            if d in g:
                g[d][:] = np.asarray(coords[d].values)[: g[d].shape[0]]
        g["point"][old:] = np.arange(old, P)
        g["frequency"][old:] = np.asarray([p.f for p in new], dtype=np.float64)
        for a, _ in study.grid:
            values = [dict(p.grid)[a] for p in new]
            g[a][old:] = np.asarray(values, dtype=None if isinstance(values[0], str) else np.float64)
        g.attrs.update({"workflow": json_attr(study.to_dict()), "workflow_toml": study.text})
        grown = StudyStore(self.path, study)
        grown.consolidate()
        return grown

    def add_frequencies(self, new: tuple[float, ...]) -> StudyStore:
        """Grow the store along the frequency axis by ``new`` (Hz, refined frequencies);
        returns the handle on the grown store.  Arrays are resized (Zarr writes no chunk for
        the new, empty rows), the coordinates extended, and the stored workflow updated last,
        so an interruption leaves a store that a re-run grows the same way again."""
        study = self.study.with_refined(self.study.refined + tuple(new))
        F = len(study.frequencies)
        g = self.group("r+")
        for _, arr in g.arrays():
            dims = arr.metadata.dimension_names
            if dims and dims[0] == "frequency" and arr.shape[0] != F:
                arr.resize((F, *arr.shape[1:]))
        old = len(self.study.frequencies)
        g = zarr.open_group(self.path, mode="r+", use_consolidated=False)  # the new shapes
        g["frequency"][old:] = np.asarray(study.frequencies[old:], dtype=np.float64)
        g["refined"][old:] = True
        g.attrs.update({"workflow": json_attr(study.to_dict())})
        grown = StudyStore(self.path, study)
        grown.consolidate()
        return grown

    def consolidate(self) -> None:
        with warnings.catch_warnings():  # consolidated metadata is not yet in the v3 spec
            warnings.simplefilter("ignore")
            zarr.consolidate_metadata(self.path)


def _dims(arr: zarr.Array) -> tuple[str, ...]:
    return tuple(arr.metadata.dimension_names or ())


def _check_layout_version(path: str, attrs: dict[str, Any]) -> None:
    layout = attrs.get("bbb_store_layout")
    if layout != LAYOUT_VERSION:
        why = f" ({OLDER_LAYOUTS[layout]})" if layout in OLDER_LAYOUTS else ""
        raise StoreError(f"{path}: store layout {layout!r} of an older bbb{why}; "
                         f"allowed: layout {LAYOUT_VERSION} (delete it or use another --store)")


def _open_group(path: str, eager: bool = False) -> zarr.Group | None:
    """The store's root group, None if there is none.  A damaged metadata file raises
    MetadataDamaged naming it: looked for first if ``eager`` and the store is local (a few kB
    read), else when Zarr cannot open the group (a URL: each file is a request)."""
    if eager and is_local(path):
        check_metadata(path)
    try:
        return zarr.open_group(path, mode="r")
    except (FileNotFoundError, zarr.errors.GroupNotFoundError, zarr.errors.NodeTypeValidationError):
        check_metadata(path)  # a root zarr.json deleted while the arrays remain
        return None
    except Exception as e:  # e.g. an unreadable file where the store should be
        check_metadata(path)
        raise StoreError(f"{path}: cannot open ({type(e).__name__}: {e})") from None

