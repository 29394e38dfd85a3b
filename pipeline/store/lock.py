"""The run lock: ``<store>.lock`` beside a local store while a run writes to it.

One writer per store at a time.  The lock file records the holder's host, pid and start time;
a lock left by a killed run on this host (its pid is gone) is stale and taken over under a
flock of its directory, so that two runs finding the same stale lock cannot both take it.
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import json
import os
import socket
from collections.abc import Iterator
from contextlib import contextmanager

from .study_store import StoreError, is_local, normalize_path

__all__ = ["run_lock"]


@contextmanager
def run_lock(path: str) -> Iterator[None]:
    """Hold ``<store>.lock`` (beside a local store) while a run writes to the store.

    The lock records the holder's host, pid and start time.  A second run is refused with
    that information; a lock left by a killed run on this host (its pid is gone) is stale and
    taken over.  fsspec URLs are not locked (no atomic create on object stores).
    """
    path = normalize_path(path)
    if not is_local(path):
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
