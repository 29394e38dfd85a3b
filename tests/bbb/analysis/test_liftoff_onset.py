"""bbb.analysis.liftoff_onset: the lowest lift-off frequency, against Γ = 1 and against the kernel itself."""

import math

import numpy as np
import pytest

from bbb import Params, simulate
from bbb.analysis.liftoff_onset import liftoff_frequency


def test_a_flat_floor_vibrated_vertically_lets_go_at_gamma_one():
    p = Params.preset("klages2004", f=60.0, R=math.inf)
    assert liftoff_frequency(p) == pytest.approx(math.sqrt(p.g / p.A) / (2 * math.pi), rel=1e-15)


def test_an_oblique_throw_lets_go_where_its_normal_share_reaches_g():
    # flat floor, throw 30°: the normal amplitude is A sin 30° = A / 2
    p = Params.preset("klages2004", f=60.0, R=math.inf, throw=30.0)
    assert liftoff_frequency(p) == pytest.approx(math.sqrt(2 * p.g / p.A) / (2 * math.pi))


@pytest.mark.parametrize("geometry", [dict(throw=30.0), dict(tilt=5.0, throw=60.0)])
def test_stuck_particles_on_arcs_stay_below_it_and_some_lift_off_above(geometry):
    f0 = liftoff_frequency(Params.preset("klages2004", f=60.0, **geometry))
    times = np.array([0.0, 2.0])
    # 0.2 % below and 0.4 % above: a wrong sign of the throw's angle moves f0 by 0.6 % at
    # tilt 5°, throw 60°; ~6 % of the particles start where the floor lets go above f0
    below = simulate(Params.preset("klages2004", f=0.998 * f0, **geometry), 128, 2.0, 1, "rest",
                     sample_times=times)
    above = simulate(Params.preset("klages2004", f=1.004 * f0, **geometry), 128, 2.0, 1, "rest",
                     sample_times=times)
    assert below.counters["liftoffs"].sum() == 0
    assert above.counters["liftoffs"].sum() > 0
