"""Floor shapes as types: what the kernel needs of a floor's profile, one module per shape.

A floor is the profile y = y_f(t) − c(d) repeated in cells of width S (mm): c(d) ≥ 0 (mm) is
the depth below the profile's top at offset d (mm, |d| ≤ S/2) from the cell's centre.  A
shape is a small record (the arc's is its radius R, a float; :class:`~.sine.Sine`,
:class:`~.sawtooth.Sawtooth`) and a module with its formulae, each a jitted function of
(record, ...):

- ``depth(sh, d)``, ``slope(sh, d)`` = c'(d), ``curvature(sh, d)`` = c''(d),
  ``normal(sh, d)``: the outward unit normal (c', 1)/√(1 + c'²) of y = −c(d)
- the certificates the collision search proves with (bbb.dynamics.bounds), each
  rigorous over an interval [da, db] inside one cell (ca, cb: c at its ends):
  ``curvature_max(sh, da, db, ca, cb)`` ≥ c'' there (inf across a convex kink),
  ``concavity(sh)`` with c'' ≥ −concavity in every cell, ``depth_min(sh, da, db, ca, cb)``
  ≤ c there
- ``valley_depth(sh, S)``: the largest c; ``is_flat(sh)``: the flat floor (c ≡ 0)

Concave kinks (cusps, a sawtooth's valleys) must sit at the cell edges, where the search splits
a flight.  The functions below dispatch on the record's type at compile time (numba
overloads): a kernel compiled for one shape holds that shape's code only.  Adding a shape is
a module like :mod:`.sine` plus one line in :data:`SHAPES`.
"""

from __future__ import annotations

import numpy as np
from numba import types
from numba.extending import overload

from ...jit import allocating
from . import arc, sawtooth, sine

#: every floor shape's module but the arc's (whose record is a float, its radius)
SHAPES = (sine, sawtooth)
#: what a shape's module provides (module doc)
INTERFACE = ("depth", "slope", "curvature", "normal", "curvature_max", "concavity", "depth_min",
             "valley_depth", "is_flat")


def module_of(shape_type):
    """The module of the shape whose record has the numba type ``shape_type``, or None."""
    if isinstance(shape_type, types.Float):
        return arc
    cls = getattr(shape_type, "instance_class", None)
    for mod in SHAPES:
        if cls is mod.RECORD:
            return mod
    return None


def _impl(shape_type, name):
    mod = module_of(shape_type)
    return None if mod is None else getattr(mod, name).py_func


# the generic functions: stubs that numba replaces by the shape's own (no Python body runs)
def depth(sh, d):
    """c(d) (mm), the depth below the top at offset d (mm)."""


def slope(sh, d):
    """c'(d)."""


def curvature(sh, d):
    """c''(d) (1/mm)."""


def normal(sh, d):
    """The outward unit normal (nx, ny) of the floor at offset d."""


def curvature_max(sh, da, db, ca, cb):
    """An upper bound of c'' (1/mm) on [da, db] within one cell; ca, cb are c at its ends."""


def concavity(sh):
    """κ ≥ 0 (1/mm) with c'' ≥ −κ in every cell."""


def depth_min(sh, da, db, ca, cb):
    """A lower bound of c (mm) on [da, db] within one cell; ca, cb are c at its ends."""


def valley_depth(sh, S):
    """The largest depth c (mm) in a cell of width S (mm)."""


def is_flat(sh):
    """Whether the floor is flat (c ≡ 0)."""


overload(depth)(lambda sh, d: _impl(sh, "depth"))
overload(slope)(lambda sh, d: _impl(sh, "slope"))
overload(curvature)(lambda sh, d: _impl(sh, "curvature"))
overload(normal)(lambda sh, d: _impl(sh, "normal"))
overload(curvature_max)(lambda sh, da, db, ca, cb: _impl(sh, "curvature_max"))
overload(concavity)(lambda sh: _impl(sh, "concavity"))
overload(depth_min)(lambda sh, da, db, ca, cb: _impl(sh, "depth_min"))
overload(valley_depth)(lambda sh, S: _impl(sh, "valley_depth"))
overload(is_flat)(lambda sh: _impl(sh, "is_flat"))


@allocating
def depths(sh, d):
    """c (mm) at every offset of the array d (mm): the numpy face of :func:`depth`."""
    out = np.empty(d.shape[0])
    for i in range(d.shape[0]):
        out[i] = depth(sh, d[i])
    return out


@allocating
def normals(sh, d):
    """The outward unit normals (nx, ny) at every offset of the array d (mm)."""
    nx = np.empty(d.shape[0])
    ny = np.empty(d.shape[0])
    for i in range(d.shape[0]):
        nx[i], ny[i] = normal(sh, d[i])
    return nx, ny
