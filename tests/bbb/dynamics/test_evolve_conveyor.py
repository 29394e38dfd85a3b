"""The conveyor map (bbb.conveyor) in a cusp: a carried particle there rests against both arcs
and lifts off only when both let go (docs/physics.md, "Transport")."""

from __future__ import annotations

import math

import numpy as np

from bbb import Params, simulate
from bbb.ensemble import InitialState
from tests.bbb.trajectory_check import check_particle, start_event

S = 2.0


def at_rest_in_the_cusp(p: Params, side: float) -> InitialState:
    """One particle carried by the floor at the cusp x = side·S/2, floor phase 0."""
    depth = p.R - math.sqrt(p.R**2 - (S / 2) ** 2)
    one = np.ones(1)
    return InitialState(cell=np.zeros(1, np.int64), d=side * S / 2 * one, y=-depth * one,
                        vx=0.0 * one, vy=0.0 * one, s=0.0 * one, stuck=np.ones(1, bool),
                        from_surface=np.ones(1, bool))


def both_let_go(p: Params, side: float) -> float:
    """The first floor phase (in periods, on a grid of 1e-7) at which the normal loads of both
    arcs at the cusp, n·(a_floor + g), are negative: an independent scan of the model."""
    phi, psi, w = math.radians(p.tilt), math.radians(p.throw), 2 * math.pi * p.f
    th = np.arange(0.0, 1.0, 1e-7) * 2 * math.pi
    fx = p.A * math.cos(psi) * w**2 * np.sin(th) + p.g * math.sin(phi)
    fy = p.A * math.sin(psi) * w**2 * np.sin(th) + p.g * math.cos(phi)
    loads = []
    for e in (side * S / 2, -side * S / 2):  # the arc's own cusp offset, its neighbour's
        nx, ny = e / p.R, math.sqrt(p.R**2 - e**2) / p.R
        loads.append(nx * fx + ny * fy)
    both = (loads[0] < 0) & (loads[1] < 0)
    return th[np.argmax(both)] / (2 * math.pi) if both.any() else math.nan


def run_from_the_cusp(throw: float, tilt: float, side: float):
    p = Params(g=9800.0, A=1.0, f=53.0, R=1.5, S=S, alpha=0.25, beta=0.0, tilt=tilt, throw=throw)
    st = at_rest_in_the_cusp(p, side)
    run = simulate(p, 1, 5.0 / p.f, seed=0, initial=st, record_collisions=400, record_liftoffs=True,
                   sample_times=np.linspace(0.0, 5.0 / p.f, 11))
    return p, st, run


def test_a_particle_in_a_cusp_lifts_off_when_both_arcs_let_go():
    for side in (1.0, -1.0):
        p, st, run = run_from_the_cusp(throw=60.0, tilt=5.0, side=side)
        rows = run.collisions_dense[0, : run.n_recorded[0]]
        assert rows[0, 6] == 1.0  # the first event is the lift-off, from where it rested
        assert abs(rows[0, 5] - both_let_go(p, side)) < 2e-7
        start = start_event(p, st.cell[0], st.d[0], st.y[0], st.vx[0], st.vy[0], st.s[0], st.stuck[0])
        rep = check_particle(p, np.vstack([start, rows]))
        assert rep.carried > 0 and rep.failures["liftoff_time"] == 0, rep.messages


def test_a_particle_in_a_cusp_shaken_sideways_stays_where_both_arcs_never_let_go():
    # ψ = 10°: at every phase one wall presses (its load ≥ 0), and the stick model's infinite
    # friction holds the particle there: carried with the floor to the end of the run
    p, st, run = run_from_the_cusp(throw=10.0, tilt=0.0, side=1.0)
    assert math.isnan(both_let_go(p, 1.0)) and run.counters["liftoffs"][0] == 0
    x = run.positions[0]
    w = 2 * math.pi * p.f
    t = run.sample_times
    assert np.allclose(x, S / 2 - p.A * math.cos(math.radians(p.throw)) * np.sin(w * t), atol=1e-12)
