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
field          (field,)                     t,x,y,vx,vy    str     whole    [collisions]
positions      (frequency, family, particle, time)  x, mm  f8      (1, 1, chunk_size, T)
collisions     (frequency, family, particle, collision, field)  f8  (1, 1, chunk_size, K, 5)
n_recorded     (frequency, family, particle)  valid rows   i8      (1, 1, chunk_size) [coll.]
n_collisions, n_sticks, n_liftoffs  (frequency, family, particle)  i8  (1, 1, chunk_size)
done           (frequency, family, chunk)   bool           b1      (1, 1, 1)
chunk_seconds  (frequency, family, chunk)   simulate, s    f8      (1, 1, 1)   not reproducible
=============  ==========================================  ======  ===========================

One Dask task computes one (frequency, family, chunk) and writes exactly one chunk of every
data array, so concurrent writers never share a chunk.  ``done`` is set only after the data:
with Zarr v3's ``write_empty_chunks=False`` a chunk's presence proves nothing (an all-NaN or
all-zero chunk is never written).  Root attributes hold the resolved workflow, its TOML
source, the parameters, numerics, accuracy, the seeding rule, the package version and a
fingerprint of everything that determines the stored numbers; opening the store with a
workflow of another fingerprint is refused.
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import json
import os
import socket
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from importlib import metadata
from typing import Any

import numpy as np
import zarr

from bbb.record import COLLISION_FIELDS, COUNTER_NAMES

from .workflow import Study

__all__ = ["StoreError", "StudyStore", "run_lock", "normalize_path", "COLLISION_FIELDS", "LAYOUT_VERSION",
           "package_version"]

# 2: collisions carry bbb.record.COLLISION_FIELDS (t, x, y, vx, vy, phase); 1 had no phase
LAYOUT_VERSION = 2
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
            attrs = dict(existing.attrs)
            if "fingerprint" not in attrs:
                if attrs.get("bbb_creating"):  # layout creation was interrupted: no data yet
                    return cls._create(path, study, overwrite=True)
                raise StoreError(f"{path}: exists and is not a bbb study store; "
                                 "allowed: a new path or a store made by the same workflow")
            if attrs.get("bbb_store_layout") != LAYOUT_VERSION:
                raise StoreError(f"{path}: store layout {attrs.get('bbb_store_layout')!r} of an older bbb; "
                                 f"allowed: layout {LAYOUT_VERSION} (delete it or use another --store)")
            if attrs["fingerprint"] != study.fingerprint():
                old = Study.from_dict(attrs["workflow"])
                raise StoreError(f"{path}: made by a different workflow "
                                 f"({_difference(old, study)}); "
                                 "allowed: the same workflow, or another --store")
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
        attrs = dict(g.attrs)
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
        if g.attrs.get("workflow") != _jsonable(study.to_dict()):
            g = zarr.open_group(self.path, mode="r+")
            g.attrs.update({"workflow": _jsonable(study.to_dict()), "workflow_toml": study.text})

    # -- reading ---------------------------------------------------------------------------
    def group(self, mode: str = "r") -> zarr.Group:
        return zarr.open_group(self.path, mode=mode)

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
        g["chunk_seconds"][fi, mi, ci] = seconds
        # Only now, after every data array: the chunk is complete.
        if mark_done:
            g["done"][fi, mi, ci] = True

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

    def coord(name, values, dtype, units, long_name):
        arr = g.create_array(name, shape=(len(values),), dtype=dtype, chunks=(max(1, len(values)),),
                             dimension_names=[name if name != "initial" else "family"],
                             attributes={"units": units, "long_name": long_name})
        arr[:] = np.asarray(values, dtype=dtype if dtype is not str else None)

    def data(name, dims, shape, chunks, dtype, fill, units, long_name):
        attrs = {"units": units, "long_name": long_name}
        if "family" in dims:  # CF convention: xarray then shows `initial` as a coordinate
            attrs["coordinates"] = "initial"
        g.create_array(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=fill,
                       dimension_names=list(dims), attributes=attrs)

    coord("frequency", list(study.frequencies), "float64", "Hz", "floor frequency f")
    coord("family", [f.name for f in study.families], str, "", "initial-condition family")
    coord("initial", [f.initial for f in study.families], str, "", "initial condition kind")
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
        coord("field", list(COLLISION_FIELDS), str, "s, mm, mm, mm/s, mm/s, floor phase (1)",
              "post-collision state component")
        data("collisions", ("frequency", "family", "particle", "collision", "field"),
             (F, M, N, K, len(COLLISION_FIELDS)), (1, 1, cs, K, len(COLLISION_FIELDS)), "float64",
             np.nan, "s, mm, mm, mm/s, mm/s", "post-collision (t, x, y, vx, vy), NaN-padded")
        data("n_recorded", ("frequency", "family", "particle"), (F, M, N), (1, 1, cs), "int64",
             0, "", "valid rows of collisions")
    for name in COUNTERS:
        data(f"n_{name}", ("frequency", "family", "particle"), (F, M, N), (1, 1, cs), "int64", 0,
             "", f"number of {name} up to t_max")
    data("done", ("frequency", "family", "chunk"), (F, M, C), (1, 1, 1), "bool", False, "",
         "chunk completely written")
    data("chunk_seconds", ("frequency", "family", "chunk"), (F, M, C), (1, 1, 1), "float64",
         np.nan, "s", "wall time of the chunk's simulation (not reproducible)")


def _root_attrs(study: Study) -> dict[str, Any]:
    return _jsonable({
        "bbb_store_layout": LAYOUT_VERSION,
        "bbb_version": package_version(),
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "workflow": study.to_dict(),
        "workflow_toml": study.text,
        "params": study.base_params,
        "numerics": study.accuracy.numerics().as_dict(),
        "accuracy": asdict(study.accuracy),
        "seeding": SEEDING,
        "fingerprint": study.fingerprint(),
    })


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
