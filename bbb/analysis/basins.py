"""What a grid of initial conditions ends in: the share of each final state with its Wilson
interval, the transients' lifetimes and escape rate with bootstrap intervals, the basin
entropy of a labelled grid, and the mixture D_mix = Σᵢ shareᵢ · Dᵢ of the states' own D.

Inputs are the per-window labels of :mod:`bbb.analysis.states` (codes of its ``LABELS``).
Units: s, 1/s, mm²/s.
"""

from __future__ import annotations

import math

import numpy as np

from .states import ABSORBING, CHAOTIC, DIFFUSING, LABELS, LOCKED_1, LOCKED_K, STUCK, UNKNOWN
from .stats.proportion import wilson

__all__ = ["shares", "lifetimes", "escape_rate", "basin_entropy", "state_D", "LOG2", "CLASSES",
           "NO_CLASS", "IRREGULAR", "classes", "held_classes"]

#: the basin entropy of the boundary boxes above which the boundary is fractal (Daza et al.,
#: Sci. Rep. 6, 31416, 2016: S_bb > ln 2 is sufficient)
LOG2 = math.log(2.0)
#: the classes D is measured for: the labels with chaotic and diffusing joined (a chaotic
#: particle confined to one arc in a window crosses arcs in another)
CLASSES = ("none", "stuck", "locked_1", "locked_k", "irregular")
NO_CLASS, IRREGULAR = 0, 4
_CLASS_OF = np.zeros(len(LABELS), np.int8)
_CLASS_OF[[STUCK, LOCKED_1, LOCKED_K, CHAOTIC, DIFFUSING]] = (1, 2, 3, IRREGULAR, IRREGULAR)


def classes(labels: np.ndarray) -> np.ndarray:
    """The class (code of :data:`CLASSES`; 0 for unknown) of each label."""
    return _CLASS_OF[np.asarray(labels, dtype=np.int64)]


def held_classes(labels: np.ndarray, x: np.ndarray, window: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Per particle, the class it holds in every window of the run's second half (NO_CLASS
    where it changes or a window is unknown) and dx²/(2 Δt) over that half (mm²/s, from x at
    the window edges (particle, window + 1), mm)."""
    nw = labels.shape[1]
    half = nw // 2
    c = classes(labels[:, half:])
    held = np.where((c == c[:, :1]).all(axis=1), c[:, 0], NO_CLASS) if nw else np.zeros(
        labels.shape[0], np.int8)
    dt = (nw - half) * window
    return held.astype(np.int8), state_D(x[:, nw] - x[:, half], dt)


def shares(labels: np.ndarray, ci: float) -> dict[str, tuple[float, float, float]]:
    """{label: (share, lo, hi)} of the particles with each label among those with a known
    one, Wilson intervals at level ``ci``; ``unknown`` is the share of all particles."""
    labels = np.asarray(labels)
    known = labels != UNKNOWN
    n = int(known.sum())
    out = {name: wilson(int(np.sum(labels == code)), n, ci) for code, name in enumerate(LABELS)
           if code != UNKNOWN}
    out["unknown"] = wilson(int((~known).sum()), labels.size, ci) if labels.size else (
        math.nan, math.nan, math.nan)
    return out


def lifetimes(settle: np.ndarray, final: np.ndarray, t_max: float) -> tuple[np.ndarray, np.ndarray]:
    """Per particle with a known final state: (lifetime s, settled bool): the settle time where
    the final state is absorbing, else the run's length t_max, censored (still in its
    transient)."""
    known = final != UNKNOWN
    settled = np.isin(final, ABSORBING) & known
    tau = np.where(settled, settle, t_max)[known]
    return tau, settled[known]


def escape_rate(tau: np.ndarray, settled: np.ndarray, t0: float, t_max: float,
                rng: np.random.Generator, n_resamples: int, ci: float) -> tuple[float, float, float]:
    """The rate (1/s) at which particles leave their transient for an absorbing state after
    ``t0``: among the particles still in it at t0 (lifetime > t0), the settled ones per unit
    time spent in it after t0 (the exponential law's estimate with censoring at t_max), with a
    percentile bootstrap interval over the particles; NaNs where no particle was in a transient
    at t0 or none left it (an interval of zero width is NaN too)."""
    at = tau > t0
    if not at.any():
        return math.nan, math.nan, math.nan
    ev = (settled & at).astype(float)[at]
    ex = (np.minimum(tau, t_max) - t0)[at]
    if ev.sum() == 0 or ex.sum() <= 0:
        return math.nan, math.nan, math.nan
    rate = ev.sum() / ex.sum()
    n = ev.size
    w = rng.multinomial(n, np.full(n, 1.0 / n), size=n_resamples)
    with np.errstate(invalid="ignore", divide="ignore"):
        boot = (w @ ev) / (w @ ex)
    if not np.all(np.isfinite(boot)):
        return rate, math.nan, math.nan
    lo, hi = np.quantile(boot, [(1 - ci) / 2, (1 + ci) / 2])
    return (rate, float(lo), float(hi)) if hi > lo else (rate, math.nan, math.nan)


def basin_entropy(grid: np.ndarray, box: int) -> tuple[float, float, int, int]:
    """(S_b, S_bb, boundary boxes, boxes) of a labelled grid (n_phase, n_value) cut into
    ``box`` × ``box`` boxes (the edge's leftover cells dropped): each box's Gibbs entropy
    −Σ p ln p of its labels, averaged over all boxes (S_b) and over the boxes holding more
    than one label (S_bb).  Boxes holding an unknown label are left out.  NaN where no box."""
    a, b = grid.shape[0] // box, grid.shape[1] // box
    if a == 0 or b == 0:
        return math.nan, math.nan, 0, 0
    cells = grid[:a * box, :b * box].reshape(a, box, b, box).transpose(0, 2, 1, 3).reshape(a * b, -1)
    keep = ~(cells == UNKNOWN).any(axis=1)
    cells = cells[keep]
    if not cells.shape[0]:
        return math.nan, math.nan, 0, 0
    ent = np.zeros(cells.shape[0])
    for code in range(len(LABELS)):
        p = (cells == code).mean(axis=1)
        ent -= np.where(p > 0, p * np.log(np.where(p > 0, p, 1.0)), 0.0)
    border = ent > 0
    s_bb = float(ent[border].mean()) if border.any() else 0.0
    return float(ent.mean()), s_bb, int(border.sum()), int(ent.size)


def state_D(dx: np.ndarray, dt: float) -> np.ndarray:
    """Per particle, the squared displacement over ``dt`` s halved per unit time, dx²/(2 dt)
    (mm²/s): its mean over particles is D (the floor mirror-symmetric: no drift)."""
    return np.asarray(dx, dtype=float) ** 2 / (2.0 * dt)
