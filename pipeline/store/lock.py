"""The run lock: one bbb run writes to a store at a time.

A local store: ``<store>.lock`` beside it -- beside its real path, symlinks resolved, so that
two runs reaching one store by different names take the same lock -- created exclusively
(O_EXCL), holding the holder's host, pid and start time.  A lock left by a killed run on this
host (its pid is gone) is stale and taken over under a flock of its directory, so that two
runs finding the same stale lock cannot both take it.  One left by a run on another host is
not (its pid cannot be checked from here): the refusal names the file to delete.

A store at an fsspec URL: the object ``<url>.lock`` beside it, created with fsspec's exclusive
mode (``open(..., "xb")``: the filesystem refuses to create an object that exists), holding
host, pid, start time and a heartbeat, which the run rewrites every HEARTBEAT_SECONDS.  A lock
is abandoned, and taken over, when its heartbeat is older than STALE_SECONDS (its run was
killed, or lost its connection), or at once when its holder ran on this host and its pid is
gone.  See docs/cluster.md for which filesystems create exclusively.
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import json
import os
import socket
import sys
import threading
import uuid
from collections.abc import Iterator
from contextlib import contextmanager

from .study_store import StoreError, is_local, normalize_path

__all__ = ["run_lock", "pid_alive", "HEARTBEAT_SECONDS", "STALE_SECONDS"]

# A URL lock's holder rewrites its heartbeat this often; a lock whose heartbeat is older than
# STALE_SECONDS is abandoned.  Ten missed heartbeats: a run is never taken over for a slow
# write or a short network outage, and a killed run's store is free again within 5 minutes
# (at once from the killed run's host).  Each heartbeat is one small write (a PUT on S3).
HEARTBEAT_SECONDS = 30.0
STALE_SECONDS = 300.0


@contextmanager
def run_lock(path: str) -> Iterator[None]:
    """Hold the store's lock while a run writes to the store: ``<store>.lock`` beside a local
    store, the object ``<url>.lock`` beside a store at an fsspec URL.

    A second run is refused (StoreError, one line naming the store and the holder's host, pid
    and start time); a stale lock is taken over (see the module's docstring).
    """
    path = normalize_path(path)
    if not is_local(path):
        with _url_lock(path):
            yield
        return
    # the real path: two runs reaching one store through different names (a symlink to the
    # store or to a folder above it, a bind mount seen as a symlink) take the same lock
    with _local_lock(os.path.realpath(path)):
        yield


@contextmanager
def _local_lock(path: str) -> Iterator[None]:
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
            if holder.get("host") == me["host"] and not pid_alive(holder.get("pid")):
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


def pid_alive(pid) -> bool:
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


# -- stores at fsspec URLs ---------------------------------------------------------------------
def _now() -> _dt.datetime:
    return _dt.datetime.now(_dt.UTC)


@contextmanager
def _url_lock(path: str) -> Iterator[None]:
    import fsspec

    url = path.rstrip("/") + ".lock"
    try:
        fs, lock = fsspec.core.url_to_fs(url)
    except (ImportError, ValueError) as e:
        raise StoreError(f"{path}: cannot open the lock {url} ({e})") from None
    me = {"host": socket.gethostname(), "pid": os.getpid(),
          "started": _now().isoformat(timespec="seconds"), "token": uuid.uuid4().hex}
    for _ in range(3):
        holder = _read_url_lock(fs, lock)
        if holder is not None:
            age = _heartbeat_age(fs, lock, holder)
            if not _abandoned(holder, age):
                raise StoreError(
                    f"{path}: in use by another bbb run (host {holder.get('host', '?')}, pid "
                    f"{holder.get('pid', '?')}, since {holder.get('started', '?')}, last heartbeat "
                    f"{_seconds(age)} ago); a run whose heartbeat stops is taken over after "
                    f"{STALE_SECONDS:.0f} s, or delete {url} if no run is active") from None
            _remove_url_lock(fs, lock, holder)  # abandoned: its run was killed or cut off
        try:
            _create_url_lock(fs, lock, me)
        except FileExistsError:
            continue  # another run took it between our look and our create: look again
        except (OSError, ValueError, NotImplementedError) as e:  # ValueError: no "xb" mode
            raise StoreError(f"{path}: cannot create the lock {url} ({type(e).__name__}: {e}); "
                             "allowed: a filesystem that creates files exclusively "
                             "(docs/cluster.md)") from None
        break
    else:
        raise StoreError(f"{path}: could not take the lock {url}; delete it if no run is active")
    stop = threading.Event()
    beat = threading.Thread(target=_heartbeat, args=(fs, lock, me, stop, path), daemon=True,
                            name="bbb-lock-heartbeat")
    beat.start()
    try:
        yield
    finally:
        stop.set()
        beat.join()
        if (_read_url_lock(fs, lock) or {}).get("token") == me["token"]:
            try:
                fs.rm_file(lock)
            except FileNotFoundError:
                pass


def _create_url_lock(fs, lock: str, me: dict) -> None:
    """Create the lock object only if none exists: FileExistsError otherwise."""
    from fsspec.implementations.local import LocalFileSystem

    if isinstance(fs, LocalFileSystem):  # local:// -- its folder may not exist yet
        fs.makedirs(os.path.dirname(lock), exist_ok=True)
    with fs.open(lock, "xb") as fh:
        fh.write(json.dumps({**me, "heartbeat": _now().isoformat()}).encode())


def _heartbeat(fs, lock: str, me: dict, stop: threading.Event, path: str) -> None:
    """Rewrite the lock's heartbeat every HEARTBEAT_SECONDS while it is still ours."""
    while not stop.wait(HEARTBEAT_SECONDS):
        try:
            if (_read_url_lock(fs, lock) or {}).get("token") != me["token"]:
                print(f"bbb: warning: {path}: the lock {lock} is no longer this run's (deleted or "
                      "taken over); another run may write to the store", file=sys.stderr)
                return
            with fs.open(lock, "wb") as fh:
                fh.write(json.dumps({**me, "heartbeat": _now().isoformat()}).encode())
        except OSError:
            pass  # a failed write is retried at the next beat; STALE_SECONDS allows ten


def _read_url_lock(fs, lock: str) -> dict | None:
    """The lock's contents; None if there is no lock, {} if it cannot be read or parsed."""
    try:
        return json.loads(fs.cat_file(lock))
    except FileNotFoundError:
        return None
    except (OSError, ValueError):  # being rewritten, or not a lock of bbb's
        return {} if fs.exists(lock) else None


def _heartbeat_age(fs, lock: str, holder: dict) -> float | None:
    """Seconds since the holder's last heartbeat (by its clock), else since the object was last
    written (by the filesystem's); None if neither can be known."""
    try:
        then = _dt.datetime.fromisoformat(holder["heartbeat"])
    except (KeyError, TypeError, ValueError):
        try:
            then = fs.modified(lock)
        except (NotImplementedError, OSError):
            return None
    if then.tzinfo is None:
        then = then.replace(tzinfo=_dt.UTC)
    return (_now() - then).total_seconds()


def _abandoned(holder: dict, age: float | None) -> bool:
    if holder.get("host") == socket.gethostname() and not pid_alive(holder.get("pid")):
        return True  # its run was killed on this machine
    return age is not None and age > STALE_SECONDS


def _seconds(age: float | None) -> str:
    return "? s" if age is None else f"{max(age, 0.0):.0f} s"


def _remove_url_lock(fs, lock: str, stale: dict) -> None:
    """Remove the abandoned lock ``stale`` if the object still holds it.  Not atomic: object
    stores have no compare-and-delete, so two runs that find the same abandoned lock within the
    same instant could both take it over (docs/cluster.md)."""
    if _read_url_lock(fs, lock) == stale:
        try:
            fs.rm_file(lock)
        except FileNotFoundError:
            pass
