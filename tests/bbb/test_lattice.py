"""bbb.ensemble.lattice_state: the grid of initial conditions is the cells' centres, in row
order, and refuses what it cannot be."""

import numpy as np
import pytest

from bbb import Params
from bbb.ensemble import lattice_state
from bbb.surface import depth

P = Params.preset("klages2004", f=54.0)


def test_dropped_lattice_cells_are_phase_rows_and_height_columns_at_their_centres():
    st = lattice_state(P, "dropped", np.arange(12), (3, 4), 0.5, drop_height=(0.0, 2.0))
    s_cells = st.s * P.f  # fraction of a period
    assert np.allclose(s_cells.reshape(3, 4), np.array([[1 / 6], [3 / 6], [5 / 6]]))
    surface = -P.A * np.sin(P.omega * st.s) - depth(st.d, P.R)
    assert np.allclose((st.y - surface).reshape(3, 4), [[0.25, 0.75, 1.25, 1.75]] * 3)
    assert (st.d == 0.5).all() and (st.vy == 0).all() and not st.stuck.any()
    st.check(P)


def test_launched_lattice_speeds_are_relative_to_the_floor():
    st = lattice_state(P, "launched", np.array([5]), (2, 4), -0.25, launch_speed=(0.0, 200.0))
    floor_v = -P.A * P.omega * np.cos(P.omega * st.s)
    assert np.allclose(st.vy - floor_v, 75.0) and np.allclose(st.s * P.f, 0.75)


def test_a_chunk_of_the_lattice_is_the_same_cells_as_the_whole():
    whole = lattice_state(P, "dropped", np.arange(64), (8, 8), 0.5)
    part = lattice_state(P, "dropped", np.arange(16, 32), (8, 8), 0.5)
    assert np.array_equal(whole.y[16:32], part.y) and np.array_equal(whole.s[16:32], part.s)


@pytest.mark.parametrize("bad", [dict(family="rest"), dict(index=np.array([64])),
                                 dict(offset=1.5)], ids=["rest", "index", "offset"])
def test_a_lattice_refuses_what_it_cannot_be(bad):
    kw = dict(family="dropped", index=np.arange(4), offset=0.5) | bad
    with pytest.raises(ValueError):
        lattice_state(P, kw["family"], kw["index"], (8, 8), kw["offset"])
