"""A particle's state over time: each time window of a run labelled stuck/creeping, locked 1/1,
locked period-k, chaotic (within one arc) or diffusing (chaotic, crossing arcs), from the
post-collision states the kernel records (bbb.record.COLLISION_FIELDS, from t = 0).

The labels, per window [a, b) of ``window`` seconds, in the order the rule tries them:

unknown    the recording ends before b (its ``rows`` were used up): not measured, never a
           state guessed;
stuck      no collision in the window (held at rest on the floor: a flight cannot last a
           window, :func:`check_window`), or the particle lands at rest relative to the floor
           (a collision that ends a cascade: speed relative to the floor below ``stick_speed``)
           in at least ``creep_share`` of the window's floor periods: the chattering motion
           that comes to rest once a period (creeping);
locked     the window's sequence of post-collision states repeats after k collisions: for the
           smallest k ≤ ``k_max`` with at least ``min_pairs`` pairs (i, i + k), every pair
           agrees to ``lock_tol`` in the floor phase (fraction of a period, on the circle), in
           vx and vy (per the floor's peak speed A·2πf) and in the offset within the arc
           (per S); ``locked_1`` when k = 1 and the collisions are one floor period apart
           (1/1), else ``locked_k`` (the cycle's length in floor periods kept in ``period``);
chaotic    none of these, the particle in one arc over the window;
diffusing  none of these, the particle crossing an arc boundary within the window.

The thresholds are calibrated on runs with known answers (benchmarks/calibrations/states.py:
the flat floor's 1/1 orbit between Γ₁ and Γ′, its period-2 orbit beyond Γ′, a particle held
below lift-off, the paper's floor where particles diffuse) and read from the rule file beside
this module (:data:`RULE_FILE`, written by that calibration; :func:`calibrated_rule`).
Units: s, mm, mm/s, Hz.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from numba import njit

__all__ = ["LABELS", "UNKNOWN", "STUCK", "LOCKED_1", "LOCKED_K", "CHAOTIC", "DIFFUSING",
           "ABSORBING", "RULE_FILE", "RULE_KEYS", "calibrated_rule", "classify", "mismatch",
           "relative_speed",
           "n_windows", "check_window", "final_state", "settle_time"]

#: the labels, by their code (int8 in a store)
LABELS = ("unknown", "stuck", "locked_1", "locked_k", "chaotic", "diffusing")
UNKNOWN, STUCK, LOCKED_1, LOCKED_K, CHAOTIC, DIFFUSING = range(len(LABELS))
#: the states a particle stays in once reached (at rest, or an orbit that repeats)
ABSORBING = (STUCK, LOCKED_1, LOCKED_K)
RULE_FILE = Path(__file__).resolve().parent / "states_rule.json"
#: the rule's thresholds (the rest of the rule file says where they come from)
RULE_KEYS = ("lock_tol", "stick_speed", "creep_share", "k_max", "min_pairs")
_T, _X, _VX, _VY, _PH = 0, 1, 3, 4, 5


def calibrated_rule(path: Path = RULE_FILE) -> dict:
    """The calibrated thresholds {key: value} of :data:`RULE_KEYS` (KeyError naming a missing
    key of the file)."""
    rule = json.loads(Path(path).read_text(encoding="utf-8"))
    missing = [k for k in RULE_KEYS if k not in rule]
    if missing:
        raise KeyError(f"{path.name}: no {', '.join(missing)}; allowed: a rule file written by "
                       "benchmarks/calibrations/states.py")
    return {k: rule[k] for k in RULE_KEYS}


def n_windows(t_max: float, window: float) -> int:
    """Whole windows of ``window`` s within a run of ``t_max`` s."""
    return int(math.floor(t_max / window + 1e-9))


def check_window(window: float, f: float, g: float, v_max: float) -> None:
    """Refuse (ValueError) a window no longer than a flight at ``v_max`` (mm/s, the fastest
    start or floor speed) or shorter than 4 floor periods: an empty window must mean held."""
    flight = 2.0 * v_max / g
    if not (window > flight and window * f >= 4.0):
        raise ValueError(f"window = {window!r} s is out of range; allowed: longer than the "
                         f"longest flight 2 v_max / g = {flight:.4g} s and at least 4 floor "
                         f"periods ({4.0 / f:.4g} s at {f:g} Hz)")


@njit(cache=True)
def _mismatch(rec, lo, hi, k, f, vscale, S):
    # the largest disagreement of the pairs (i, i + k) of rows lo..hi-1 (see mismatch)
    worst = 0.0
    for i in range(lo, hi - k):
        j = i + k
        dp = abs(rec[j, _PH] - rec[i, _PH])
        dp = min(dp, 1.0 - dp)
        dvx = abs(rec[j, _VX] - rec[i, _VX]) / vscale
        dvy = abs(rec[j, _VY] - rec[i, _VY]) / vscale
        di = rec[i, _X] - S * math.floor(rec[i, _X] / S + 0.5)
        dj = rec[j, _X] - S * math.floor(rec[j, _X] / S + 0.5)
        dd = abs(dj - di) / S
        worst = max(worst, dp, dvx, dvy, dd)
    return worst


@njit(cache=True)
def _relative_speed(row, A, w):
    # |post-collision velocity − the floor's| (mm/s): 0 for a particle held on the floor
    vf = -A * w * math.cos(2.0 * math.pi * row[_PH])
    return math.hypot(row[_VX], row[_VY] - vf)


def relative_speed(rec: np.ndarray, f: float, A: float) -> np.ndarray:
    """The speed (mm/s) of each post-collision state relative to the floor: (..., 6) rows →
    (...); a row that ends a cascade (the particle held) has ≈ 0."""
    w = 2.0 * math.pi * f
    vf = -A * w * np.cos(2.0 * math.pi * rec[..., _PH])
    return np.hypot(rec[..., _VX], rec[..., _VY] - vf)


@njit(cache=True)
def _classify(rec, n, t_max, window, nw, f, A, S, lock_tol, stick_speed, creep_share,
              k_max, min_pairs, labels, period, mism):
    w = 2.0 * math.pi * f
    vscale = A * w
    P, R = rec.shape[0], rec.shape[1]
    for p in range(P):
        # the recording covers [0, t_max) unless its rows ran out: then up to its last row
        cover = t_max if n[p] < R else rec[p, R - 1, _T]
        row = 0
        for q in range(nw):
            a, b = q * window, (q + 1) * window
            while row < n[p] and rec[p, row, _T] < a:
                row += 1
            lo = row
            hi = lo
            while hi < n[p] and rec[p, hi, _T] < b:
                hi += 1
            mism[p, q] = math.nan
            period[p, q] = 0
            if b > cover:
                labels[p, q] = UNKNOWN
                continue
            m = hi - lo
            if m == 0:
                labels[p, q] = STUCK
                continue
            sticks = 0
            for i in range(lo, hi):
                if _relative_speed(rec[p, i], A, w) <= stick_speed:
                    sticks += 1
            if sticks >= creep_share * (b - a) * f:
                labels[p, q] = STUCK
                continue
            best = math.inf
            for k in range(1, k_max + 1):
                if m - k < min_pairs:
                    break
                mk = _mismatch(rec[p], lo, hi, k, f, vscale, S)
                best = min(best, mk)
                if mk <= lock_tol:
                    period[p, q] = k
                    break
            mism[p, q] = best
            if period[p, q] > 0:
                k = period[p, q]
                # the cycle's length in floor periods (k collisions apart, on average)
                cyc = (rec[p, hi - 1, _T] - rec[p, lo, _T]) / (m - 1) * k * f
                periods = max(1, int(math.floor(cyc + 0.5)))
                period[p, q] = min(periods, 127)
                labels[p, q] = LOCKED_1 if k == 1 and periods == 1 else LOCKED_K
                continue
            c0 = math.floor(rec[p, lo, _X] / S + 0.5)
            crossed = False
            for i in range(lo + 1, hi):
                if math.floor(rec[p, i, _X] / S + 0.5) != c0:
                    crossed = True
                    break
            labels[p, q] = DIFFUSING if crossed else CHAOTIC


def classify(rec: np.ndarray, n: np.ndarray, t_max: float, window: float, f: float, A: float,
             S: float, rule: dict | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Label each particle's windows.

    rec: float64 (particle, row, 6) post-collision (t, x, y, vx, vy, phase) from t = 0
    (bbb.SimRun.collisions_dense, NaN-padded); n: int (particle,) valid rows; t_max: s, the
    run's end; window: s; f: Hz; A, S: mm; rule: the thresholds (default: the calibrated
    :func:`calibrated_rule`).  Returns (labels int8 (particle, window) codes of :data:`LABELS`,
    period int8 (particle, window): the floor periods of a locked window's cycle (1 for 1/1, 2 for
    period-2, ...; at most 127), 0 elsewhere, mismatch float64
    (particle, window): the smallest pair disagreement found (:func:`mismatch`; NaN where no
    pair was compared))."""
    rule = calibrated_rule() if rule is None else rule
    nw = n_windows(t_max, window)
    P = rec.shape[0]
    labels = np.zeros((P, nw), np.int8)
    period = np.zeros((P, nw), np.int8)
    mism = np.full((P, nw), np.nan)
    if rec.ndim != 3 or rec.shape[1] == 0:
        raise ValueError(f"rec must be (particle, row, 6) with at least one row, got shape "
                         f"{rec.shape}; allowed: a recording of collisions from t = 0")
    _classify(np.ascontiguousarray(rec, dtype=np.float64), np.asarray(n, np.int64),
              float(t_max), float(window), nw, float(f), float(A), float(S),
              float(rule["lock_tol"]), float(rule["stick_speed"]), float(rule["creep_share"]),
              int(rule["k_max"]), int(rule["min_pairs"]), labels, period, mism)
    return labels, period, mism


def mismatch(rec: np.ndarray, k: int, f: float, A: float, S: float) -> float:
    """The largest disagreement of the pairs of rows (i, i + k) of one particle's rows ``rec``
    (row, 6): floor phase on the circle (fraction of a period), vx and vy per A·2πf, offset in
    the arc per S (dimensionless; 0 on an orbit that repeats every k collisions)."""
    return float(_mismatch(np.ascontiguousarray(rec, dtype=np.float64), 0, rec.shape[0], k,
                           float(f), float(A) * 2.0 * math.pi * float(f), float(S)))


def final_state(labels: np.ndarray) -> np.ndarray:
    """Each particle's state at the end of its run: the label of its last window (unknown
    when the recording ran out before it)."""
    return labels[:, -1].copy() if labels.shape[1] else np.zeros(labels.shape[0], np.int8)


def settle_time(labels: np.ndarray, window: float) -> np.ndarray:
    """Per particle, the start (s) of the first window from which every window carries its
    final label, where that label is absorbing (:data:`ABSORBING`): the transient's lifetime;
    NaN where the final state is not absorbing (chaotic, diffusing, unknown: still in its
    transient, or not measured, at the run's end)."""
    P, nw = labels.shape
    out = np.full(P, np.nan)
    if nw == 0:
        return out
    last = labels[:, -1]
    same = labels == last[:, None]
    # the last window that differs from the final label, +1
    differs = ~same
    idx = np.where(differs.any(axis=1), nw - np.argmax(differs[:, ::-1], axis=1), 0)
    ok = np.isin(last, ABSORBING)
    out[ok] = idx[ok] * window
    return out
