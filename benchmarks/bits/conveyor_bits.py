"""Does the conveyor floor (tilted and thrown, bbb's conveyor kernel) give the same bits as another bbb?

    .venv/bin/python -m benchmarks.bits.conveyor_bits --baseline main [--particles 8] [--t-max 4]

The twin of benchmarks/bits/paper_floor_bits.py for the conveyor: the bbb package of git revision
REF (``git archive``) and this checkout, in fresh processes with their own numba caches, run
the same seeded ensembles under stick, slide and Coulomb contact on tilted, thrown, tilted-and-
thrown and flat conveyors (and the paper's floor forced through the conveyor kernel), and hash
positions, recorded events (lift-offs and contact events included), counters and contact
times; the rows that differ are printed.  Commit the output under benchmarks/results/.
"""

from __future__ import annotations

from benchmarks.bits.paper_floor_bits import PREAMBLE, cli

SNIPPET = PREAMBLE + """
FLOORS = ((0.0, 60.0, 15.0), (5.0, 90.0, 15.0), (5.0, 60.0, 15.0), (-8.0, 110.0, 15.0),
          (3.0, 75.0, 1.1), (2.0, 70.0, float("inf")), (0.0, 90.0, 15.0))
for contact, mu in (("stick", 0.0), ("slide", 0.0), ("coulomb", 0.05), ("coulomb", 0.3)):
    for tilt, throw, R in FLOORS:
        for f in (50.0, 60.0, 80.0):
            for fam in ("rest", "launched"):
                p = Params.preset("klages2004", f=f, contact=contact, mu=mu, tilt=tilt,
                                  throw=throw, R=R)
                r = simulate(p, n, t_max, seed=int(f * 7), initial=fam, sample_times=SAMPLES,
                             record_collisions=500, record_liftoffs=True, _force_conveyor=True)
                print(contact, mu, tilt, throw, R, f, fam, digest(r))
"""


if __name__ == "__main__":
    cli(__doc__, "conveyor floor", SNIPPET, 8, 4.0,
        "contact mu tilt throw R f family hash collisions")
