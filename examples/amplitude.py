"""A = 0.01 (the paper's printed amplitude) versus A = 0.1 at f = 54 and 60 Hz.

    .venv/bin/python examples/amplitude.py

Do particles take off, and where do post-collision vertical velocities cluster?
Output recorded in docs/amplitude.md.
"""

import numpy as np

from bbb import Params, simulate

for A in (0.01, 0.1):
    for f in (54.0, 60.0):
        p = Params.preset("klages2004", f=f, A=A)
        for fam in ("rest", "launched"):
            run = simulate(p, 200, 20.0, seed=1, initial=fam, record_collisions=2000, record_from=10.0,
                           sample_times=np.array([0.0, 10.0, 20.0]))
            vy = run.collisions["vy"]
            moving = np.mean(run.positions[:, 2] != run.positions[:, 1])
            q = np.round(np.percentile(vy, [50, 90, 99]), 1) if vy.size else "-"
            peak = "-"
            if np.any(vy > 20):
                hist, edges = np.histogram(vy[vy > 20], bins=40)
                peak = f"{0.5 * (edges[hist.argmax()] + edges[hist.argmax() + 1]):.1f}"
            print(f"A={A} f={f} Gamma={p.gamma:.3f} {fam:9s} "
                  f"liftoffs/particle={run.counters['liftoffs'].mean():.1f} "
                  f"collisions after 10 s={vy.size} moving in 10-20 s={moving:.2f} "
                  f"vy+ median/90/99%={q} peak(vy+>20)={peak}")
