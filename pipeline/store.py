"""The Zarr v3 store of one study: layout, chunk-aligned writes, done-markers, resume checks.

Layout (``F`` frequencies, ``M`` families, ``N`` particles per (frequency, family) split into
``C = N / chunk_size`` chunks, ``T`` sample times, ``K`` recorded collisions per particle):

=============  ==========================================  ======  ===========================
array          dims                                        dtype   chunks
=============  ==========================================  ======  ===========================
frequency      (frequency,)                 Hz             f8      whole
family         (family,)                    name           str     whole
initial        (family,)                    rest|dropped|..str     whole
particle       (particle,)                  index          i8      whole
chunk          (chunk,)                     index          i8      whole
time           (time,)                      s              f8      whole    [positions]
collision      (collision,)                 index          i8      whole    [collisions]
field          (field,)          bbb.record.COLLISION_FIELDS  str  whole    [collisions]
positions      (frequency, family, particle, time)  x, mm  f8      (1, 1, chunk_size, T)
collisions     (frequency, family, particle, collision, field)  f8  (1, 1, chunk_size, K, n_fields)
n_recorded     (frequency, family, particle)  valid rows   i8      (1, 1, chunk_size) [coll.]
n_<counter>    (frequency, family, particle)  bbb counters  i8  (1, 1, chunk_size)
held_time, sliding_time  (frequency, family, particle)  s  f8  (1, 1, chunk_size)  [contact]
done           (frequency, family, chunk)   bool           b1      (1, 1, 1)
chunk_seconds  (frequency, family, chunk)   simulate, s    f8      (1, 1, 1)   not reproducible
n_chunks_used  (frequency, family)          chunks         i8      (1, 1)      [target_ci]
stop_reason    (frequency, family)          STOP_LEGEND    i1      (1, 1)      [target_ci]
refined        (frequency,)                 added by refine b1     like frequency  [refine]
=============  ==========================================  ======  ===========================

With ``target_ci`` the chunk axis is sized by the cap (max_particles); a (frequency, family)
uses the first ``n_chunks_used`` chunks, and ``stop_reason`` says why it stopped
(:data:`pipeline.adaptive.STOP_LEGEND`, also the array's ``legend`` attribute; 0 = not decided
yet).  With ``refine`` the store grows along the frequency axis (:meth:`StudyStore.
add_frequencies`): refined frequencies follow the workflow's own, ``refined`` marks them, and
no chunk written before is rewritten.

One Dask task computes one (frequency, family, chunk) and writes exactly one chunk of every
data array, so concurrent writers never share a chunk.  ``done`` is set only after the data:
with Zarr v3's ``write_empty_chunks=False`` a chunk's presence proves nothing (an all-NaN or
all-zero chunk is never written).  Root attributes hold the resolved workflow, its TOML
source, the parameters, numerics, accuracy, the seeding rule, the package version, the kernel
that computed the chunks (:func:`bbb.provenance.kernel_identity`: a hash of the kernel's
sources, the numba and numpy versions) and a fingerprint of everything that determines the
stored numbers (the workflow's data identity and the kernel); opening the store with a
workflow of another fingerprint, or with another kernel, is refused.

Root attributes are netCDF-safe (``xr.open_zarr(store).to_netcdf(...)`` works): flat strings
and numbers; the nested ones (:data:`JSON_ATTRS`) are JSON strings, decoded by
:func:`read_attrs`.
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import hashlib
import json
import os
import socket
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from importlib import metadata
from typing import Any

import numpy as np
import zarr

from bbb.provenance import kernel_identity
from bbb.record import COLLISION_FIELDS, CONTACT_TIME_NAMES, COUNTER_NAMES

from .schema import as_dict
from .workflow import Study

__all__ = ["StoreError", "StudyStore", "run_lock", "normalize_path", "COLLISION_FIELDS", "LAYOUT_VERSION",
           "package_version", "read_attrs", "store_fingerprint", "JSON_ATTRS", "KERNEL_ATTRS"]

# 3: root attributes record the kernel (KERNEL_ATTRS) and are netCDF-safe (JSON_ATTRS are JSON
#    strings); 2: collisions carry bbb.record.COLLISION_FIELDS (t, x, y, vx, vy, phase);
#    1 had no phase
LAYOUT_VERSION = 3
_OLDER_LAYOUTS = {2: "it records no kernel hash, so whether its chunks were computed by this "
                     "kernel cannot be known",
                  1: "its collisions have no floor phase"}
#: root attributes held as JSON strings (nested dicts, which netCDF attributes cannot hold)
JSON_ATTRS = ("workflow", "params", "numerics", "accuracy")
#: root attributes naming the kernel that computed the chunks (bbb.provenance.kernel_identity)
KERNEL_ATTRS = ("kernel_hash", "numba_version", "numpy_version")
# Per-particle counters kept from bbb's SimRun.counters ('recorded' is stored as n_recorded).
COUNTERS = tuple(c for c in COUNTER_NAMES if c != "recorded")
SEEDING = ("SeedSequence(workflow seed, spawn_key=(round(f * 1000), "
           "zlib.crc32(family name), chunk index))")


class StoreError(ValueError):
    """A store that cannot be used as asked (wrong workflow, not a bbb store, unwritable)."""


def package_version() -> str:
    try:
        return metadata.version("bbb")
    except metadata.PackageNotFoundError:  # running from a source tree without install
        return "unknown"


def normalize_path(path: str | os.PathLike) -> str:
    """A store path as used everywhere: ``file://`` URLs become plain local paths, and local
    paths absolute (workers may run in another directory); other URLs are kept."""
    path = os.fspath(path)
    if path.startswith("file://"):
        path = path.removeprefix("file://")
    return path if "://" in path else os.path.abspath(path)


def _is_local(path: str) -> bool:
    return "://" not in path


@dataclass(frozen=True)
class StudyStore:
    """A handle on one study's store: its path (local or fsspec URL) and its Study."""

    path: str
    study: Study

    # -- opening ---------------------------------------------------------------------------
    @classmethod
    def create_or_open(cls, path: str | os.PathLike, study: Study) -> StudyStore:
        """Create the whole layout, or reopen an existing store made by the same workflow."""
        path = normalize_path(path)
        existing = _open_group(path)
        if existing is not None:
            attrs = read_attrs(existing)
            if "fingerprint" not in attrs:
                if attrs.get("bbb_creating"):  # layout creation was interrupted: no data yet
                    return cls._create(path, study, overwrite=True)
                raise StoreError(f"{path}: exists and is not a bbb study store; "
                                 "allowed: a new path or a store made by the same workflow")
            layout = attrs.get("bbb_store_layout")
            if layout != LAYOUT_VERSION:
                why = f" ({_OLDER_LAYOUTS[layout]})" if layout in _OLDER_LAYOUTS else ""
                raise StoreError(f"{path}: store layout {layout!r} of an older bbb{why}; "
                                 f"allowed: layout {LAYOUT_VERSION} (delete it or use another --store)")
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
                                 f"({_difference(old, study)}); "
                                 "allowed: the same workflow, or another --store")
            if attrs["fingerprint"] != store_fingerprint(study.fingerprint(), kernel):
                raise StoreError(f"{path}: its fingerprint does not match its own workflow and "
                                 "kernel attributes (altered?); run `bbb verify` on it")
            stored = Study.from_dict(attrs["workflow"])
            if stored.refined:  # frequencies an earlier run added by refinement
                study = study.with_refined(stored.refined)
            store = cls(path, study)
            store._update_reduce_settings(existing, study)
            return store
        if _is_local(path) and os.path.exists(path):
            raise StoreError(f"{path}: exists and is not a Zarr store; allowed: a new path or a "
                             "store made by the same workflow")
        return cls._create(path, study, overwrite=False)

    @classmethod
    def open(cls, path: str | os.PathLike) -> StudyStore:
        """Open an existing store read-only, with the Study it was made by."""
        path = normalize_path(path)
        g = _open_group(path)
        if g is None:
            raise StoreError(f"{path}: no such store")
        attrs = read_attrs(g)
        if "fingerprint" not in attrs:
            raise StoreError(f"{path}: not a (complete) bbb study store")
        return cls(path, Study.from_dict(attrs["workflow"], text=attrs.get("workflow_toml", "")))

    @classmethod
    def _create(cls, path: str, study: Study, overwrite: bool) -> StudyStore:
        try:
            g = zarr.open_group(path, mode="w" if overwrite else "w-",
                                attributes={"bbb_creating": True})
            _create_layout(g, study)
            # The fingerprint goes last: a store without it was never completely laid out.
            g.attrs.update(_root_attrs(study))
            del g.attrs["bbb_creating"]
        except (OSError, zarr.errors.ContainsGroupError, zarr.errors.ContainsArrayError) as e:
            raise StoreError(f"{path}: cannot create the store ({e}); "
                             "allowed: a writable, new path") from None
        return cls(path, study)

    def _update_reduce_settings(self, g: zarr.Group, study: Study) -> None:
        # Same data, possibly new reduce settings (analysis, bootstrap resamples, name): the
        # stored numbers stay valid, so the workflow recorded for `bbb reduce` is updated.
        if read_attrs(g).get("workflow") != _jsonable(study.to_dict()):
            g = zarr.open_group(self.path, mode="r+")
            g.attrs.update({"workflow": _json_attr(study.to_dict()), "workflow_toml": study.text})

    # -- reading ---------------------------------------------------------------------------
    def group(self, mode: str = "r") -> zarr.Group:
        return zarr.open_group(self.path, mode=mode)

    def attrs(self) -> dict[str, Any]:
        """The root attributes, JSON strings (:data:`JSON_ATTRS`) decoded."""
        return read_attrs(self.group())

    def done(self) -> np.ndarray:
        """bool (frequency, family, chunk): chunks whose data are completely written."""
        return np.asarray(self.group()["done"][...], dtype=bool)

    def chunk_particles(self, chunk: int) -> slice:
        c = self.study.accuracy.chunk_size
        return slice(chunk * c, (chunk + 1) * c)

    def read_done(self, name: str, fi: int, mi: int, done_fm: np.ndarray | None = None
                  ) -> np.ndarray:
        """Array ``name`` at (frequency index fi, family index mi) for the particles of the
        done chunks only, in particle order: shape (particles of done chunks, ...).

        Chunks not marked done are never read, so a half-written or damaged chunk of an
        interrupted run cannot break a reduction.  A done chunk that cannot be decoded raises
        StoreError naming it (``bbb verify`` checks every done chunk).
        """
        arr = self.group()[name]
        if done_fm is None:
            done_fm = self.done()[fi, mi]
        parts = []
        for ci in np.flatnonzero(done_fm):
            try:
                parts.append(np.asarray(arr[fi, mi, self.chunk_particles(int(ci))]))
            except Exception as e:  # zarr/codec errors differ by cause; all mean the same here
                f = self.study.frequencies[fi]
                fam = self.study.families[mi].name
                raise StoreError(
                    f"{self.path}: {name}[f = {f:g} Hz, family {fam}, chunk {ci}] is marked done "
                    f"but cannot be read ({type(e).__name__}: {e}); run `bbb verify` on the "
                    "store") from None
        if parts:
            return np.concatenate(parts)
        return np.zeros((0, *arr.shape[3:]), dtype=arr.dtype)

    # -- writing ---------------------------------------------------------------------------
    def write_chunk(self, fi: int, mi: int, ci: int, run: Any, seconds: float,
                    mark_done: bool = True) -> None:
        """Write one task's results (a bbb SimRun) into its own chunk of every array, then
        mark it done.  Indices: fi frequency, mi family, ci chunk; seconds: its simulation time.

        Idempotent: Dask may run a task twice, and a rerun writes the same bytes.
        mark_done=False leaves a written chunk unfinished (fault injection in tests).
        """
        g = self.group("r+")
        sl = self.chunk_particles(ci)
        obs = self.study.observables
        if obs.positions:
            g["positions"][fi, mi, sl, :] = run.positions
        if obs.collisions:
            g["collisions"][fi, mi, sl, :, :] = run.collisions_dense
            g["n_recorded"][fi, mi, sl] = run.n_recorded
        for name in COUNTERS:
            g[f"n_{name}"][fi, mi, sl] = run.counters[name]
        if obs.contact:
            for name in CONTACT_TIME_NAMES:
                g[f"{name}_time"][fi, mi, sl] = run.contact_time[name]
        g["chunk_seconds"][fi, mi, ci] = seconds
        # Only now, after every data array: the chunk is complete.
        if mark_done:
            g["done"][fi, mi, ci] = True

    def write_stop(self, fi: int, mi: int, n_chunks: int, reason: int) -> None:
        """Record that (frequency fi, family mi) stopped after ``n_chunks`` chunks, and why
        (pipeline.adaptive.STOP_LEGEND).  The reason goes last: it marks the record final."""
        g = self.group("r+")
        g["n_chunks_used"][fi, mi] = n_chunks
        g["stop_reason"][fi, mi] = reason

    def stops(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(n_chunks_used, stop_reason), each (frequency, family), of a target_ci store."""
        g = self.group()
        if "stop_reason" not in g:
            return None
        return (np.asarray(g["n_chunks_used"][...]), np.asarray(g["stop_reason"][...]))

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
        g.attrs.update({"workflow": _json_attr(study.to_dict())})
        grown = StudyStore(self.path, study)
        grown.consolidate()
        return grown

    def consolidate(self) -> None:
        with warnings.catch_warnings():  # consolidated metadata is not yet in the v3 spec
            warnings.simplefilter("ignore")
            zarr.consolidate_metadata(self.path)


# -------------------------------------------------------------------------------------------
@contextmanager
def run_lock(path: str) -> Iterator[None]:
    """Hold ``<store>.lock`` (beside a local store) while a run writes to the store.

    The lock records the holder's host, pid and start time.  A second run is refused with
    that information; a lock left by a killed run on this host (its pid is gone) is stale and
    taken over.  fsspec URLs are not locked (no atomic create on object stores).
    """
    path = normalize_path(path)
    if not _is_local(path):
        yield
        return
    lock = path.rstrip("/") + ".lock"
    me = {"host": socket.gethostname(), "pid": os.getpid(),
          "started": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")}
    try:
        os.makedirs(os.path.dirname(os.path.abspath(lock)), exist_ok=True)
    except OSError as e:
        raise StoreError(f"{path}: cannot create its directory ({e.strerror})") from None
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            holder = _read_lock(lock)
            if holder.get("host") == me["host"] and not _pid_alive(holder.get("pid")):
                _remove_stale(lock, holder)  # its run was killed on this machine
                continue
            raise StoreError(
                f"{path}: in use by another bbb run (host {holder.get('host', '?')}, pid "
                f"{holder.get('pid', '?')}, since {holder.get('started', '?')}); if no run is "
                f"active, delete {lock}") from None
        except OSError as e:
            raise StoreError(f"{path}: cannot create the lock {lock} ({e.strerror})") from None
        with os.fdopen(fd, "w") as fh:
            json.dump(me, fh)
        break
    else:
        raise StoreError(f"{path}: could not take the lock {lock}; delete it if no run is active")
    try:
        yield
    finally:
        if _read_lock(lock).get("pid") == me["pid"]:
            _remove(lock)


def _remove_stale(lock: str, stale: dict) -> None:
    """Remove ``lock`` if it still holds ``stale``.  Two runs that find the same stale lock must
    not both take it over: the later one would remove the lock the first has just written.  So
    the check and the removal happen under an exclusive flock of the lock's directory (no extra
    file; where directories cannot be locked, e.g. on some NFS mounts, the check runs unlocked)."""
    try:
        dfd = os.open(os.path.dirname(lock) or ".", os.O_RDONLY)
    except OSError:
        dfd = None
    try:
        if dfd is not None:
            try:
                fcntl.flock(dfd, fcntl.LOCK_EX)
            except OSError:
                pass
        if _read_lock(lock) == stale:
            _remove(lock)
    finally:
        if dfd is not None:
            os.close(dfd)  # releases the flock


def _read_lock(lock: str) -> dict:
    try:
        with open(lock) as fh:
            return json.load(fh)
    except (OSError, ValueError):  # gone, or written only half by a killed run
        return {}


def _pid_alive(pid) -> bool:
    if not isinstance(pid, int) or pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def _remove(path: str) -> None:
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


def _open_group(path: str) -> zarr.Group | None:
    try:
        return zarr.open_group(path, mode="r")
    except (FileNotFoundError, zarr.errors.GroupNotFoundError, zarr.errors.NodeTypeValidationError):
        return None
    except Exception as e:  # e.g. an unreadable file where the store should be
        raise StoreError(f"{path}: cannot open ({type(e).__name__}: {e})") from None


def _create_layout(g: zarr.Group, study: Study) -> None:
    acc, obs = study.accuracy, study.observables
    F, M, N, C = len(study.frequencies), len(study.families), acc.n_particles, acc.n_chunks
    cs = acc.chunk_size
    # chunked by the workflow's own grid, so that refinement (which appends) keeps the chunks
    n_base = max(1, len(study.base_frequencies))

    def coord(name, values, dtype, units, long_name, dim=None, chunk=None):
        arr = g.create_array(name, shape=(len(values),), dtype=dtype,
                             chunks=(chunk or max(1, len(values)),),
                             dimension_names=[dim or name],
                             attributes={"units": units, "long_name": long_name})
        arr[:] = np.asarray(values, dtype=dtype if dtype is not str else None)

    def data(name, dims, shape, chunks, dtype, fill, units, long_name, **extra):
        attrs = {"units": units, "long_name": long_name, **extra}
        if "family" in dims:  # CF convention: xarray then shows `initial` as a coordinate
            attrs["coordinates"] = "initial"
        g.create_array(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill,
                       dimension_names=list(dims), attributes=attrs)

    coord("frequency", list(study.frequencies), "float64", "Hz", "floor frequency f",
          chunk=n_base)
    if study.refine is not None:
        added = {round(f * 1000) for f in study.refined}
        coord("refined", [round(f * 1000) in added for f in study.frequencies], "bool", "",
              "frequency added by adaptive refinement", dim="frequency", chunk=n_base)
    coord("family", [f.name for f in study.families], str, "", "initial-condition family")
    coord("initial", [f.initial for f in study.families], str, "", "initial condition kind",
          dim="family")
    coord("particle", np.arange(N), "int64", "", "particle index within the family")
    coord("chunk", np.arange(C), "int64", "", f"ensemble chunk of {cs} particles")
    if obs.positions:
        times = study.sample_times()
        coord("time", times, "float64", "s", "sample time")
        data("positions", ("frequency", "family", "particle", "time"), (F, M, N, len(times)),
             (1, 1, cs, len(times)), "float64", np.nan, "mm", "horizontal position x")
    if obs.collisions:
        K = obs.collisions_record
        coord("collision", np.arange(K), "int64", "", f"collision index from t = "
              f"{obs.collisions_from:g} s")
        units = ", ".join(collision_field_units())
        coord("field", list(COLLISION_FIELDS), str, units, "post-collision state component")
        data("collisions", ("frequency", "family", "particle", "collision", "field"),
             (F, M, N, K, len(COLLISION_FIELDS)), (1, 1, cs, K, len(COLLISION_FIELDS)), "float64",
             np.nan, units, f"post-collision ({', '.join(COLLISION_FIELDS)}), NaN-padded")
        data("n_recorded", ("frequency", "family", "particle"), (F, M, N), (1, 1, cs), "int64",
             0, "", "valid rows of collisions")
    for name in COUNTERS:
        data(f"n_{name}", ("frequency", "family", "particle"), (F, M, N), (1, 1, cs), "int64", 0,
             "", f"number of {name} up to t_max")
    if obs.contact:
        for name in CONTACT_TIME_NAMES:
            data(f"{name}_time", ("frequency", "family", "particle"), (F, M, N), (1, 1, cs),
                 "float64", np.nan, "s", f"time {name} in sustained contact up to t_max")
    data("done", ("frequency", "family", "chunk"), (F, M, C), (1, 1, 1), "bool", False, "",
         "chunk completely written")
    data("chunk_seconds", ("frequency", "family", "chunk"), (F, M, C), (1, 1, 1), "float64",
         np.nan, "s", "wall time of the chunk's simulation (not reproducible)")
    if acc.adaptive:
        from .adaptive import STOP_LEGEND

        legend = "; ".join(f"{k} {v}" for k, v in STOP_LEGEND.items())
        data("n_chunks_used", ("frequency", "family"), (F, M), (1, 1), "int64", 0, "",
             "chunks used: the first n_chunks_used chunks (0: not decided yet)")
        data("stop_reason", ("frequency", "family"), (F, M), (1, 1), "int8", 0, "",
             f"why sampling stopped ({legend})", legend=legend)


#: units of the recorded collision fields (bbb.record.COLLISION_FIELDS), "1": dimensionless
FIELD_UNITS = {"t": "s", "x": "mm", "y": "mm", "vx": "mm/s", "vy": "mm/s", "phase": "1"}


def collision_field_units() -> tuple[str, ...]:
    """Units of bbb.record.COLLISION_FIELDS in storage order ('?' for a field this module does
    not know yet: tests/pipeline/test_store.py fails on it, so it is named here)."""
    return tuple(FIELD_UNITS.get(name, "?") for name in COLLISION_FIELDS)


def _root_attrs(study: Study) -> dict[str, Any]:
    kernel = kernel_identity()
    return {
        "bbb_store_layout": LAYOUT_VERSION,
        "bbb_version": package_version(),
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "workflow": _json_attr(study.to_dict()),
        "workflow_toml": study.text,
        "params": _json_attr(study.base_params),
        "numerics": _json_attr(study.accuracy.numerics().as_dict()),
        "accuracy": _json_attr(as_dict(study.accuracy)),
        "seeding": SEEDING,
        **kernel,
        "workflow_fingerprint": study.fingerprint(),
        "fingerprint": store_fingerprint(study.fingerprint(), kernel),
    }


def store_fingerprint(workflow_fingerprint: str, kernel: dict[str, str]) -> str:
    """sha256 over the workflow's data fingerprint and the kernel identity (KERNEL_ATTRS):
    two stores with the same fingerprint hold the same numbers, chunk for chunk."""
    blob = json.dumps({"workflow": workflow_fingerprint, **{k: kernel[k] for k in KERNEL_ATTRS}},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()


def read_attrs(group: zarr.Group) -> dict[str, Any]:
    """A store's root attributes with the JSON strings of :data:`JSON_ATTRS` decoded (a store
    of layout <= 2 holds them as nested dicts already: returned as they are)."""
    attrs = dict(group.attrs)
    for key in JSON_ATTRS:
        if isinstance(attrs.get(key), str):
            try:
                attrs[key] = json.loads(attrs[key])
            except ValueError:
                pass  # left as it is: bbb verify reports an unreadable attribute
    return attrs


def _json_attr(o: Any) -> str:
    return json.dumps(_jsonable(o), sort_keys=True)


def _jsonable(o: Any) -> Any:
    if isinstance(o, dict):
        return {k: _jsonable(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [_jsonable(v) for v in o]
    return o


def _difference(old: Study, new: Study) -> str:
    """Name the first data-determining key that differs, e.g. 'params.alpha: 0.7 -> 0.5'."""
    a, b = old.data_identity(), new.data_identity()
    for k in a:
        if a[k] != b[k]:
            if isinstance(a[k], dict):
                for kk in sorted(set(a[k]) | set(b[k])):
                    if a[k].get(kk) != b[k].get(kk):
                        return f"{k}.{kk}: store {a[k].get(kk)!r}, workflow {b[k].get(kk)!r}"
            return f"{k}: store {a[k]!r}, workflow {b[k]!r}"
    return "fingerprints differ"
