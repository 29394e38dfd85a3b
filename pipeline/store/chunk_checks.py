"""The checks of one done chunk's data (``bbb verify``, :mod:`pipeline.store.verify`): is each
particle's record what a sound run of the kernel could have written?

- ``positions`` finite, starting inside the first cell (|x(0)| <= S/2, mm; on a thrown floor
  the cell rides on the floor, so x(0) may be off by its along-plane amplitude |A_x|);
- ``n_recorded`` within [0, record]; ``collisions`` finite in the first ``n_recorded`` rows and
  NaN after them; each recorded collision at record_from <= t <= t_max (s), floor phase in
  [0, 1], times non-decreasing, and on the floor surface y = -A sin(2 pi phase) - c(d) (mm)
  of the stored parameters, within :data:`ON_SURFACE_MM`;
- counters >= 0, n_recorded <= n_collisions, n_anomalies = 0 (bbb repairs no velocity in a
  sound run); ``held_time``, ``sliding_time`` finite, >= 0, together at most t_max;
- ``chunk_seconds`` finite and >= 0; and every chunk file of the chunk readable.

Each check yields (array, what is wrong); :mod:`pipeline.store.verify` names the chunk.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

import numpy as np
import zarr

from bbb.params import Params
from bbb.surface import cell_of, floor_depth

from ..workflow.observables.counters import COUNTERS
from ..workflow.study import Study

__all__ = ["chunk_problems", "ON_SURFACE_MM"]

#: A recorded collision further than this from the floor surface is an inconsistency, mm.
#: Rounding puts a sound collision within ~1e-9 mm of it (benchmarks/checks/soak.py: none beyond
#: that in 5e8 checked rows); the faults looked for here (a value written below the surface,
#: a chunk of another run or of garbage) are orders of magnitude larger.
ON_SURFACE_MM = 1e-6


def chunk_problems(g: zarr.Group, study: Study, fi: int, mi: int, ci: int,
                   params_at: Callable[[int], Params]) -> Iterator[tuple[str, str]]:
    """What is wrong with the data of chunk ci of (point fi, family mi), as (array, what);
    ``params_at(fi)``: the Params the point's data were made with."""
    acc, obs = study.accuracy, study.observables
    cs = acc.chunk_size
    sl = slice(ci * cs, (ci + 1) * cs)
    p = params_at(fi)
    data: dict[str, np.ndarray] = {}
    names = ["chunk_seconds", *(f"n_{c}" for c in COUNTERS)]
    names += ["positions"] if obs.positions else []
    names += ["n_recorded", "collisions"] if obs.collisions else []
    names += ["held_time", "sliding_time"] if obs.contact else []
    for name in names:
        try:
            data[name] = np.asarray(g[name][fi, mi, ci] if name == "chunk_seconds"
                                    else g[name][fi, mi, sl])
        except Exception as e:  # a torn or foreign chunk file
            yield name, f"unreadable ({type(e).__name__}: {e})"

    sec = data.get("chunk_seconds")
    if sec is not None and not (math.isfinite(float(sec)) and float(sec) >= 0):
        yield "chunk_seconds", f"{float(sec)!r}; allowed: finite, >= 0 s"
    for c in COUNTERS:
        n = data.get(f"n_{c}")
        if n is not None and (n < 0).any():
            i = int(np.argmax(n < 0))
            yield f"n_{c}", f"{int((n < 0).sum())} negative counts (particle {ci * cs + i}: {n[i]})"
    anomalies = data.get("n_anomalies")
    if anomalies is not None and (anomalies > 0).any():
        i = int(np.argmax(anomalies > 0))
        yield "n_anomalies", (f"{int((anomalies > 0).sum())} particles with repaired velocities "
                              f"(particle {ci * cs + i}: {anomalies[i]}); allowed: 0")

    x = data.get("positions")
    if x is not None:
        bad = ~np.isfinite(x)
        if bad.any():
            i, k = np.argwhere(bad)[0]
            yield "positions", (f"{int(bad.sum())} non-finite values (first: particle "
                                f"{ci * cs + i}, t = {study.sample_times()[k]:g} s: {float(x[i, k])!r})")
        x0 = x[:, 0]
        # a thrown floor starts displaced along its plane by up to its amplitude there
        shift = abs(p.floor_frame()[2]) if p.transport else 0.0
        out = np.isfinite(x0) & (np.abs(x0) > 0.5 * p.S + shift)
        if out.any():
            i = int(np.argmax(out))
            allowed = (f"S/2 = {0.5 * p.S:g} mm" if not shift else
                       f"S/2 + |A_x| = {0.5 * p.S + shift:g} mm (the thrown floor's offset)")
            yield "positions", (f"{int(out.sum())} particles start outside the first cell "
                                f"(particle {ci * cs + i}: x(0) = {float(x0[i])!r} mm); allowed: "
                                f"|x(0)| <= {allowed}")

    yield from _contact_problems(data, acc.t_max, ci * cs)
    nrec = data.get("n_recorded")
    rows = data.get("collisions")
    if nrec is not None:
        K = obs.collisions_record
        wrong = (nrec < 0) | (nrec > K)
        if wrong.any():
            i = int(np.argmax(wrong))
            yield "n_recorded", (f"{int(wrong.sum())} out of range (particle {ci * cs + i}: "
                                 f"{nrec[i]}); allowed: 0 <= n_recorded <= record = {K}")
        ncoll = data.get("n_collisions")
        if ncoll is not None and (nrec > ncoll).any():
            i = int(np.argmax(nrec > ncoll))
            yield "n_recorded", (f"exceeds n_collisions for {int((nrec > ncoll).sum())} particles "
                                 f"(particle {ci * cs + i}: {nrec[i]} > {ncoll[i]})")
        if rows is not None and not wrong.any():
            yield from _collision_problems(rows, nrec, p, study, ci * cs)


def _contact_problems(data: dict[str, np.ndarray], t_max: float, first: int
                      ) -> Iterator[tuple[str, str]]:
    """held_time, sliding_time (s) of one chunk: finite, >= 0, together at most t_max."""
    held, sliding = data.get("held_time"), data.get("sliding_time")
    for name, t in (("held_time", held), ("sliding_time", sliding)):
        if t is not None and not (np.isfinite(t) & (t >= 0)).all():
            i = int(np.argmax(~(np.isfinite(t) & (t >= 0))))
            yield name, f"particle {first + i}: {float(t[i])!r}; allowed: finite, >= 0 s"
    if held is not None and sliding is not None:
        over = held + sliding > t_max * (1 + 1e-9)
        if over.any():
            i = int(np.argmax(over))
            yield "held_time", (f"held + sliding exceeds t_max = {t_max:g} s for "
                                f"{int(over.sum())} particles (particle {first + i}: "
                                f"{float(held[i] + sliding[i])!r} s)")


def _collision_problems(rows: np.ndarray, nrec: np.ndarray, p, study: Study, first: int
                        ) -> Iterator[tuple[str, str]]:
    """rows (particle, collision, field) of one chunk, n_recorded (particle,)."""
    from bbb.record import COLLISION_FIELDS

    col = {name: i for i, name in enumerate(COLLISION_FIELDS)}
    valid = np.arange(rows.shape[1])[None, :] < nrec[:, None]
    finite = np.isfinite(rows).all(axis=2)
    nan_pad = np.isnan(rows).all(axis=2)

    def first_of(mask) -> str:
        i, k = np.argwhere(mask)[0]
        return f"particle {first + i}, collision {k}"

    bad = valid & ~finite
    if bad.any():
        yield "collisions", (f"{int(bad.sum())} recorded rows with non-finite values "
                             f"(first: {first_of(bad)}), within n_recorded")
    bad = ~valid & ~nan_pad
    if bad.any():
        yield "collisions", (f"{int(bad.sum())} rows beyond n_recorded are not NaN padding "
                             f"(first: {first_of(bad)})")
    ok = valid & finite
    if not ok.any():
        return
    t, x, y, ph = (rows[..., col[k]] for k in ("t", "x", "y", "phase"))
    acc, obs = study.accuracy, study.observables
    bad = ok & ((t < obs.collisions_from) | (t > acc.t_max))
    if bad.any():
        yield "collisions", (f"{int(bad.sum())} collisions outside record_from <= t <= t_max = "
                             f"[{obs.collisions_from:g}, {acc.t_max:g}] s (first: "
                             f"{first_of(bad)}: t = {float(t[tuple(np.argwhere(bad)[0])])!r} s)")
    back = np.zeros_like(ok)
    back[:, 1:] = ok[:, 1:] & ok[:, :-1] & (np.diff(t, axis=1) < 0)
    if back.any():
        yield "collisions", (f"{int(back.sum())} times run backwards (first: {first_of(back)})")
    bad = ok & ((ph < 0) | (ph > 1))
    if bad.any():
        yield "collisions", (f"{int(bad.sum())} floor phases outside [0, 1] "
                             f"(first: {first_of(bad)})")
    _, d = cell_of(np.where(ok, x, 0.0), p.S)
    surface = -p.A * np.sin(2 * np.pi * np.where(ok, ph, 0.0)) - floor_depth(p, d)
    gap = np.where(ok, y - surface, 0.0)
    bad = np.abs(gap) > ON_SURFACE_MM
    if bad.any():
        i, k = np.argwhere(bad)[0]
        below = int((gap < -ON_SURFACE_MM).sum())
        yield "collisions", (f"{int(bad.sum())} collisions off the floor surface by more than "
                             f"{ON_SURFACE_MM:g} mm ({below} below it; first: particle {first + i}, "
                             f"collision {k}: y = {y[i, k]:.9g} mm, surface {surface[i, k]:.9g} mm "
                             f"at x = {x[i, k]:.9g} mm, phase {ph[i, k]:.6g})")
