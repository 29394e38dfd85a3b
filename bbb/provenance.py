"""Which kernel made a trajectory: a hash of the bbb sources that determine it, plus the
numba and numpy versions that compiled and seeded it.

A store records :func:`kernel_identity` so that resuming it with another kernel (an edited
collision search, another initial-condition draw, a changed default tolerance) is refused
instead of silently mixing chunks of two kernels.

What is hashed (:data:`KERNEL_SOURCES`): every module of ``bbb`` that ``bbb.simulate`` runs
or reads — the map of both floors, its collision search and its contact phase (every module
of bbb/dynamics/, by its path), the floor (surface.py), the initial conditions (ensemble.py),
how the kernel compiles (jit.py), the parameters and their presets (params.py), the numerical
tolerances and their defaults (numerics.py), the driver (simulate.py) and what it records
(record.py).
Not hashed: ``bbb/__init__.py`` (it holds the version string; a version bump alone changes
no trajectory) and the analyses (every module of bbb/analysis/: stats, transport, locking,
extrema, ...), which never touch a stored trajectory.  A test checks that the list is exactly
the bbb modules ``bbb.simulate`` imports, so a new kernel module cannot be left out.

What the hash covers is the code as it compiles, not the text: each source is parsed and its
syntax tree, with every bare string statement (docstrings) removed, is written out by
``ast.dump`` (:func:`normalised`) -- so comments, docstrings, blank lines, line breaks and
positions change nothing, and any edit of code (a constant, an operator, a name, an argument)
makes a new kernel.  ``ast.dump``'s text is fixed within a Python minor version (the grammar
and the node classes change only between minor versions), so the hash is sha256 over
``python <major>.<minor>``, a NUL, then for each file in sorted order its name, a NUL, its
normalised code and a NUL: the same sources give the same hash on every patch release of
one Python minor version, and a new hash on another minor version (a store is then refused,
as for any other kernel).
"""

from __future__ import annotations

import ast
import functools
import hashlib
import sys
from importlib import metadata, resources

__all__ = ["KERNEL_SOURCES", "kernel_hash", "kernel_identity", "normalised", "python_minor"]

#: the bbb modules (file names) that determine a simulated trajectory
KERNEL_SOURCES = ("dynamics/__init__.py", "dynamics/bounds.py", "dynamics/collide.py",
                  "dynamics/contact_step.py", "dynamics/events.py",
                  "dynamics/evolve.py",
                  "dynamics/floors/__init__.py", "dynamics/floors/arc.py",
                  "dynamics/floors/sawtooth.py", "dynamics/floors/sine.py",
                  "dynamics/liftoff.py", "dynamics/motion.py", "dynamics/options.py",
                  "dynamics/search.py", "dynamics/slide.py", "dynamics/static_friction.py",
                  "ensemble.py", "jit.py", "numerics.py", "params.py", "record.py", "simulate.py",
                  "surface.py")


class _NoBareStrings(ast.NodeTransformer):
    """Drops every statement that is only a string (a docstring, or a string left as a note):
    the compiler keeps none of them in the code it runs."""

    def visit_Expr(self, node: ast.Expr) -> ast.Expr | None:
        if isinstance(node.value, ast.Constant) and isinstance(node.value.value, str):
            return None
        return node


def normalised(source: str) -> str:
    """The code of a Python source as it compiles: ``ast.dump`` of its syntax tree without
    docstrings (comments and positions are not in the tree).  Raises SyntaxError on a source
    that does not parse."""
    return ast.dump(_NoBareStrings().visit(ast.parse(source)), include_attributes=False)


def python_minor() -> str:
    """``"<major>.<minor>"`` of the running Python: the version whose ``ast.dump`` the hash reads."""
    return f"{sys.version_info.major}.{sys.version_info.minor}"


@functools.cache  # the sources as this process first saw them: close to what it has loaded
def kernel_hash() -> str:
    """sha256 (hex) over the Python minor version and the :func:`normalised` code of the sorted
    :data:`KERNEL_SOURCES` of the imported bbb package (module docstring)."""
    root = resources.files(__package__)
    h = hashlib.sha256(f"python {python_minor()}\0".encode())
    for name in sorted(KERNEL_SOURCES):
        code = normalised(root.joinpath(name).read_text(encoding="utf-8"))
        h.update(name.encode() + b"\0" + code.encode() + b"\0")
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
