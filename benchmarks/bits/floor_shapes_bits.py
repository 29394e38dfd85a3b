"""Do the sine and sawtooth floors give the same bits as another bbb?

    .venv/bin/python -m benchmarks.bits.floor_shapes_bits --baseline REF [--particles 8] [--t-max 5]

The shapes' own side by side (benchmarks/bits/paper_floor_bits.py is the arcs'): the bbb of git
revision REF (``git archive``) and this checkout, in fresh processes with their own numba
caches, run the same seeded ensembles on sines and sawtooths of several depths (the sawtooth
also off-centre) at 48-90 Hz, from rest and launched, under the stick model (the one both
shapes run), hash positions, recorded events, counters and contact times, and print the rows
that differ.  Commit the output under benchmarks/results/.
"""

from __future__ import annotations

from benchmarks.bits.paper_floor_bits import PREAMBLE, cli

SNIPPET = PREAMBLE + """
SHAPES = (("sine", 0.1, 0.5), ("sine", 0.3, 0.5), ("sine", 0.6, 0.5), ("sawtooth", 0.1, 0.5),
          ("sawtooth", 0.3, 0.3), ("sawtooth", 0.6, 0.2))
for floor, depth, peak in SHAPES:
    for f in (48.0, 52.0, 56.0, 60.0, 70.0, 80.0, 90.0):
        for fam in ("rest", "launched"):
            kw = {"peak": peak} if floor == "sawtooth" else {}
            p = Params.preset("klages2004", f=f, floor=floor, depth=depth, **kw)
            r = simulate(p, n, t_max, seed=int(f * 7), initial=fam, sample_times=SAMPLES,
                         record_collisions=500, record_liftoffs=True)
            print(floor, depth, peak, f, fam, digest(r))
"""


if __name__ == "__main__":
    cli(__doc__, "floor shapes", SNIPPET, 8, 5.0,
        "floor depth peak f family hash collisions")
