"""Initial-condition families' mirror images and pairs (bbb.ensemble)."""

from __future__ import annotations

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.ensemble import initial_state, mirror_pair_units, mirror_pairs, mirrored

T_MAX = 4.0  # s


def _run(p: Params, state, n: int):
    # positions at the samples and at every floor period (the store's [jumps] grid), every
    # collision and lift-off row, counters and contact times: all a store keeps of a particle
    times = np.union1d(np.arange(9) * 0.5, np.minimum(np.arange(int(T_MAX * p.f) + 1) / p.f, T_MAX))
    return simulate(p, n, T_MAX, 0, state, sample_times=times, record_collisions=3000,
                    record_liftoffs=True)


@pytest.mark.parametrize("contact", [{}, {"contact": "slide"}, {"contact": "coulomb", "mu": 0.3}],
                         ids=["stick", "slide", "coulomb"])
@pytest.mark.parametrize("family", ["rest", "dropped", "launched"])
@pytest.mark.parametrize("f", [58.0, 60.0, 84.0])
def test_on_the_level_floor_the_image_is_the_reflected_trajectory_bit_for_bit(f, family, contact):
    p = Params.preset("klages2004", f=f, **contact)
    n = 6
    st = initial_state(p, n, np.random.SeedSequence([23, round(f)]), family)
    a, b = _run(p, st, n), _run(p, mirrored(st), n)
    assert a.counters["collisions"].sum() > 100  # a run with something to reflect
    assert np.array_equal(b.positions, -a.positions)
    assert np.array_equal(b.n_recorded, a.n_recorded)
    sign = np.ones(a.collisions_dense.shape[-1])
    sign[[1, 3]] = -1  # x and vx (bbb.record.EVENT_FIELDS)
    assert np.array_equal(b.collisions_dense, a.collisions_dense * sign, equal_nan=True)
    for name in a.counters:
        assert np.array_equal(b.counters[name], a.counters[name]), name
    for name in a.contact_time:
        assert np.array_equal(b.contact_time[name], a.contact_time[name]), name


def test_on_a_tilted_floor_the_image_is_not_the_reflection():
    # the symmetry the estimators use is the floor's: with a tilt it is gone (fails if the
    # test above compared runs that ignore x's sign)
    p = Params.preset("klages2004", f=60.0, tilt=2.0)
    st = initial_state(p, 6, np.random.SeedSequence(3), "dropped")
    a, b = _run(p, st, 6), _run(p, mirrored(st), 6)
    assert not np.array_equal(b.positions, -a.positions)


@pytest.mark.parametrize("geometry", [{}, {"tilt": 2.0}, {"throw": 30.0}])
@pytest.mark.parametrize("family", ["rest", "dropped", "launched"])
def test_a_partner_is_the_same_draw_at_minus_d_and_a_member_of_its_family(family, geometry):
    p = Params.preset("klages2004", f=70.0, **geometry)
    seed = np.random.SeedSequence(11)
    st = mirror_pairs(p, 8, seed, family)
    half = initial_state(p, 4, seed, family)
    first, second = slice(0, 4), slice(4, 8)
    for k in ("cell", "d", "y", "vx", "vy", "s", "stuck", "from_surface"):
        assert np.array_equal(getattr(st, k)[first], getattr(half, k)), k
    assert np.array_equal(st.d[second], -half.d)
    # a family member: the family's velocity at its floor phase, whatever d is (on a thrown
    # floor the reflected -vx of 'rest'/'launched' would not be: those two cases fail then)
    assert np.array_equal(st.vx[second], half.vx) and np.array_equal(st.vy[second], half.vy)
    assert np.array_equal(st.y[second], half.y)  # the arcs are even in d
    if p.floor_frame()[2] == 0.0:  # vibrated normal to the plane: the partner is the image
        img = mirrored(half)
        assert np.array_equal(st.vx[second], img.vx) and np.array_equal(st.d[second], img.d)


def test_pair_units_label_each_chunks_halves_alike():
    u = mirror_pair_units(12, 6)
    assert u.tolist() == [0, 1, 2, 0, 1, 2, 3, 4, 5, 3, 4, 5]
    with pytest.raises(ValueError, match="even chunk size"):
        mirror_pair_units(10, 5)
    with pytest.raises(ValueError, match="even number"):
        mirror_pairs(Params.preset("klages2004", f=60.0), 5, np.random.SeedSequence(1), "rest")
