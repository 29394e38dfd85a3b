"""How the kernel is compiled: one set of numba options for every jitted function of the map,
so that a choice made here holds for all of them.

``@jitted``      a kernel function: nopython, cached on disk, no fastmath (bit for bit the
                 IEEE arithmetic the source spells out);
``@inlined``     the same, inlined into its caller by numba (small formulae: the gap, a
                 floor's depth, a bound);
``@allocating``  the same with numba's reference counting (NRT) on, for the few functions
                 that create an array (the ensemble's bisection stack, the numpy faces).

Two options differ from numba's defaults, both for speed and neither changing a bit of any
result (benchmarks/results/kernel-jit-*.txt measures them side by side):

* ``error_model="numpy"``: a float division by zero gives ±inf or NaN instead of raising
  ZeroDivisionError, so no test of the divisor precedes every division.  The map's guards
  already catch a non-finite state (counted as an anomaly, bbb.dynamics.events) and no run
  divides by zero (one that did would have stopped with a traceback before).
* ``_nrt=False``: the kernel allocates nothing, so it needs no reference counts.  With them,
  every call that passes an array (the bisection stack, the output rows) increments and
  decrements a count atomically, a few per collision; a function compiled this way cannot
  create an array (numba refuses to compile one that does: use ``@allocating``).
"""

from __future__ import annotations

from numba import njit

__all__ = ["KERNEL_OPTIONS", "jitted", "inlined", "allocating"]

#: numba options of every kernel function (module doc)
KERNEL_OPTIONS = {"cache": True, "error_model": "numpy", "_nrt": False}

jitted = njit(**KERNEL_OPTIONS)
inlined = njit(inline="always", **KERNEL_OPTIONS)
allocating = njit(**{**KERNEL_OPTIONS, "_nrt": True})
