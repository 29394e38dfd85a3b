"""Run an adaptive study on a Dask client: waves of chunks per (frequency, family) and
refinement rounds, every decision taken on the client by the rules of :mod:`pipeline.execute.adaptive`.

While one (frequency, family) waits for its wave, the others keep the workers busy: the next
wave of a (frequency, family) is submitted as soon as its current wave is complete.  A
decision reads the first n chunks of the store (never the ones that happened to finish first)
and computes D's CI with :func:`interval_of`, seeded by (f in mHz, family, "stop", n): the
store is the same whatever the worker count, and a re-run replays the decisions from the done
chunks (:meth:`Waves.plan`).

**One CI**: :func:`pipeline.execute.intervals.row_intervals` (importable from here, as
before), which the stopping rule decides on, `bbb reduce` reports and refinement reads.
"""

from __future__ import annotations

import sys
import time
import uuid
from collections.abc import Callable

import numpy as np

from ..store.layout import OPEN, STOP_LEGEND, ZERO
from ..store.study_store import StudyStore
from ..workflow.identity import stop_seed  # stop_seed: importable from here as before
from ..workflow.point import Point
from ..workflow.study import Study
from .adaptive import (
    StoppingRule,
    UnitState,
    advance,
    decide,
    refine_frequencies,
    remaining,
)
from .elastic import QueueGauge
from .intervals import (  # importable from here, as before the split
    interval_of,
    pair_units,
    pooled_ci,
    pooled_v,
    row_intervals,
    unit_ci,
)
from .task import is_failing, point_arg, store_argument, task_key

__all__ = ["Waves", "rule_of", "stop_seed", "interval_of", "pair_units", "row_intervals",
           "unit_ci", "pooled_ci", "pooled_v"]

Unit = tuple[int, int]  # (frequency index, family index)


def rule_of(study: Study) -> StoppingRule:
    acc = study.accuracy
    if not acc.adaptive:
        return StoppingRule.fixed(acc.n_chunks)
    return StoppingRule(acc.target_ci, acc.d_resolved, acc.n_chunks, 1)


def _prefix(done_fm: np.ndarray) -> int:
    """How many leading chunks are done."""
    return int(np.argmin(done_fm)) if not done_fm.all() else done_fm.size


class Waves:
    """The state of an adaptive run: one :class:`UnitState` per (frequency, family)."""

    def __init__(self, store: StudyStore, echo: Callable[[str], None] = print):
        self.store, self.echo = store, echo
        self.rule = rule_of(store.study)
        self.states: dict[Unit, UnitState] = {}
        self.rounds = 0

    # -- deciding ----------------------------------------------------------------------------
    def plan(self, fis) -> None:
        """(Re-)derive the state of every unit at the frequency indices ``fis`` from the done
        chunks, replaying the rule from wave 1; records the stops it finds."""
        store, study = self.store, self.store.study
        done, stops = store.done(), store.stops()
        for fi in fis:
            for mi in range(len(study.families)):
                if stops is not None and stops[1][fi, mi] != OPEN:  # decided and recorded
                    n = int(stops[0][fi, mi])
                    state = UnitState(n, [n], int(stops[1][fi, mi]))
                    if state.reason == ZERO:
                        state = self._recheck_zero(fi, mi, state, done[fi, mi])
                else:
                    state = self._advance(None, fi, mi, _prefix(done[fi, mi]))
                self.states[(fi, mi)] = state
                self._drop_beyond(fi, mi, done[fi, mi])

    def _recheck_zero(self, fi, mi, state: UnitState, done_fm: np.ndarray) -> UnitState:
        """A recorded "resolved to ±d_resolved" stands only if the rule still takes it: a store decided
        before a sample with no mover had an unbounded CI (it had [0, 0], "resolved") is
        reopened and sampled on.  One bootstrap per such unit, so cheap; other stops are
        unaffected by that change and are not re-derived."""
        if _prefix(done_fm) < state.n:
            return state
        reason, n_next = decide(self.rule, state.n, unit_ci(self.store, fi, mi, state.n))
        if reason != OPEN:
            return state
        study = self.store.study
        self.echo(f"{study.name}: {study.points[fi].label()}, {study.families[mi].name}: "
                  f"recorded as resolved to ±d_resolved after {state.n} chunks, but no particle moved "
                  f"(D has no upper bound yet): reopened, next wave {n_next} chunks")
        g = self.store.group("r+")
        g["stop_reason"][fi, mi] = OPEN  # first: an interrupted reopening stays open
        g["n_chunks_used"][fi, mi] = 0
        return UnitState(n_next, [state.n, n_next], OPEN, n_next)

    def _advance(self, state, fi, mi, prefix) -> UnitState:
        state = advance(self.rule, state, prefix,
                        lambda n: unit_ci(self.store, fi, mi, n))
        if state.reason != OPEN and self.store.study.accuracy.adaptive:
            self.store.write_stop(fi, mi, state.n, state.reason)
        return state

    def _drop_beyond(self, fi, mi, done_fm) -> None:
        # A done chunk the rule never asked for would change D if reduced: it is unmarked.
        n = self.states[(fi, mi)].n
        beyond = np.flatnonzero(done_fm[n:]) + n
        if beyond.size:
            g = self.store.group("r+")
            for ci in beyond:
                g["done"][fi, mi, int(ci)] = False
            where, fam = self.store.study.points[fi].label(), self.store.study.families[mi].name
            self.echo(f"{self.store.study.name}: {where}, {fam}: chunks "
                      f"{beyond.tolist()} lie beyond what the rule asks for (first {n}); "
                      "unmarked as done")

    def missing(self) -> list[tuple[int, int, int]]:
        """(fi, mi, ci) of the chunks the open units want and do not have, fi-major."""
        done = self.store.done()
        return [(fi, mi, ci) for (fi, mi), s in sorted(self.states.items()) if s.reason == OPEN
                for ci in range(s.n) if not done[fi, mi, ci]]

    def refine(self) -> bool:
        """One refinement round, once every unit has stopped: grow the store by the
        frequencies the rule adds and plan them.  False if the grid is fine enough."""
        study = self.store.study
        if any(s.reason == OPEN for s in self.states.values()):
            return False
        if study.grid:
            return self._refine_grid()
        if study.refine is None:
            return False
        done = self.store.done()
        table = np.array([pooled_ci(self.store, fi, done) for fi in range(len(study.frequencies))])
        rf = study.refine
        new = refine_frequencies(study.f_mhz, table[:, 0], table[:, 1], table[:, 2], to=rf.to,
                                 ci=study.analysis.ci, extrema=rf.extrema, jumps=rf.jumps)
        new = [m for m in new if m not in set(study.f_mhz)]
        if not new:
            return False
        self.rounds += 1
        old = len(study.frequencies)
        self.store = self.store.add_frequencies(tuple(m / 1000 for m in new))
        self.echo(f"{study.name}: refinement round {self.rounds}: {len(new)} frequencies added "
                  f"({', '.join(f'{m / 1000:g}' for m in new[:8])}{' ...' if len(new) > 8 else ''} Hz)")
        self.plan(range(old, len(self.store.study.frequencies)))
        return True

    def _refine_grid(self) -> bool:
        """One refinement round of a map ([grid.refine], pipeline.execute.grid_refine): grow
        the store by the points the rule adds and plan them.  False if none."""
        from .grid_refine import refine_grid

        study = self.store.study
        rule = study.grid_refine
        if rule is None:
            return False
        done = self.store.done()
        table = np.array([self._refined_quantity(fi, done, rule.quantity)
                          for fi in range(len(study.points))])
        own = {"f": study.base_frequencies, **{a: vs for a, vs in study.grid}}
        new = refine_grid(study.points, table, rule, ci=study.analysis.ci, own=own)
        if not new:
            return False
        self.rounds += 1
        old = len(study.points)
        grown = study.with_stored_points(tuple((p.f, p.grid) for p in study.points) + tuple(new))
        self.store = self.store.add_points(grown)
        shown = ", ".join(Point(f, g, None).label() for f, g in new[:4])
        self.echo(f"{study.name}: refinement round {self.rounds}: {len(new)} points added "
                  f"({shown}{' ...' if len(new) > 4 else ''})")
        self.plan(range(old, len(self.store.study.points)))
        return True

    def _refined_quantity(self, fi: int, done: np.ndarray, quantity: str
                          ) -> tuple[float, float, float]:
        """(value, lo, hi) of ``quantity`` ("D": pooled D as `bbb reduce` reports it; "v":
        the drift, mm/s) at point fi."""
        if quantity == "D":
            return pooled_ci(self.store, fi, done)
        return pooled_v(self.store, fi, done)

    def prepare(self) -> list[tuple[int, int, int]]:
        """Plan every unit, refine while nothing is missing; the chunks to compute."""
        self.plan(range(len(self.store.study.points)))
        while not (todo := self.missing()) and self.refine():
            pass
        return todo

    def summary(self) -> str:
        counts: dict[int, int] = {}
        for s in self.states.values():
            counts[s.reason] = counts.get(s.reason, 0) + 1
        return ", ".join(f"{counts[k]} {STOP_LEGEND[k]}" for k in sorted(counts))

    # -- computing ---------------------------------------------------------------------------
    def execute(self, client, fails, report, progress: bool, compute_chunk, on_failure) -> None:
        """Compute until every unit has stopped and refinement adds nothing."""
        from distributed import as_completed
        from tqdm import tqdm

        token = uuid.uuid4().hex[:8]
        bar = tqdm(total=0, unit="chunk", disable=not progress, file=sys.stderr,
                   desc=self.store.study.name, smoothing=0.1)
        pending: dict = {}
        outstanding: dict[Unit, set[int]] = {}
        ac = as_completed()
        # chunks done per unit, kept here: the progress line must not re-read the store's
        # `done` flags (one file per chunk) at every submit — that made the client the
        # bottleneck of make figures (~90 % of its time in zarr reads)
        done_counts: dict[Unit, int] = {}

        def count_done() -> None:
            done = self.store.done()
            done_counts.clear()
            done_counts.update({(fi, mi): int(done[fi, mi].sum()) for fi, mi in self.states})

        handle = {}  # the store as the tasks get it, anew when refinement grows it
        gauge = QueueGauge(client)  # the queue's length, which elastic workers follow

        def submit(chunks) -> None:
            study = self.store.study
            if handle.get("of") is not self.store:
                handle.update({"of": self.store, "arg": store_argument(self.store)})
            for fi, mi, ci in chunks:
                fut = client.submit(compute_chunk, handle["arg"], fi, mi, ci,
                                    is_failing(study, fi, mi, ci, fails), point_arg(study, fi),
                                    key=task_key(study, fi, mi, ci, token),
                                    priority=-fi, retries=0, pure=False)
                pending[fut] = (fi, mi, ci)
                outstanding.setdefault((fi, mi), set()).add(ci)
                ac.add(fut)
            bar.total += len(chunks)
            gauge.publish(len(pending), force=True)
            self._postfix(bar, done_counts)
            bar.refresh()

        try:
            t0 = time.perf_counter()
            count_done()
            submit(self.missing())
            report.submit_seconds = time.perf_counter() - t0
            while True:
                for fut in ac:
                    fi, mi, ci = pending.pop(fut)
                    try:
                        res = fut.result()
                    except Exception as e:
                        on_failure(fut, self.store.study, fi, mi, ci, e,
                                   lambda: client.cancel(list(pending)))
                    report.computed.append(res.key)
                    report.collisions += res.collisions
                    report.task_seconds += res.seconds
                    report.write_seconds += res.write_seconds
                    bar.update(1)
                    gauge.publish(len(pending))
                    done_counts[(fi, mi)] = done_counts.get((fi, mi), 0) + 1
                    outstanding[(fi, mi)].discard(ci)
                    if not outstanding[(fi, mi)]:  # its wave is complete: decide
                        state = self.states[(fi, mi)]
                        # only the first state.n flags: none beyond is done (plan() unmarks
                        # them, and only chunks below state.n are submitted); the whole row is
                        # one file per chunk, read twice per decision (figure2_matyas2004: 128)
                        self._advance(state, fi, mi, _prefix(self._done(fi, mi, state.n)))
                        if state.reason == OPEN:
                            done = self._done(fi, mi, state.n)
                            submit([(fi, mi, c) for c in range(state.n) if not done[c]])
                        self._postfix(bar, done_counts)
                if not self.refine():
                    break
                count_done()  # the store grew by the refined frequencies
                submit(self.missing())
        finally:
            gauge.publish(len(pending), force=True)
            bar.close()

    def _done(self, fi: int, mi: int, n: int) -> np.ndarray:
        """The done flags of the first n chunks of (fi, mi)."""
        return np.asarray(self.store.group()["done"][fi, mi, :n], dtype=bool)

    def progress_line(self, done_counts: dict[Unit, int] | None = None) -> str:
        """What the waves still need, e.g. "waves: 12 (f, family) mid-wave, need ~40 more
        chunks; 100 target met, 20 resolved to ±d_resolved" (the need from the 1/sqrt(N) law).
        ``done_counts``: chunks done per (fi, mi) if the caller keeps them; else read."""
        if done_counts is None:
            done = self.store.done()
            done_counts = {(fi, mi): int(done[fi, mi].sum()) for fi, mi in self.states}
        units = sorted(self.states)
        k, n = remaining([self.states[u] for u in units], [done_counts.get(u, 0) for u in units])
        return f"waves: {k} (f, family) mid-wave, need ~{n} more chunks; {self.summary()}"

    def _postfix(self, bar, done_counts: dict[Unit, int]) -> None:
        if not bar.disable:
            bar.set_postfix_str(self.progress_line(done_counts), refresh=False)
