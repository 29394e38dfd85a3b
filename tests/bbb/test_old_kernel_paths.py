"""The kernel's former module paths (bbb.kernel, bbb.conveyor, bbb.search, bbb.conveyor_search,
bbb.contact, bbb.conveyor_contact) still import every name they export, for one release."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from bbb import Params
from bbb.ensemble import initial_state
from bbb.record import COLLISION_FIELDS, COUNTER_NAMES

OLD = ("kernel", "conveyor", "search", "conveyor_search", "contact", "conveyor_contact")


@pytest.mark.parametrize("name", OLD)
def test_an_old_kernel_path_still_exports_its_names(name):
    mod = importlib.import_module(f"bbb.{name}")
    missing = [n for n in mod.__all__ if not hasattr(mod, n)]
    assert mod.__all__ and missing == []


def test_the_old_evolve_ensemble_signature_gives_the_new_kernels_collisions():
    from bbb.dynamics.evolve import evolve_ensemble as new
    from bbb.dynamics.options import Floor, Run
    from bbb.kernel import evolve_ensemble as old

    p = Params.preset("klages2004", f=60.0)
    st = initial_state(p, 4, np.random.SeedSequence(3), "launched", launch_speed=(50.0, 200.0))

    def outputs():
        return (np.zeros((4, 0)), np.full((4, 20, len(COLLISION_FIELDS)), np.nan),
                np.zeros((4, len(COUNTER_NAMES)), np.int64), np.zeros((4, 2)), np.zeros((4, 4)))

    a, b = outputs(), outputs()
    args = (st.cell, st.d, st.y, st.vx, st.vy, st.s, st.stuck, st.from_surface)
    old(*args, p.g, p.A, p.omega, p.R, p.S, p.alpha, p.beta, 0.5, np.zeros(0), a[0], 0.0, a[1],
        1e-12, 1e-3, 0.25, a[2], None, a[3], a[4])
    new(*args, Floor(p.g, p.A, p.omega, p.R, p.S, p.alpha, p.beta), Run(0.5, 0.0, 1e-12, 1e-3, 0.25),
        None, None, np.zeros(0), b)
    assert np.isfinite(a[1][:, 0, 0]).all()
    assert all(np.array_equal(x, y, equal_nan=True) for x, y in zip(a, b, strict=True))
