"""bbb.analysis.states: each label returned on a recording whose answer is known (synthetic rows
built from the orbit's definition, and one kernel run on the flat floor's 1/1 orbit), and a
perturbed recording that must lose its label; thresholds from the committed calibration."""

import math

import numpy as np
import pytest

from bbb import Params
from bbb.analysis import states as st
from bbb.analysis.period1 import frequency_at, gamma_1, gamma_prime

F, A, S, G = 45.0, 0.1, 2.0, 9800.0
T_MAX, WINDOW = 4.0, 0.5
RULE = st.calibrated_rule()


def rows(t, x, vx, vy, phase, R=None):
    """(1, R, 6) recording of one particle from the given columns, NaN-padded."""
    n = len(t)
    R = n + 5 if R is None else R
    rec = np.full((1, R, 6), np.nan)
    rec[0, :n] = np.stack([t, x, np.zeros(n), vx, vy, phase], axis=1)
    return rec, np.array([min(n, R)])


def orbit(periods_per_cycle=1, vys=(94.0,), phases=(0.66,), x=0.3, noise=0.0, seed=1):
    """A recording that repeats (vy, phase) every len(vys) collisions, one collision every
    ``periods_per_cycle / len(vys)`` floor periods on average, for T_MAX s."""
    k = len(vys)
    n = int(T_MAX * F * k / periods_per_cycle)
    t = (np.arange(n) * periods_per_cycle / k + 0.1) / F
    rng = np.random.default_rng(seed)
    vy = np.array([vys[i % k] for i in range(n)]) + noise * A * 2 * math.pi * F * rng.standard_normal(n)
    ph = np.array([phases[i % k] for i in range(n)])
    return rows(t, np.full(n, x), np.zeros(n), vy, ph)


def labels(rec, n):
    lab, per, _ = st.classify(rec, n, T_MAX, WINDOW, F, A, S, RULE)
    return lab[0], per[0]


def test_calibration_fixed_thresholds_in_their_gaps():
    # the rule file says where it comes from and its thresholds lie in the calibrated gaps
    rule = st.calibrated_rule()
    assert 1e-14 < rule["lock_tol"] < 1e-3
    assert 0.0 < rule["stick_speed"] < 1e-3  # below the kernel's v_stick (1e-3 mm/s)
    assert 0.35 < rule["creep_share"] < 0.99


def test_one_one_orbit_is_locked_1():
    lab, per = labels(*orbit())
    assert (lab == st.LOCKED_1).all() and (per == 1).all()


def test_perturbed_one_one_orbit_is_not_locked():
    # noise 100 × the tolerance (per A·2πf) on vy: no repetition within lock_tol
    lab, _ = labels(*orbit(noise=100 * RULE["lock_tol"]))
    assert not np.isin(lab, (st.LOCKED_1, st.LOCKED_K)).any()


def test_period_two_orbit_is_locked_k_with_cycle_two():
    lab, per = labels(*orbit(periods_per_cycle=2, vys=(68.0, 106.0), phases=(0.60, 0.72)))
    assert (lab == st.LOCKED_K).all() and (per == 2).all()


def test_one_collision_every_two_periods_is_locked_k_not_1_1():
    lab, per = labels(*orbit(periods_per_cycle=2))
    assert (lab == st.LOCKED_K).all() and (per == 2).all()


def test_no_collision_is_stuck():
    rec = np.full((1, 10, 6), np.nan)
    lab, _ = labels(rec, np.array([0]))
    assert (lab == st.STUCK).all()


def test_landing_at_rest_each_period_is_creeping():
    # 5 collisions a period, the last at rest relative to the floor (vy = floor velocity)
    n_per, periods = 5, int(T_MAX * F)
    t = (np.repeat(np.arange(periods), n_per) + np.tile(np.linspace(0.2, 0.4, n_per), periods)) / F
    ph = (t * F) % 1.0
    vf = -A * 2 * math.pi * F * np.cos(2 * math.pi * ph)
    vy = vf + np.tile([8.0, 4.0, 2.0, 1.0, 0.0], periods)
    lab, _ = labels(*rows(t, np.full(t.size, 0.3), np.zeros(t.size), vy, ph))
    assert (lab == st.STUCK).all()


def test_landing_at_rest_perturbed_above_stick_speed_is_not_creeping():
    # the same rows with the rest landing 10 × stick_speed off: never at rest, never stuck
    n_per, periods = 5, int(T_MAX * F)
    t = (np.repeat(np.arange(periods), n_per) + np.tile(np.linspace(0.2, 0.4, n_per), periods)) / F
    ph = (t * F) % 1.0
    vf = -A * 2 * math.pi * F * np.cos(2 * math.pi * ph)
    vy = vf + np.tile([8.0, 4.0, 2.0, 1.0, 10 * RULE["stick_speed"]], periods)
    lab, _ = labels(*rows(t, np.full(t.size, 0.3), np.zeros(t.size), vy, ph))
    assert not (lab == st.STUCK).any()


def irregular(x_step):
    rng = np.random.default_rng(3)
    n = int(T_MAX * F)
    t = (np.arange(n) + rng.uniform(0.1, 0.9, n)) / F
    x = 0.2 + x_step * np.arange(n)
    return rows(t, x, rng.normal(0, 30, n), rng.uniform(50, 120, n), (t * F) % 1.0)


def test_irregular_within_one_arc_is_chaotic():
    lab, _ = labels(*irregular(0.0))
    assert (lab == st.CHAOTIC).all()


def test_irregular_crossing_arcs_is_diffusing():
    lab, _ = labels(*irregular(0.2))  # a cell (2 mm) every 10 collisions
    assert (lab == st.DIFFUSING).all()


def test_recording_used_up_is_unknown_after_its_end():
    rec, _ = orbit()
    R = 90  # 2 s of one collision a period at 45 Hz
    lab, _ = labels(rec[:, :R], np.array([R]))
    last = rec[0, R - 1, 0]
    covered = (np.arange(lab.size) + 1) * WINDOW <= last
    assert (lab[~covered] == st.UNKNOWN).all() and (lab[covered] == st.LOCKED_1).all()


def test_settle_time_is_the_start_of_the_final_absorbing_stretch():
    lab = np.array([[st.CHAOTIC, st.LOCKED_1, st.CHAOTIC, st.LOCKED_1, st.LOCKED_1],
                    [st.CHAOTIC] * 5, [st.STUCK] * 5], np.int8)
    out = st.settle_time(lab, 0.5)
    assert out[0] == 1.5 and math.isnan(out[1]) and out[2] == 0.0


def test_kernel_on_the_flat_floor_1_1_orbit_is_locked_1():
    # between Γ₁ and Γ′ on the flat floor, a particle started on the stable 1/1 orbit
    from bbb.ensemble import InitialState
    from bbb.simulate import simulate

    p = Params.preset("klages2004", f=F, floor="flat")
    assert frequency_at(gamma_1(0.7), A, G) < F < frequency_at(gamma_prime(0.7), A, G)
    V = p.g * (1 - p.alpha) / (2 * F * (1 + p.alpha))
    th = 2 * math.pi - math.acos(-V / (p.A * p.omega))
    s, y = th / p.omega, -p.A * math.sin(th)
    one = np.ones(2)
    init = InitialState(np.zeros(2, np.int64), 0.3 * one, y * one, 0 * one, p.g / (2 * F) * one,
                        s * one, np.zeros(2, bool), np.ones(2, bool))
    run = simulate(p, 2, T_MAX, 1, init, record_collisions=400)
    lab, per, _ = st.classify(run.collisions_dense, run.n_recorded, T_MAX, WINDOW, F, A, S, RULE)
    assert (lab == st.LOCKED_1).all()


def test_empty_recording_is_refused():
    with pytest.raises(ValueError, match="at least one row"):
        st.classify(np.zeros((1, 0, 6)), np.array([0]), T_MAX, WINDOW, F, A, S, RULE)
