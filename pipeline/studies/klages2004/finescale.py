"""The fine-scale study: does D(f) show "irregularities on finer and finer scales" (the
paper's outlook)?  Counts of significant extrema per Hz as the frequency resolution doubles,
from one refined window (scene ``finescale``), and the figure.

**Resolution levels.**  Refinement (pipeline/execute/adaptive.py) halves gaps on the mHz grid, so a
window refined from a grid of step h0 down to h0 / 2^k holds a subset of the h0 / 2^k grid
anchored at the window's start.  The D(f) a resolution h would have seen is the sub-sample of
the refined table on the h grid (:func:`subsample`): the base grid at h0, every refined point
at the finest h.  Refinement adds points only around extrema and significant jumps, so the
finest levels are dense only there: a count at fine h is of the extrema that appear *next to
structure seen at the coarser levels*, a lower bound on what a uniform fine grid would show.

**Counts and their CI** (:func:`extrema_per_hz`).  At each level the significant extrema of
``bbb.analysis.extrema.find_extrema`` (the same rule as REPORT.md's extrema: pairwise z-tests of the
95 % CIs, Bonferroni over the level's points) are counted and divided by the window's width
(Hz).  The CI is a parametric bootstrap of the D curve within its CIs: each resample draws
every D_i from a normal of standard deviation (hi_i - lo_i) / (2 z_0.975) around D_i, keeps
each point's CI width, and recounts; the 2.5 and 97.5 percentiles of the counts are the 95 %
interval of "the count a D(f) compatible with the measured CIs would give".

**Locations** (:func:`located_extrema`).  Each extremum of the finest level at f_i is placed
in [min(f_lo, f_i - g_l / 2), max(f_hi, f_i + g_r / 2)]: the range of neighbouring points
whose CIs overlap its own (``Extremum.f_lo, f_hi``), at least half the gaps g_l, g_r to its
neighbours on the refined grid (where the extremum of the underlying curve may lie).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from statistics import NormalDist

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from bbb.analysis.extrema import Extremum, find_extrema
from pipeline.workflow.identity import f_key, f_keys

__all__ = ["LEVELS", "LevelCount", "Located", "subsample", "extrema_per_hz",
           "located_extrema", "new_extrema", "table_arrays", "figure_finescale",
           "finescale_summary", "write_table", "EXTREMA_UNITS"]

#: resolutions (Hz) at which the extrema are counted: the base grid and three halvings
LEVELS = (0.4, 0.2, 0.1, 0.05)


@dataclass(frozen=True)
class LevelCount:
    """Significant extrema at resolution h (Hz): count (with its 95 % bootstrap interval
    [lo, hi]), per Hz of the window, from n_points points."""

    h: float
    n_points: int
    count: int
    lo: float
    hi: float
    width: float  # Hz

    @property
    def per_hz(self) -> tuple[float, float, float]:
        return (self.count / self.width, self.lo / self.width, self.hi / self.width)


@dataclass(frozen=True)
class Located:
    """An extremum of the finest level: kind, f (Hz), D (mm²/s), and the interval [f_lo,
    f_hi] (Hz) it lies in."""

    kind: str
    f: float
    D: float
    f_lo: float
    f_hi: float


def subsample(f_hz, h: float, origin: float) -> np.ndarray:
    """Mask of the frequencies on the grid origin + k h (to the mHz)."""
    return (f_keys(f_hz) - f_key(origin)) % f_key(h) == 0


def table_arrays(table: pd.DataFrame, cols=("f", "D", "D_lo", "D_hi")):
    t = table.sort_values(cols[0])
    t = t[np.isfinite(t[list(cols)]).all(axis=1)]
    return tuple(t[c].to_numpy(dtype=np.float64) for c in cols)


def _counts(f, D, lo, hi, levels, origin, ci, n_boot, seed):
    """Sorted arrays; per level the subsample mask, the count and the bootstrap counts
    (n_boot resamples, the same draws at every level)."""
    f, D, lo, hi = (np.asarray(a, dtype=np.float64) for a in (f, D, lo, hi))
    order = np.argsort(f, kind="stable")
    f, D, lo, hi = f[order], D[order], lo[order], hi[order]
    origin = float(f.min()) if origin is None else origin
    sigma = (hi - lo) / (2 * NormalDist().inv_cdf(0.5 + ci / 2))
    draws = D + np.random.default_rng(seed).standard_normal((n_boot, D.size)) * sigma
    masks, counts, boot = [], [], np.zeros((n_boot, len(levels)), dtype=np.int64)
    for j, h in enumerate(levels):
        m = subsample(f, h, origin)
        fm, Dm, lm, hm = f[m], D[m], lo[m], hi[m]
        masks.append(m)
        counts.append(len(find_extrema(fm, Dm, lm, hm, ci=ci)))
        boot[:, j] = [len(find_extrema(fm, d[m], d[m] - (Dm - lm), d[m] + (hm - Dm), ci=ci))
                      for d in draws]
    return f, masks, counts, boot


def extrema_per_hz(f, D, lo, hi, *, levels=LEVELS, origin: float | None = None,
                   width: float | None = None, ci: float = 0.95, n_boot: int = 400,
                   seed: int = 2004) -> list[LevelCount]:
    """The significant extrema per Hz at each resolution in ``levels`` (Hz), with their 95 %
    bootstrap interval (module docstring).  f in Hz, D and its CI [lo, hi] in mm²/s at level
    ``ci``; origin and width default to the window min(f) and max(f) - min(f)."""
    fs, masks, counts, boot = _counts(f, D, lo, hi, levels, origin, ci, n_boot, seed)
    width = float(fs.max() - fs.min()) if width is None else width
    q = np.percentile(boot, [2.5, 97.5], axis=0)
    return [LevelCount(h, int(m.sum()), n, float(q[0, j]), float(q[1, j]), width)
            for j, (h, m, n) in enumerate(zip(levels, masks, counts, strict=True))]


def new_extrema(f, D, lo, hi, *, coarse: float = LEVELS[0], fine: float = LEVELS[-1],
                origin: float | None = None, ci: float = 0.95, n_boot: int = 400,
                seed: int = 2004) -> tuple[int, float, float]:
    """How many more significant extrema the ``fine`` resolution shows than the ``coarse``
    one: (value, lo, hi), the interval from the same bootstrap, paired draw by draw."""
    _, _, counts, boot = _counts(f, D, lo, hi, (coarse, fine), origin, ci, n_boot, seed)
    diff = boot[:, 1] - boot[:, 0]
    q = np.percentile(diff, [2.5, 97.5])
    return counts[1] - counts[0], float(q[0]), float(q[1])


def located_extrema(f, D, lo, hi, *, ci: float = 0.95) -> list[Located]:
    """The significant extrema of the whole (refined) table, each with the interval it lies
    in (module docstring)."""
    f, D, lo, hi = (np.asarray(a, dtype=np.float64) for a in (f, D, lo, hi))
    order = np.argsort(f, kind="stable")
    f, D, lo, hi = f[order], D[order], lo[order], hi[order]
    out = []
    e: Extremum
    for e in find_extrema(f, D, lo, hi, ci=ci):
        i = e.index
        left = f[i] - 0.5 * (f[i] - f[i - 1]) if i > 0 else f[i]
        right = f[i] + 0.5 * (f[i + 1] - f[i]) if i < f.size - 1 else f[i]
        out.append(Located(e.kind, e.f, e.D, min(e.f_lo, left), max(e.f_hi, right)))
    return out


def figure_finescale(table: pd.DataFrame, out_dir: str | os.PathLike | None,
                     name: str = "fig_finescale") -> Figure:
    """(a) significant extrema per Hz against the resolution; (b) the refined D(f) with its
    CIs, the base grid's points, and the extrema of the finest level with their intervals."""
    from matplotlib import rc_context

    from ...plot.style import STYLE

    with rc_context(STYLE):
        return _draw(table, out_dir, name)


def _draw(table: pd.DataFrame, out_dir, name: str) -> Figure:
    from ...plot.style import new_figure, save_figure

    f, D, lo, hi = table_arrays(table)
    origin = float(f.min())
    counts = extrema_per_hz(f, D, lo, hi, origin=origin)
    located = located_extrema(f, D, lo, hi)
    fig = new_figure(name, (7.0, 2.8))
    a, b = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1, 2.2]})
    h = np.array([c.h for c in counts])
    v = np.array([c.per_hz for c in counts])
    a.errorbar(h, v[:, 0], yerr=[v[:, 0] - v[:, 1], v[:, 2] - v[:, 0]], fmt="o-", color="k",
               capsize=3, ms=4)
    a.set_xscale("log", base=2)
    a.set_xticks(h, [f"{x:g}" for x in h])
    a.invert_xaxis()
    a.set_xlabel("resolution (Hz)")
    a.set_ylabel("significant extrema per Hz")
    a.set_ylim(bottom=0.0, top=max(1.0, 1.2 * float(v[:, 2].max())))
    a.set_title("(a)", loc="left")
    base = subsample(f, LEVELS[0], origin)
    b.fill_between(f, lo, hi, color="0.8", lw=0)
    b.plot(f, D, "-", color="k", lw=0.8)
    b.plot(f[~base], D[~base], ".", color="tab:blue", ms=3, label="refined")
    b.plot(f[base], D[base], "o", color="k", ms=3, label=f"{LEVELS[0]:g} Hz grid")
    for e in located:
        c = "tab:red" if e.kind == "max" else "tab:green"
        b.errorbar([e.f], [e.D], xerr=[[e.f - e.f_lo], [e.f_hi - e.f]], fmt="v" if e.kind == "min"
                   else "^", color=c, ms=5, capsize=2)
    b.set_xlabel("f (Hz)")
    b.set_ylabel("D (mm²/s)")
    b.set_title("(b)", loc="left")
    b.legend(loc="best", fontsize="small", frameon=False)
    return save_figure(fig, out_dir)


def finescale_summary(table: pd.DataFrame) -> tuple[list[LevelCount], list[Located]]:
    """The counts per level and the located extrema of a finescale diffusion table."""
    f, D, lo, hi = table_arrays(table)
    return extrema_per_hz(f, D, lo, hi, origin=float(f.min())), located_extrema(f, D, lo, hi)


#: units of the columns of finescale_extrema.csv (conventions: pipeline.tables.units)
EXTREMA_UNITS = {"h": "Hz", "n_points": "1", "count": "1", "per_hz": "1/Hz"}


def write_table(table: pd.DataFrame, out_dir: str | os.PathLike) -> Path:
    """extrema_per_hz as CSV (h, n_points, count, lo, hi, per_hz, per_hz_lo, per_hz_hi)."""
    counts, _ = finescale_summary(table)
    rows = [{"h": c.h, "n_points": c.n_points, "count": c.count, "count_lo": c.lo,
             "count_hi": c.hi, "per_hz": c.per_hz[0], "per_hz_lo": c.per_hz[1],
             "per_hz_hi": c.per_hz[2]} for c in counts]
    p = Path(out_dir) / "finescale_extrema.csv"
    pd.DataFrame(rows).to_csv(p, index=False, float_format="%.6g")
    return p
