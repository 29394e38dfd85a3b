"""bbb.jit: every kernel function is compiled with the kernel's options, and the options do
what its docstring says (a division by zero is IEEE, a kernel function cannot allocate)."""

from __future__ import annotations

import importlib
import pkgutil

import numpy as np
import pytest
from numba.core.errors import NumbaError
from numba.core.registry import CPUDispatcher

import bbb.dynamics
from bbb import jit, surface

#: functions that create an array, compiled with reference counting (@allocating)
ALLOCATING = {"evolve_ensemble", "depths", "normals"}


def kernel_dispatchers() -> dict[str, CPUDispatcher]:
    """Every jitted function defined in bbb.dynamics (and its subpackages) and bbb.surface."""
    mods = [surface]
    for info in pkgutil.walk_packages(bbb.dynamics.__path__, "bbb.dynamics."):
        mods.append(importlib.import_module(info.name))
    return {f"{m.__name__}.{name}": obj for m in mods for name, obj in vars(m).items()
            if isinstance(obj, CPUDispatcher) and obj.py_func.__module__ == m.__name__}


def test_every_kernel_function_has_the_kernel_options():
    found = kernel_dispatchers()
    assert len(found) > 50
    for name, d in found.items():
        opts = d.targetoptions
        assert opts.get("error_model") == "numpy", name
        assert opts.get("_nrt") is (name.rsplit(".", 1)[1] in ALLOCATING), name


def test_a_division_by_zero_in_the_kernel_is_inf_not_an_exception():
    @jit.jitted
    def ratio(a, b):
        return a / b

    assert ratio(1.0, 0.0) == np.inf
    assert np.isnan(ratio(0.0, 0.0))
    assert ratio(1.0, 4.0) == 0.25


def test_a_kernel_function_cannot_allocate():
    @jit.jitted
    def make(n):
        return np.empty(n)

    with pytest.raises(NumbaError):
        make(3)

    @jit.allocating
    def make_counted(n):
        return np.zeros(n)

    assert make_counted(3).tolist() == [0.0, 0.0, 0.0]
