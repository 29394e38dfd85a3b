"""D's confidence interval, one place for it: of a (point, family) from its first n chunks, of
a point's pooled families, and the drift v's of a point.

**One CI.**  :func:`row_intervals` is the only place D's CI of a (point, family) and of a
point's pooled families is computed: the stopping rule decides on it
(:mod:`pipeline.execute.waves`), `bbb reduce` reports it (columns D_<family>_lo/hi, and
D_lo/hi, which with a single family are the same interval), and refinement reads it.  So a
(point, family) that stopped as "target met" shows in the table the very half-width that met
the target.
"""

from __future__ import annotations

import numpy as np

from bbb.analysis.stats.interval import DInterval

from ..store.study_store import StudyStore
from ..workflow.identity import reduce_seed, stop_seed
from ..workflow.study import Study

__all__ = ["interval_of", "pair_units", "row_intervals", "unit_ci", "pooled_ci", "pooled_v"]


def interval_of(study: Study, x: np.ndarray, seed, units: np.ndarray | None = None
                ) -> DInterval | None:
    """D's CI (:class:`bbb.analysis.stats.interval.DInterval`, mm²/s) of positions x (particle, time)
    with the study's estimator, fit range, level, method and resamples, resampling the
    ``units`` (mirror pairs, :func:`pair_units`) when given; None below 2 particles."""
    from bbb.analysis import stats

    if x.shape[0] < 2:
        return None
    an = study.analysis
    T = an.duration(study.accuracy.t_max)
    return stats.bootstrap_D(x, study.sample_times(), n_resamples=study.accuracy.n_resamples,
                             ci=an.ci, seed=seed, method=an.ci_method, fit_from=an.fit_from * T,
                             fit_to=an.fit_to * T, discard=an.discard, detail=True, units=units)


def pair_units(study: Study, sizes: list[tuple[object, int]], point=None) -> np.ndarray | None:
    """The labels of the independent units of the particles of ``sizes`` = [(family, number
    of its particles), ...] pooled in that order: mirror pairs when every family holds them
    (:meth:`pipeline.workflow.study.Study.pairing` at ``point``, None: the scene without a
    grid; each chunk's second half partners its first half, bbb.ensemble.mirror_pairs), else
    None (particles are the units)."""
    from bbb.analysis.transport import PAIRS
    from bbb.ensemble import mirror_pair_units

    if not sizes or any(study.pairing(fam, point) != PAIRS for fam, _ in sizes):
        return None
    labels, offset = [], 0
    for _, n in sizes:
        labels.append(mirror_pair_units(n, study.accuracy.chunk_size) + offset)
        offset += n // 2
    return np.concatenate(labels)


def row_intervals(study: Study, fi: int, parts: dict[int, tuple[np.ndarray, int]]
                  ) -> tuple[dict[int, DInterval], DInterval | None]:
    """D's CIs at point index fi (the frequency index without a grid) from ``parts`` =
    {family index: (positions, chunks used)}: (per family with >= 2 particles, pooled).  A
    family's CI is seeded by :func:`stop_seed` with its chunk count, so it is the CI its last
    stopping decision read; the pooled CI is that same CI when one family has data, else the
    bootstrap of all pooled (seeded by the reduction's key)."""

    point = study.points[fi]
    f, at = point.f, point if study.grid else None
    fam = study.families
    fams = {mi: interval_of(study, x, stop_seed(study, f, fam[mi], n),
                            pair_units(study, [(fam[mi], x.shape[0])], at))
            for mi, (x, n) in parts.items() if x.shape[0] >= 2}
    if len(fams) == 1:
        return fams, next(iter(fams.values()))
    if not fams:
        return fams, None
    x = np.concatenate([parts[mi][0] for mi in fams])
    units = pair_units(study, [(fam[mi], parts[mi][0].shape[0]) for mi in fams], at)
    return fams, interval_of(study, x, reduce_seed(study, f), units)


def _as_ci(r: DInterval | None) -> tuple[float, float, float]:
    return (np.nan, np.nan, np.nan) if r is None else (r.D, r.lo, r.hi)


def unit_ci(store: StudyStore, fi: int, mi: int, n: int) -> tuple[float, float, float]:
    """(D, lo, hi), mm²/s, of (frequency fi, family mi) from its first n chunks (hi NaN when
    no particle moved: that leaves the unit open, :func:`pipeline.execute.adaptive.decide`)."""
    study = store.study
    first = np.arange(study.accuracy.n_chunks) < n
    x = store.read_done("positions", fi, mi, first)
    return _as_ci(row_intervals(study, fi, {mi: (x, n)})[0].get(mi))


def pooled_ci(store: StudyStore, fi: int, done: np.ndarray) -> tuple[float, float, float]:
    """(D, lo, hi) of all families pooled at frequency fi, as `bbb reduce` reports D_lo/hi."""
    study = store.study
    parts = {mi: (store.read_done("positions", fi, mi, done[fi, mi]), int(done[fi, mi].sum()))
             for mi in range(len(study.families))}
    return _as_ci(row_intervals(study, fi, parts)[1])


def pooled_v(store: StudyStore, fi: int, done: np.ndarray) -> tuple[float, float, float]:
    """(v, lo, hi), mm/s, of all families pooled at point fi: the drift and its CI as `bbb
    reduce` computes them (bbb.analysis.transport, seeded by the reduction's key)."""
    from bbb.analysis.transport import transport

    from ..workflow.identity import child_seed

    study = store.study
    point = study.points[fi]
    fams = [(fam, store.read_done("positions", fi, mi, done[fi, mi]))
            for mi, fam in enumerate(study.families)]
    fams = [(fam, x) for fam, x in fams if x.shape[0] >= 2]
    if not fams:
        return (np.nan, np.nan, np.nan)
    x = np.concatenate([x for _, x in fams])
    kinds = {study.pairing(fam, point) for fam, _ in fams}
    pairing = kinds.pop() if len(kinds) == 1 else "independent"
    units = pair_units(study, [(fam, x.shape[0]) for fam, x in fams], point)
    an = study.analysis
    T = an.duration(study.accuracy.t_max)
    t = transport(x, study.sample_times(), point.params.S, n_resamples=study.accuracy.n_resamples,
                  ci=an.ci, method=an.ci_method,
                  seed=child_seed(reduce_seed(study, point.f), "transport"),
                  pairing=pairing, units=units if pairing == "pairs" else None,
                  fit_from=an.fit_from * T, fit_to=an.fit_to * T, discard=an.discard)
    return (t.v, t.v_lo, t.v_hi)
