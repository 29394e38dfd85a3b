"""The rules of adaptive studies, as pure functions: when a (frequency, family) has enough
particles, how many chunks its next wave adds, and which frequencies refinement adds.

No Dask and no store here: :mod:`pipeline.execute.run` feeds these rules the confidence interval of D
computed from the chunks done so far, and the tests feed them synthetic data.

**Waves** (``[accuracy] target_ci``).  A (frequency, family) starts with one chunk.  After a
wave, with the first ``n`` chunks all done, the rule looks at D and its CI from exactly those
chunks (in index order: never at whichever chunks happened to finish first) and either stops
or asks for the first ``n_next`` chunks:

* *target met*    (D > 0 and half-width hw <= target_ci * D),
* *resolved to ±d_resolved* (hw <= d_resolved: D is known to +-d_resolved; below onset D ~ 0,
  near onset, where the target is not met yet, D may be far above d_resolved),
* *cap*           (n reached max_particles / chunk_size),
* else ``n_next = min(2 n, cap, max(n + 1, ceil(n (hw / goal)^2)))`` with
  goal = max(target_ci * D, d_resolved): the 1/sqrt(N) law's prediction of the chunks that
  meet the target (docs/accuracy.md: hw ~ 1.6 D / sqrt(N)), at most doubling, because the
  half-width measured on few particles is itself uncertain and a wave too large is wasted,
  while one too small costs only one more wave.

hw is half the CI's width, (hi - lo) / 2, of the same bootstrap `bbb reduce` uses.  So the
chunks a (frequency, family) ends with are a function of its data only, and replaying the
rule on a store's done chunks (:func:`advance`) re-derives every decision of a run that was
interrupted.

**Refinement** (``[frequencies] refine``).  After every frequency has stopped,
:func:`refine_frequencies` adds, around each significant extremum of the pooled D(f)
(:func:`bbb.analysis.extrema.find_extrema`), the midpoints (on the 1 mHz grid) of the gaps to its
neighbours that are wider than ``to``; with ``jumps`` also the midpoints of wide gaps between
neighbours whose D differ significantly.  Repeated on the grown grid until nothing is added,
every extremum ends with neighbours at most ``to`` away on both sides; the frequencies added
are a function of the data at the frequencies before them, hence of the data only.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from statistics import NormalDist

import numpy as np

from bbb.analysis.extrema import Significance, critical_z, find_extrema

from ..store.layout import CAP, OPEN, STOP_LEGEND, TARGET, ZERO
from ..workflow.identity import f_key

__all__ = ["OPEN", "TARGET", "ZERO", "CAP", "STOP_LEGEND", "StoppingRule", "UnitState",
           "advance", "decide", "chunks_needed", "remaining", "wave_ends", "refine_frequencies", "split_gaps"]

#: the stop_reason codes and their legend are stored values: defined with the store's layout
#: (pipeline.store.layout) and importable from here as before

CI = tuple[float, float, float]  # (D, lo, hi), mm²/s


@dataclass(frozen=True)
class StoppingRule:
    """target_ci: relative half-width of D to reach; d_resolved: absolute half-width, mm²/s,
    at which D counts as resolved (None: off); cap: most chunks; first: chunks of wave 1.
    ``cap = first`` with target_ci = None is a fixed ensemble (one wave, never decided)."""

    target_ci: float | None
    d_resolved: float | None
    cap: int
    first: int = 1

    @classmethod
    def fixed(cls, n_chunks: int) -> StoppingRule:
        return cls(None, None, n_chunks, n_chunks)


def decide(rule: StoppingRule, n: int, ci: CI) -> tuple[int, int]:
    """After the first ``n`` chunks, with their (D, lo, hi): (reason, n_next).  A reason other
    than OPEN stops at n_next = n; OPEN asks for the first n_next > n chunks."""
    if rule.target_ci is None:
        return CAP, n  # a fixed ensemble: its one wave is all it gets
    D, lo, hi = ci
    hw = 0.5 * (hi - lo)
    if math.isfinite(D) and math.isfinite(hw):
        d = max(D, 0.0)
        if d > 0 and hw <= rule.target_ci * d:
            return TARGET, n
        if rule.d_resolved is not None and hw <= rule.d_resolved:
            return ZERO, n
    if n >= rule.cap:
        return CAP, n
    return OPEN, min(2 * n, rule.cap, max(n + 1, chunks_needed(rule, n, ci)))


def chunks_needed(rule: StoppingRule, n: int, ci: CI) -> int:
    """The 1/sqrt(N) law's prediction, from the first ``n`` chunks and their (D, lo, hi), of
    how many chunks in all meet the target (uncapped); 2 n when there is nothing to predict
    from (D <= 0 without d_resolved, or no CI yet)."""
    D, lo, hi = ci
    hw = 0.5 * (hi - lo)
    goal = max(rule.target_ci * max(D, 0.0) if math.isfinite(D) and rule.target_ci else 0.0,
               rule.d_resolved or 0.0)
    if goal > 0 and math.isfinite(hw):
        return max(n, math.ceil(n * (hw / goal) ** 2))
    return 2 * n


@dataclass
class UnitState:
    """Where one (frequency, family) stands: it wants the first ``n`` chunks; ``waves`` lists
    the n after each wave; ``reason`` is OPEN until it stops."""

    n: int
    waves: list[int] = field(default_factory=list)
    reason: int = OPEN
    #: the law's latest prediction of the chunks it ends with (capped; ``n`` until decided)
    need: int = 0


def advance(rule: StoppingRule, state: UnitState | None, n_done_prefix: int,
            ci_of: Callable[[int], CI]) -> UnitState:
    """Apply the rule as far as the done chunks allow: while the first ``state.n`` chunks are
    all done (``n_done_prefix``: how many leading chunks are done), decide from them.
    ``ci_of(n)`` is D's CI from the first n chunks.  ``state`` None starts from wave 1, so
    ``advance(rule, None, prefix, ci_of)`` replays every decision from scratch."""
    if state is None:
        state = UnitState(min(rule.first, rule.cap), [min(rule.first, rule.cap)])
    while state.reason == OPEN and state.n <= n_done_prefix:
        ci = ci_of(state.n)
        reason, n_next = decide(rule, state.n, ci)
        if reason != OPEN:
            state.reason = reason
            state.need = state.n
        else:
            state.need = min(rule.cap, max(n_next, chunks_needed(rule, state.n, ci)))
            state.n = n_next
            state.waves.append(n_next)
    return state


def remaining(states: Iterable[UnitState], n_done: Iterable[int]) -> tuple[int, int]:
    """(units still open, chunks they still need): for each open unit the law's latest
    prediction of its final chunk count (at least what its current wave asks for) less its
    ``n_done`` done chunks; what the waves' progress line shows."""
    units = chunks = 0
    for s, d in zip(states, n_done, strict=True):
        if s.reason == OPEN:
            units += 1
            chunks += max(s.n, s.need) - d
    return units, chunks


def predicted_waves(first: int, n_needed: int, cap: int) -> int:
    """Waves the rule takes when every half-width follows hw ~ 1/sqrt(N) exactly and the
    target needs ``n_needed`` chunks: doubling from ``first`` until the prediction is in
    reach, then one wave to it."""
    return len(wave_ends(first, n_needed, cap))


def wave_ends(first: int, n_needed: int, cap: int) -> list[int]:
    """The chunks wanted after each wave, under the same exact law as
    :func:`predicted_waves`: [first, 2 first, 4 first, ..., n_needed] (capped).  Wave k
    submits ``ends[k] - ends[k - 1]`` chunks once wave k - 1 is complete (waves.py); what
    ``bbb plan --workers`` simulates (pipeline/execute/scaling.py)."""
    n = min(first, cap)
    ends = [n]
    while n < min(n_needed, cap):
        n = min(2 * n, cap, max(n + 1, n_needed))
        ends.append(n)
    return ends


# -- refinement ---------------------------------------------------------------------------------
def refine_frequencies(f_mhz: Sequence[int], D: Sequence[float], lo: Sequence[float],
                       hi: Sequence[float], *, to: float, ci: float = 0.95, extrema: bool = True,
                       jumps: bool = False, alpha: float = 0.05) -> list[int]:
    """Frequencies (mHz, sorted) to add to the grid ``f_mhz`` with pooled D and its CI
    [lo, hi] (mm²/s) at level ``ci``: the midpoints of the gaps wider than ``to`` (Hz) next
    to every significant extremum (and, with ``jumps``, between significantly different
    neighbours).  NaN rows (no data) are left out.  Empty: the grid is fine enough."""
    f = np.asarray(f_mhz, dtype=np.int64)
    gaps = split_gaps(f / 1000.0, D, lo, hi, ci=ci, extrema=extrema, jumps=jumps, alpha=alpha)
    to_mhz = f_key(to)
    return sorted({int((a + b) // 2) for a, b in ((f_key(x), f_key(y)) for x, y in gaps)
                   if b - a > to_mhz})


def split_gaps(x: Sequence[float], D: Sequence[float], lo: Sequence[float],
               hi: Sequence[float], *, ci: float = 0.95, extrema: bool = True,
               jumps: bool = False, alpha: float = 0.05) -> list[tuple[float, float]]:
    """The gaps (x_i, x_i+1) between neighbours along one axis x that refinement splits: next
    to every significant extremum of D along x (bbb.analysis.extrema) and, with ``jumps``,
    between neighbours whose D differ beyond their CIs (Bonferroni over the neighbours).  NaN
    rows (no data) are left out; sorted by x."""
    x = np.asarray(x, dtype=np.float64)
    D, lo, hi = (np.asarray(a, dtype=np.float64) for a in (D, lo, hi))
    ok = np.isfinite(D) & np.isfinite(lo) & np.isfinite(hi)
    x, D, lo, hi = x[ok], D[ok], lo[ok], hi[ok]
    order = np.argsort(x, kind="stable")
    x, D, lo, hi = x[order], D[order], lo[order], hi[order]
    gaps: set[int] = set()  # index i: the gap between points i and i + 1
    if extrema and x.size >= 3:
        for e in find_extrema(x, D, lo, hi, ci=ci, alpha=alpha):
            gaps.update({e.index - 1, e.index})
    if jumps and x.size >= 2:
        sig = Significance(D, lo, hi, ci, critical_z(2, alpha))
        zc = NormalDist().inv_cdf(1.0 - alpha / (x.size - 1))  # Bonferroni over neighbours
        for i in range(x.size - 1):
            if max(sig.z(i, i + 1), sig.z(i + 1, i)) > zc:
                gaps.add(i)
    return [(float(x[i]), float(x[i + 1])) for i in sorted(gaps) if 0 <= i < x.size - 1]
