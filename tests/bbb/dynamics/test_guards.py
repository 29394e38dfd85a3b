"""The kernel's guards against endless loops (bbb.kernel's event budget, bbb.contact's step
budget of a contact stretch): an input that would loop stops with an error naming it, and the
budgets lie far above what the project's inputs need (benchmarks/guards.py, committed)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from bbb import Numerics, Params, simulate
from bbb.dynamics.events import EVENT_BUDGET, STOP_STEPS
from bbb.dynamics.slide import BUDGET, PAYBACK, STRETCH_BUDGET, slide
from bbb.ensemble import InitialState
from bbb.simulate import _raise_on_guard

#: the measured worst cases (benchmarks/guards.py --json), and how far above them a budget
#: must lie: two orders of magnitude, so that no input of the project comes near a guard
MEASURED = Path(__file__).resolve().parents[3] / "benchmarks" / "results" / "guards-2026-11-25.json"
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
    out = slide(0.01, math.nan, 0.0, 0, 0.0, 1.0 / 60.0, 9800.0, 0.1, 2 * math.pi * 60.0, 15.0,
                2.0, 0.3, False, 1.0, np.zeros(0), np.zeros(0), 0, 0, 1e-12, None)
    assert out[6] == BUDGET and out[8] > STRETCH_BUDGET
    assert out[7] < 2.0 * STRETCH_BUDGET * 1e-12


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
