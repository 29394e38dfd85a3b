"""Bit-for-bit check of a map line against the scene without a grid that shares its seed,
family and chunking: every chunk both stores computed holds the same positions.

    python -m benchmarks.bits.map_cut_bits [--runs runs]

Pairs: the α = 0.7 line of ``dissipation`` with ``figure2``, the α = 0.5 line of
``dissipation_r25`` with ``figure2_matyas2004``, the α = 0.7 line of ``dissipation_locking``
with ``locking`` (post-collision states).  A chunk's seed is (study seed, f, family, chunk),
never the grid a point sits in, so this is consistency, not a test of the physics: it says the
map's cut *is* the committed curve's ensemble where both ran it.  Prints one line per pair.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from pipeline.store.study_store import StudyStore

PAIRS = (("dissipation", 0.7, "figure2", "positions"),
         ("dissipation_r25", 0.5, "figure2_matyas2004", "positions"),
         ("dissipation_locking", 0.7, "locking", "collisions"))


def _index(study, f: float, alpha: float | None) -> int | None:
    for i, p in enumerate(study.points):
        g = dict(p.grid)
        if abs(p.f - f) < 1e-3 and (alpha is None or math.isclose(float(g["alpha"]), alpha)):
            return i
    return None


def compare(runs: Path, map_name: str, alpha: float, scene: str, array: str) -> str:
    a, b = StudyStore.open(str(runs / f"{map_name}.zarr")), StudyStore.open(str(runs / f"{scene}.zarr"))
    if a.study.accuracy.chunk_size != b.study.accuracy.chunk_size:
        return f"{map_name} α = {alpha} vs {scene}: chunk sizes differ, nothing shared"
    da, db = a.done(), b.done()
    fams_b = [fam.name for fam in b.study.families]
    freqs, chunks, same = 0, 0, 0
    for fi, p in enumerate(a.study.points):
        if not math.isclose(float(dict(p.grid)["alpha"]), alpha):
            continue
        fj = _index(b.study, p.f, None)
        if fj is None:
            continue
        freqs += 1
        for mi, fam in enumerate(a.study.families):
            mj = fams_b.index(fam.name)
            n = min(da.shape[2], db.shape[2])  # the caps may differ: the first n chunks
            both = np.flatnonzero(da[fi, mi, :n] & db[fj, mj, :n])
            for c in both:
                sl = a.chunk_particles(int(c))
                x = np.asarray(a.group()[array][fi, mi, sl])
                y = np.asarray(b.group()[array][fj, mj, sl])
                chunks += 1
                same += int(x.shape == y.shape and np.array_equal(x.view(np.uint8), y.view(np.uint8)))
    return (f"{map_name} α = {alpha} vs {scene}: {freqs} shared frequencies, {chunks} chunks "
            f"computed by both, {same} bit-identical ({array})")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", default="runs", type=Path)
    a = ap.parse_args()
    for pair in PAIRS:
        if all((a.runs / f"{n}.zarr").exists() for n in (pair[0], pair[2])):
            print(compare(a.runs, *pair), flush=True)
        else:
            print(f"{pair[0]} vs {pair[2]}: a store is missing", flush=True)


if __name__ == "__main__":
    main()
