"""The kernel's guards against endless loops (bbb.kernel's event budget, bbb.contact's step
budget of a contact stretch): an input that would loop stops with an error naming it, and the
budgets lie far above what the project's inputs need (benchmarks/calibrations/guards.py, committed)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from bbb import Numerics, Params, simulate
from bbb.dynamics.events import EVENT_BUDGET, SEARCH_BURST, SEARCH_RATE, STOP_OK, STOP_SEARCH, STOP_STEPS
from bbb.dynamics.evolve import evolve_ensemble
from bbb.dynamics.options import Floor, Run
from bbb.dynamics.slide import BUDGET, PAYBACK, STRETCH_BUDGET, Stretch, slide
from bbb.ensemble import InitialState, initial_state
from bbb.simulate import _raise_on_guard

#: the measured worst cases (benchmarks/calibrations/guards.py --json), and how far above them a budget
#: must lie: two orders of magnitude, so that no input of the project comes near a guard
MEASURED = Path(__file__).resolve().parents[3] / "benchmarks" / "results" / "guards-2026-11-28-search.json"
MARGIN = 100.0


def one(value, dtype=float):
    return np.full(1, value, dtype=dtype)


def at_the_vertical_cusp(alpha: float) -> tuple[Params, InitialState]:
    """The paper's floor with vertical cusp walls (R = S/2), a particle on the cusp point
    leaving it sideways at 10 mm/s (relative to the floor, which moves vertically)."""
    p = Params(g=9800.0, A=0.1, f=60.0, R=1.0, S=2.0, alpha=alpha, beta=0.0)
    s0 = 0.001
    y = -p.A * math.sin(p.omega * s0) - p.R
    vy = -p.A * p.omega * math.cos(p.omega * s0)
    return p, InitialState(one(0, np.int64), one(1.0), one(y), one(10.0), one(vy), one(s0),
                           one(False, bool), one(True, bool))


def test_a_zero_time_ping_pong_in_a_vertical_cusp_stops_with_an_error_naming_the_input():
    """At the cusp point of R = S/2 the walls are vertical and meet: a particle moving
    sideways hits the facing wall at once, is reflected (α = 1: undiminished) into the other
    wall at once, and so on at the same instant for ever — the default (stick) kernel on the
    paper's floor looped without end here (no result after 55 s; with α < 1 the sequence is
    finite but ~ln(u/v_stick)/(1 − α) collisions long).  The event guard stops it."""
    p, st = at_the_vertical_cusp(alpha=1.0)
    with pytest.raises(RuntimeError, match=r"guard stopped particle 0 of 1 at t = 0 s: more than "
                       r"1048576 events within .*'R': 1\.0, 'S': 2\.0, 'alpha': 1\.0"):
        simulate(p, 1, 0.05, seed=0, initial=st)


def test_a_particle_leaving_the_vertical_cusp_upwards_is_not_stopped():
    # the contrast: the same place, leaving straight up (along both walls) is an ordinary flight
    p, st = at_the_vertical_cusp(alpha=1.0)
    st = InitialState(st.cell, st.d, st.y, one(0.0), st.vy + 50.0, st.s, st.stuck, st.from_surface)
    run = simulate(p, 1, 0.05, seed=0, initial=st)
    assert run.counters["collisions"][0] >= 1


def test_a_contact_stretch_that_makes_no_progress_ends_with_the_budget_event():
    """bbb.dynamics.slide.slide from a state on which no step can be certified (here a non-finite
    speed, which only a fault upstream could hand it) would step at tol_t for ever: the step
    debt passes STRETCH_BUDGET and the stretch ends with BUDGET, having covered only
    ~STRETCH_BUDGET × tol_t of its 1 s."""
    fl = Floor(9800.0, 0.1, 2 * math.pi * 60.0, 15.0, 2.0, 0.8, 1.0)
    run = Run(1.0, 0.0, 1e-12, 1e-3, 1.0)
    _, event, (elapsed, worst) = slide(Stretch(0.01, math.nan, 0.0, 0, 0, 0), 0.0, fl, None, 0.3,
                                       run, (np.zeros(0), np.zeros(0)))
    assert event == BUDGET and worst > STRETCH_BUDGET
    assert elapsed < 2.0 * STRETCH_BUDGET * 1e-12


def test_the_step_budget_error_names_the_input():
    status = np.zeros((3, 4))
    status[1] = (STOP_STEPS, STRETCH_BUDGET + 1.0, 3.0, 0.25)
    p = Params.preset("klages2004", f=55.0, tilt=3.0, throw=60.0, contact="coulomb", mu=0.3)
    with pytest.raises(RuntimeError, match=r"particle 1 of 3 at t = 0\.25 s: a contact stretch ran a "
                       rf"step debt above {re.escape(f'{STRETCH_BUDGET:g}')} .* beyond {PAYBACK:g} per "
                       r"nominal step.*'tilt': 3\.0, 'throw': 60\.0, 'contact': 'coulomb', 'mu': 0\.3"):
        _raise_on_guard(status, p, Numerics(), np.random.SeedSequence(7), "rest")


def test_the_budgets_lie_two_orders_of_magnitude_above_the_measured_worst_cases():
    m = json.loads(MEASURED.read_text())
    assert m["max_debt"] > 0 and m["max_events"] > 0  # measured, not a placeholder
    assert STRETCH_BUDGET >= MARGIN * m["max_debt"]
    assert EVENT_BUDGET >= MARGIN * m["max_events"]


def test_the_search_budget_lies_two_orders_of_magnitude_above_the_deepest_measured_draw():
    m = json.loads(MEASURED.read_text())
    assert m["max_search"] > 0  # measured, not a placeholder
    assert SEARCH_BURST >= MARGIN * m["max_search"]


def raw_run(p: Params, st: InitialState, t_max: float) -> np.ndarray:
    """The kernel on states that bbb.simulate would refuse (no validation): the status rows."""
    n = st.cell.shape[0]
    status = np.zeros((n, 5))
    evolve_ensemble((st.cell, st.d, st.y, st.vx, st.vy, st.s, st.stuck, st.from_surface),
                    Floor(p.g, p.A, p.omega, p.R, p.S, p.alpha, p.beta),
                    Run(t_max, 0.0, 1e-12, 1e-3, 0.25), None, None, np.zeros(0),
                    (np.zeros((n, 0)), np.zeros((n, 0, 6)), np.zeros((n, 5), np.int64),
                     np.zeros((n, 2)), status))
    return status


def with_state(st: InitialState, **values: float) -> InitialState:
    # bypasses InitialState's own checks: the kernel's last line of defence is under test
    out = InitialState(**{k: getattr(st, k).copy() for k in st.__dataclass_fields__})
    for k, v in values.items():
        getattr(out, k)[:] = v
    return out


@pytest.mark.parametrize("bad", [dict(d=math.nan), dict(vx=math.inf), dict(vx=1e300)])
def test_a_search_that_makes_no_progress_stops_on_the_search_budget(bad):
    """A NaN gap never certifies a step (the search crept on at tol_t: ~1e11 steps per flight)
    and vx = 1e300 crosses 1e300 arcs: before the budget such a state never returned.  The
    kernel stops it after SEARCH_BURST steps (its budget drawn down to below zero)."""
    p = Params.preset("klages2004", f=60.0)
    st = with_state(initial_state(p, 1, np.random.SeedSequence(1), "launched"), **bad)
    status = raw_run(p, st, 1.0)
    assert status[0, 0] == STOP_SEARCH and status[0, 4] == SEARCH_BURST + 1


def test_a_valid_state_draws_little_on_the_search_budget_and_is_not_stopped():
    p = Params.preset("klages2004", f=60.0)
    st = initial_state(p, 4, np.random.SeedSequence(1), "launched")
    status = raw_run(p, st, 2.0)
    assert np.all(status[:, 0] == STOP_OK) and 0 < status[:, 4].max() < SEARCH_BURST / 1000


def test_the_search_budget_is_topped_up_per_floor_period():
    """A long run takes more search steps in all than SEARCH_BURST holds (at least one per
    collision: each search crosses at least one arc) and is not stopped: the budget is
    earned back per floor period (~2.7e3 s of chatter at 56 Hz, ~1.6e3 collisions per s)."""
    p = Params.preset("klages2004", f=56.0)
    guards = np.zeros((1, 5))
    run = simulate(p, 1, 3000.0, seed=3, initial="rest", _guards=guards)
    assert run.counters["collisions"][0] > SEARCH_BURST
    assert guards[0, 0] == STOP_OK and guards[0, 4] < SEARCH_BURST / 1000


def test_the_search_budget_error_names_the_input():
    status = np.zeros((2, 5))
    status[1] = (STOP_SEARCH, 0.0, 1.0, 0.5, SEARCH_BURST + 1)
    p = Params.preset("klages2004", f=60.0)
    with pytest.raises(RuntimeError, match=rf"particle 1 of 2 at t = 0\.5 s: its collision searches "
                       rf"took more than {SEARCH_BURST} steps beyond {SEARCH_RATE} per floor period.*"
                       r"'f': 60\.0.*seed entropy 7"):
        _raise_on_guard(status, p, Numerics(), np.random.SeedSequence(7), "custom")
