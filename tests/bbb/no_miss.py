"""The no-miss assertion the hypothesis tests share: a run checked by the independent
trajectory checker (tests/bbb/trajectory_check.py) and by the brute-force gap grid
(tests/bbb/flight_check.py), from each particle's initial state on."""

from __future__ import annotations

import numpy as np

from bbb import Params
from bbb.ensemble import InitialState
from tests.bbb.flight_check import gap_along_flights, on_surface_tolerance
from tests.bbb.trajectory_check import check_particle, start_event


def assert_no_miss(p: Params, st: InitialState, run, tolerated: tuple[str, ...] = ()) -> None:
    """Every particle: recorded values finite; the checker flags nothing but the kinds in
    ``tolerated``; no brute-forced flight point below the surface (mm, beyond
    :func:`on_surface_tolerance`); the kernel counted no anomaly."""
    for i in range(run.n_particles):
        rows = run.collisions_dense[i, : run.n_recorded[i]]
        assert np.all(np.isfinite(rows))
        start = start_event(p, st.cell[i], st.d[i], st.y[i], st.vx[i], st.vy[i], st.s[i], st.stuck[i])
        rep = check_particle(p, np.vstack([start, rows]))
        failed = {k: v for k, v in rep.failures.items() if v and k not in tolerated}
        assert not failed, rep.messages
        worst, _ = gap_along_flights(p, rows, n_grid=200)
        assert worst > -on_surface_tolerance(p)
    assert run.counters["anomalies"].sum() == 0
