"""The D(f, α) figures: the map with its landmarks, and its cuts against the committed Fig. 2
curves.  Units: f Hz, D mm²/s.

The map draws each judged α line (:func:`.lines.judged_lines`) as a row of cells, one per
frequency it holds (refined ones included), coloured by log D; a point whose D is below
:data:`D_FLOOR` (creeping: not diffusing) is grey, one whose estimator failed is white.  α
values refinement added hold a few points: drawn as dots in the same colours.  On top: the
contour lines k_max = 1, 2, 3, ... of the locking map (white), the flat-floor thresholds
f(Γ₁(α)) and f(Γ'(α)) (:mod:`bbb.analysis.period1`), lift-off from rest (Γ = 1), and per line
the onset of diffusion (|) and the first maximum above it (▲).
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import colors, rc_context
from matplotlib.figure import Figure

from bbb import Params
from bbb.analysis.liftoff_onset import liftoff_frequency

from ...plot.style import PAGE, STYLE, figure_files, new_figure, save_figure
from .claims import CUTS, LOCKING, MAP, cut_line, threshold_frequency
from .lines import first_max_above, judged_lines, listed_alphas, onset

__all__ = ["CAPTIONS", "D_FLOOR", "figure_map", "figure_cuts", "files"]

D_FLOOR = 1.0  # mm²/s: below it a point is drawn as not diffusing
CAPTIONS = {
    "fig_dissipation": (
        "D(f, α) from rest at the paper's arcs (R = 15 mm, A = 0.1 mm), α from 0.4 to 0.95, "
        "D to 5 % (or resolved as below 9 mm²/s), refined along f and α next to extrema and "
        "jumps (dots: α values refinement added). Grey: D < 1 mm²/s (creeping); white: no D (the "
        "estimator failed: the MSD's fit gives D significantly below 0). White "
        "lines: k_max = 2 v_max f / g = 1, 2, 3, ... (the spiral's loops; scene "
        "dissipation_locking). Dashed: the flat-floor 1/1 orbit appears (Γ₁) and loses "
        "stability (Γ'); dotted: Γ = 1, lift-off from rest. Per line: the onset of "
        "diffusion (|) and the first significant maximum above it (▲). Scene dissipation."),
    "fig_dissipation_cuts": (
        "Cuts of the D(f, α) maps against the committed curves at the same parameters, 95 % "
        "CIs: (a) α = 0.7 against Fig. 2; (b) α = 0.5 on R = 25 mm arcs against Mátyás & "
        "Klages' Fig. 2 (scene dissipation_r25). Crosses: shared frequencies where the two "
        "disagree beyond their combined CIs."),
}


def _edges(v: np.ndarray) -> np.ndarray:
    if v.size == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def _draw_lines(ax, lines: Mapping[float, pd.DataFrame], norm, cmap) -> None:
    alphas = np.array(sorted(lines))
    a_edges = _edges(alphas)
    for i, a in enumerate(alphas):
        t = lines[a]
        f = t["f"].to_numpy(float)
        D = t["D"].to_numpy(float)
        shown = np.ma.masked_invalid(np.where(D >= D_FLOOR, D, np.nan))[None, :]
        low = np.ma.masked_where(~(D < D_FLOOR), np.ones_like(D))[None, :]
        ys = a_edges[i:i + 2]
        ax.pcolormesh(_edges(f), ys, low, cmap=colors.ListedColormap(["0.82"]), shading="flat")
        ax.pcolormesh(_edges(f), ys, shown, cmap=cmap, norm=norm, shading="flat")


def _draw_landmarks(ax, lines, lock: pd.DataFrame | None, f_range) -> None:
    a = np.linspace(0.38, 0.97, 120)
    for name, style, label in (("gamma_1", "--", "f(Γ₁)"), ("gamma_prime", "--", "f(Γ')")):
        f = np.asarray(threshold_frequency(name, a))
        ok = (f >= f_range[0]) & (f <= f_range[1])
        if ok.any():
            ax.plot(f[ok], a[ok], style, color="tab:red" if name == "gamma_prime" else "tab:orange",
                    lw=1.0, label=label)
    f_lift = liftoff_frequency(Params.preset("klages2004", f=1.0))
    ax.axvline(f_lift, ls=":", color="k", lw=0.8, label="Γ = 1")
    if lock is not None and "k_max" in lock and "alpha" in lock:
        grid = lock.pivot_table(index="alpha", columns="f", values="k_max")
        if grid.shape[0] > 1 and grid.shape[1] > 1:
            cs = ax.contour(grid.columns.to_numpy(float), grid.index.to_numpy(float),
                            grid.to_numpy(float), levels=[1, 2, 3, 4, 5], colors="white",
                            linewidths=0.7)
            ax.clabel(cs, fmt="k=%d", fontsize=5.5)
    for alpha, line in lines.items():
        q = onset(line)
        if math.isfinite(q.value):
            ax.plot([q.value], [alpha], marker="|", color="k", ms=7, mew=1.2)
            m = first_max_above(line, q.value)
            if math.isfinite(m.value):
                ax.plot([m.value], [alpha], marker="^", color="k", ms=3.5, mfc="white", mew=0.7)


def figure_map(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
               name: str = "fig_dissipation", listed=None) -> Figure | None:
    """The D(f, α) map from ``tables["dissipation_diffusion"]`` (and the locking map's
    ``dissipation_locking_locking`` for the k_max lines), its rows the ``listed`` α lines
    (default: the shipped scene's); None without the map."""
    t = tables.get(f"{MAP}_diffusion")
    lines = judged_lines(t, listed or listed_alphas(MAP))
    if not lines:
        return None
    D = t["D"].to_numpy(float)
    top = float(np.nanmax(D)) if np.isfinite(D).any() else 10.0
    norm = colors.LogNorm(vmin=D_FLOOR, vmax=max(top, 10 * D_FLOOR))
    cmap = "viridis"
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 0.5 * PAGE), layout="constrained")
        ax = fig.add_subplot()
        _draw_lines(ax, lines, norm, cmap)
        extra = t[~np.isin(np.round(t["alpha"].to_numpy(float), 9), np.round(list(lines), 9))]
        if len(extra):
            d = extra["D"].to_numpy(float)
            ax.scatter(extra["f"], extra["alpha"], c=np.where(d >= D_FLOOR, d, np.nan), s=4,
                       cmap=cmap, norm=norm, edgecolors="none", plotnonfinite=False, zorder=3)
        f_range = (float(t["f"].min()), float(t["f"].max()))
        _draw_landmarks(ax, lines, tables.get(f"{LOCKING}_locking"), f_range)
        fig.colorbar(ax.collections[1], ax=ax, label="D (mm²/s)", pad=0.01)
        ax.set(xlabel="f (Hz)", ylabel="α (normal restitution)", xlim=f_range)
        ax.legend(loc="upper right", fontsize=6, frameon=True, framealpha=0.8)
        if out_dir is not None:
            save_figure(fig, out_dir)
    return fig


def figure_cuts(tables: Mapping[str, pd.DataFrame], refs: Mapping[str, pd.DataFrame],
                out_dir: str | os.PathLike | None = None,
                name: str = "fig_dissipation_cuts") -> Figure | None:
    """D(f) of each cut (:data:`.claims.CUTS`) with the committed curve ``refs[cut]`` it is
    compared with; the shared frequencies that disagree crossed (``tables["dissipation_cuts"]``);
    None without any cut."""
    shown = [(n, cut_line(tables, n), refs.get(n)) for n in CUTS]
    shown = [s for s in shown if s[1] is not None and s[2] is not None]
    if not shown:
        return None
    cmp_ = tables.get(f"{MAP}_cuts")
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 0.32 * PAGE), layout="constrained")
        axes = fig.subplots(1, len(shown), squeeze=False)[0]
        for ax, (n, line, ref), letter in zip(axes, shown, "abc", strict=False):
            for t, c, lab in ((ref, "0.45", "committed scene"), (line, "tab:blue", "map line")):
                ax.fill_between(t["f"], t["D_lo"], t["D_hi"], color=c, alpha=0.3, lw=0)
                ax.plot(t["f"], t["D"], color=c, lw=0.8, label=lab)
            if cmp_ is not None:
                bad = cmp_[(cmp_["cut"] == n) & (cmp_["agree"] == 0)]
                if len(bad):
                    ax.plot(bad["f"], bad["D"], "x", color="tab:red", ms=4, label="disagree")
            ax.set(xlabel="f (Hz)", ylabel="D (mm²/s)", title=f"({letter}) {CUTS[n][0]}")
            ax.legend(loc="upper left", fontsize=6)
        if out_dir is not None:
            save_figure(fig, out_dir)
    return fig


def files(out_dir: str | os.PathLike, figs) -> list[Path]:
    """The files the drawn figures were written to."""
    return [p for fig in figs if fig is not None for p in figure_files(out_dir, fig.get_label())]


