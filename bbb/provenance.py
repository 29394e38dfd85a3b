"""Which kernel made a trajectory: a hash of the bbb sources that determine it, plus the
numba and numpy versions that compiled and seeded it.

A store records :func:`kernel_identity` so that resuming it with another kernel (an edited
collision search, another initial-condition draw, a changed default tolerance) is refused
instead of silently mixing chunks of two kernels.

What is hashed (:data:`KERNEL_SOURCES`): every module of ``bbb`` that ``bbb.simulate`` runs
or reads — the map of both floors, its collision search and its contact phase (every module
of bbb/dynamics/, by its path), the floor (surface.py), the initial conditions (ensemble.py),
the parameters and their presets (params.py), the numerical tolerances and their defaults
(numerics.py), the driver (simulate.py) and what it records (record.py).
Not hashed: ``bbb/__init__.py`` (it holds the version string; a version bump alone changes
no trajectory), the old paths kept as re-exports (kernel.py, conveyor.py, search.py, stats/,
transport.py, ...: simulate never imports them) and the analyses (every module of bbb/analysis/:
stats, transport, locking, extrema, ...), which never touch a stored trajectory.  A test
checks that the list is exactly the bbb modules ``bbb.simulate`` imports, so a new kernel
module cannot be left out.

The hash is sha256 over, for each file in sorted order, its name, a NUL, its bytes and a NUL:
any edit, comments included, makes a new kernel (a comment-only edit is a false alarm, not
a missed one).
"""

from __future__ import annotations

import functools
import hashlib
from importlib import metadata, resources

__all__ = ["KERNEL_SOURCES", "kernel_hash", "kernel_identity"]

#: the bbb modules (file names) that determine a simulated trajectory
KERNEL_SOURCES = ("dynamics/__init__.py", "dynamics/bounds_conveyor.py", "dynamics/bounds_level.py",
                  "dynamics/collide.py", "dynamics/contact_conveyor.py",
                  "dynamics/contact_level.py", "dynamics/events.py", "dynamics/evolve.py",
                  "dynamics/floors/__init__.py", "dynamics/floors/arc.py",
                  "dynamics/floors/sawtooth.py", "dynamics/floors/sine.py",
                  "dynamics/liftoff.py", "dynamics/motion.py", "dynamics/options.py",
                  "dynamics/search.py", "dynamics/slide.py",
                  "ensemble.py", "numerics.py", "params.py", "record.py", "simulate.py", "surface.py")


@functools.cache  # the sources as this process first saw them: close to what it has loaded
def kernel_hash() -> str:
    """sha256 (hex) over the sorted :data:`KERNEL_SOURCES` of the imported bbb package."""
    root = resources.files(__package__)
    h = hashlib.sha256()
    for name in sorted(KERNEL_SOURCES):
        h.update(name.encode() + b"\0" + root.joinpath(name).read_bytes() + b"\0")
    return h.hexdigest()


@functools.cache
def _identity() -> tuple[tuple[str, str], ...]:
    return (("kernel_hash", kernel_hash()), ("numba_version", _version("numba")),
            ("numpy_version", _version("numpy")))


def kernel_identity() -> dict[str, str]:
    """{"kernel_hash": ..., "numba_version": ..., "numpy_version": ...}: all that must be the
    same for a chunk computed now to be bit-identical to one computed earlier."""
    return dict(_identity())


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "unknown"
