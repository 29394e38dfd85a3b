"""States: each particle's state in each time window of ``[observables.states] window`` s --
stuck/creeping, locked 1/1, locked period-k, chaotic, diffusing, or unknown where the
recording ran out -- by the calibrated classifier :mod:`bbb.analysis.states` (thresholds in
bbb/analysis/states_rule.json, fixed before any basin data), from the post-collision states
recorded from t = 0 (``rows`` per particle), and x at the windows' edges.

Stored per particle: ``state_label`` (int8 codes of bbb.analysis.states.LABELS),
``state_period`` (floor periods of a locked window's cycle, 0 elsewhere), ``state_x`` (mm, x
at t = 0, window, 2 window, …).  Its table, one row per (point, family): the share of each
final state (the last window's label) among the particles with a known one, with Wilson
intervals; the median lifetime of the transients that settled, the escape rate from the
transient after the first window and D of each class of states over the run's second half
(the particles that stay in one class -- stuck, locked 1/1, locked period-k, irregular --
through it: bbb.analysis.basins.held_classes), with
percentile bootstrap intervals over particles.  A statistic that cannot be measured is blank
and ``states_status`` says why.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..identity import table_seed
from ..schema import key
from .contract import Array, Chunk, Coord, Observable

__all__ = ["States", "StatesTable"]


@dataclass(frozen=True)
class StatesTable:
    window: float = key(0.5, "length of a labelled time window", units="s", gt=0, le=100,
                        note="longer than any flight and at least 4 floor periods; t_max holds "
                        "whole windows")
    rows: int = key(40000, "post-collision states recorded per particle from t = 0 (a "
                    "creeping particle collides ~25 times a floor period; windows after the "
                    "recording ends are 'unknown')", units="collisions per particle",
                    ge=10, le=10**6)


class States(Observable):
    name = "states"
    doc = ("each time window's state: stuck/creeping, locked 1/1, locked period-k, chaotic, "
           "diffusing (calibrated classifier), and x at the windows' edges")
    scene = StatesTable
    when = "stores with `[observables.states]`"
    columns = (
        ("n_particles", False, "1", "particles of done chunks"),
        ("final_<state>", True, "1", "share of the particles whose last window is <state> "
         "(stuck, locked_1, locked_k, chaotic, diffusing) among those with a known one; "
         "final_unknown: share of all whose recording ran out (Wilson intervals)"),
        ("lifetime_median", True, "s", "median transient lifetime of the particles that "
         "settled in an absorbing state (start of the window from which the final label holds)"),
        ("escape_rate", True, "1/s", "rate of leaving the transient for an absorbing state "
         "after the first window (settled per unit time in the transient, censored at t_max)"),
        ("D_<class>", True, "mm^2/s", "mean x displacement² / (2 Δt) over the run's second "
         "half of the particles in one class (stuck, locked_1, locked_k, irregular: chaotic "
         "or diffusing) in every window of it"),
        ("D_all", True, "mm^2/s", "the same over every particle"),
        ("states_status", False, "", "why a blank statistic is blank (empty: all measured)"),
    )

    def _settings(self, study) -> tuple[float, int]:
        s = self.settings(study.observables)
        return float(s["window"]), int(s["rows"])

    def edges(self, study) -> np.ndarray:
        """The windows' edges (s): 0, window, …, n_windows · window."""
        from bbb.analysis.states import n_windows

        w, _ = self._settings(study)
        return np.arange(n_windows(study.accuracy.t_max, w) + 1) * w

    def sample_times(self, study, f):
        return self.edges(study)

    def rows(self, study) -> int:
        return self._settings(study)[1]

    def rows_from(self, study) -> float:
        return 0.0  # the windows start at t = 0

    def coords(self, study):
        e = self.edges(study)
        return (Coord("state_window", e[:-1], "float64", "s", "start of the labelled window"),
                Coord("state_edge", e, "float64", "s", "window edge"))

    def arrays(self, study):
        nw = len(self.edges(study)) - 1
        return (Array("state_label", (("state_window", nw),), "int8", -1, "",
                      "state code (bbb.analysis.states.LABELS; -1: not computed)"),
                Array("state_period", (("state_window", nw),), "int8", -1, "floor periods",
                      "cycle of a locked window (0 elsewhere)"),
                Array("state_x", (("state_edge", nw + 1),), "float64", np.nan, "mm",
                      "x at the windows' edges"))

    def compute(self, chunk: Chunk):
        from bbb.analysis.states import classify

        study, run = chunk.study, chunk.run
        w, R = self._settings(study)
        p = chunk.point.params
        lab, per, _ = classify(run.collisions_dense[:, :R], np.minimum(run.n_recorded, R),
                               study.accuracy.t_max, w, p.f, p.A, p.S)
        return {"state_label": lab, "state_period": per,
                "state_x": chunk.positions_at(self.edges(study))}

    def table(self, store, done):
        import pandas as pd

        study = store.study
        w, _ = self._settings(study)
        rows = []
        for fi, point in enumerate(study.points):
            for mi, fam in enumerate(study.families):
                lab = store.read_done("state_label", fi, mi, done[fi, mi])
                x = store.read_done("state_x", fi, mi, done[fi, mi])
                rng = np.random.default_rng(table_seed(study, point.f, fam.name, self.name))
                rows.append({**point.columns(), "family": fam.name, "initial": fam.initial,
                             **state_row(lab, x, w, study.accuracy.t_max, rng,
                                         study.accuracy.n_resamples, study.analysis.ci)})
        return pd.DataFrame(rows)


def state_row(lab: np.ndarray, x: np.ndarray, window: float, t_max: float,
              rng: np.random.Generator, n_resamples: int, ci: float) -> dict:
    """The table's columns of one (point, family) from its particles' labels (particle,
    window) and x at the edges (particle, window + 1)."""
    from bbb.analysis import basins as bs
    from bbb.analysis import states as st

    why: list[str] = []
    row: dict = {"n_particles": int(lab.shape[0])}
    final = st.final_state(lab) if lab.shape[0] else np.zeros(0, np.int8)
    for name, (v, lo, hi) in bs.shares(final, ci).items():
        row[f"final_{name}"], row[f"final_{name}_lo"], row[f"final_{name}_hi"] = v, lo, hi
    settle = st.settle_time(lab, window)
    tau, settled = bs.lifetimes(settle, final, t_max)
    row.update(_median(tau[settled], rng, n_resamples, ci, "lifetime_median", why))
    k, lo, hi = bs.escape_rate(tau, settled, window, t_max, rng, n_resamples, ci)
    row["escape_rate"], row["escape_rate_lo"], row["escape_rate_hi"] = k, lo, hi
    if math.isnan(k) or math.isnan(lo):
        why.append("escape_rate: no transient left after the first window, or no interval")
    held, d_i = bs.held_classes(lab, x, window)
    for code, name in enumerate(bs.CLASSES):
        if code == bs.NO_CLASS:
            continue
        row.update(_mean(d_i[held == code], rng, n_resamples, ci, f"D_{name}", why))
    row.update(_mean(d_i[final != st.UNKNOWN], rng, n_resamples, ci, "D_all", why))
    row["states_status"] = "; ".join(why)
    return row


def _mean(v: np.ndarray, rng, n_resamples: int, ci: float, name: str, why: list) -> dict:
    """{name, name_lo, name_hi}: the mean and its percentile bootstrap interval; an interval
    of zero width (every value equal: e.g. no particle of a stuck state moves) is blank."""
    if v.size == 0:
        why.append(f"{name}: no particle")
        return {name: math.nan, f"{name}_lo": math.nan, f"{name}_hi": math.nan}
    m = float(v.mean())
    w = rng.multinomial(v.size, np.full(v.size, 1.0 / v.size), size=n_resamples)
    lo, hi = np.quantile(w @ v / v.size, [(1 - ci) / 2, (1 + ci) / 2])
    if not hi > lo:
        why.append(f"{name}: interval of zero width ({v.size} particles, all {m:.3g})")
        return {name: m, f"{name}_lo": math.nan, f"{name}_hi": math.nan}
    return {name: m, f"{name}_lo": float(lo), f"{name}_hi": float(hi)}


def _median(v: np.ndarray, rng, n_resamples: int, ci: float, name: str, why: list) -> dict:
    """{name, name_lo, name_hi}: the median and its percentile bootstrap interval (blank as
    :func:`_mean`)."""
    if v.size == 0:
        why.append(f"{name}: no particle")
        return {name: math.nan, f"{name}_lo": math.nan, f"{name}_hi": math.nan}
    m = float(np.median(v))
    idx = rng.integers(0, v.size, size=(n_resamples, v.size))
    lo, hi = np.quantile(np.median(v[idx], axis=1), [(1 - ci) / 2, (1 + ci) / 2])
    if not hi > lo:
        why.append(f"{name}: interval of zero width ({v.size} particles)")
        return {name: m, f"{name}_lo": math.nan, f"{name}_hi": math.nan}
    return {name: m, f"{name}_lo": float(lo), f"{name}_hi": float(hi)}
