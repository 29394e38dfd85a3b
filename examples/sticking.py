"""Sensitivity of D to the sticking threshold v_stick near the onset (52-60 Hz).

    .venv/bin/python examples/sticking.py

200 particles, 60 s, D from the time-averaged MSD with a 95 % bootstrap CI.
Output recorded in docs/physics.md.
"""

import time

import numpy as np

from bbb import Numerics, Params, simulate
from bbb.analysis.stats import bootstrap_D

times = np.linspace(0, 60, 601)
for f in (52.0, 54.0, 55.0, 56.0, 57.0, 58.0, 60.0):
    for v_stick in (1e-1, 1e-3, 1e-5):
        for family in ("rest", "launched"):
            t0 = time.time()
            run = simulate(Params.preset("klages2004", f=f), 200, 60.0, seed=1, initial=family,
                           sample_times=times, numerics=Numerics(v_stick=v_stick))
            ci = bootstrap_D(run.positions, times, n_resamples=500, seed=0)
            print(f"f={f} v_stick={v_stick:g} {family:9s} D={ci.D:8.2f} [{ci.lo:8.2f},{ci.hi:8.2f}] "
                  f"coll={run.counters['collisions'].sum():.3g} sticks={run.counters['sticks'].sum()} "
                  f"wall={time.time() - t0:.1f}s", flush=True)
