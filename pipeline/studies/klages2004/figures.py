"""The paper's figures, drawn from study stores and reduce tables only (matplotlib).

Every function takes ``(store, tables, out_dir=None)`` -- a store path or :class:`StudyStore`
(for Fig. 3 also a list of them), a mapping of table name to pandas DataFrame, and the output
folder -- and returns the :class:`matplotlib.figure.Figure` (labelled ``name``); given an
``out_dir`` it also writes ``<name>.png`` and ``<name>.pdf`` there (:func:`figure_files`).
Figures are made without pyplot, so importing this module selects no backend and leaves a
notebook's inline plotting alone; a returned Figure shows itself in Jupyter.

Tables used (all made by ``pipeline.tables.reduce`` or ``pipeline.tables.collisions``):

``diffusion``   the main D(f) table (``diffusion.parquet`` of the Fig. 2 scene)
``ergodicity``  optional: the ``diffusion`` table of a scene with several families
``locking``     optional: :func:`pipeline.tables.collisions.locking_table` of a collisions scene

Units on every axis: f in Hz, D in mm²/s, y in mm, v in mm/s.  Sizes are for a journal
column (3.4 in wide) or the full page width (7 in); the style is
:mod:`pipeline.plot.style`.

Size: one paper's four figures, which share their panels (Fig. 3's letters mark Fig. 2, the
k panel is drawn in Fig. 2's variant and in the locking figure), one function each.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib import rc_context
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

from bbb.analysis.approx import spiral
from bbb.analysis.locking import creep_speed, flight_time_max, flight_times

# the house style, shared by every study's figures (pipeline.plot.style); the old
# private names stay, for the figures of other studies that import them from here
from ...plot.style import COLUMN, PAGE, STYLE, figure_files
from ...plot.style import family_color as _color
from ...plot.style import new_figure as _new_figure
from ...plot.style import save_figure as _save
from ...store.study_store import StudyStore
from ...tables.collisions import as_store, states

__all__ = ["PANELS", "PAPER_K", "STYLE", "figure1", "figure2", "figure3", "figure_locking",
           "figure_files", "main_columns"]

#: Fig. 3's panels: letter -> frequency (Hz)
PANELS = {"a": 54.0, "b": 58.0, "c": 60.0, "d": 66.0, "e": 72.0, "f": 78.0}
#: the paper's k = 2 v f / g read off its spirals: f (Hz) -> k
PAPER_K = {60.0: 1.47, 72.0: 2.5, 80.0: 3.43, 90.0: 4.5}
#: Fig. 3 panels with the spiral approximation overlaid, as in the paper
SPIRAL_PANELS = ("d", "e", "f")


def main_columns(table: pd.DataFrame, family: str = "rest") -> tuple[str, str, str]:
    """Column names (D, lo, hi) of the main curve: the family's own if the table has several,
    else the pooled D."""
    if f"D_{family}" in table and table.filter(regex=r"^D_[A-Za-z].*_lo$").shape[1] > 1:
        return f"D_{family}", f"D_{family}_lo", f"D_{family}_hi"
    return "D", "D_lo", "D_hi"


def _families_in(table: pd.DataFrame) -> list[str]:
    return [c[2:-3] for c in table.columns if c.startswith("D_") and c.endswith("_lo")
            and c not in ("D_lo",)]


# -------------------------------------------------------------------------------------------
# Fig. 1: the geometry
# -------------------------------------------------------------------------------------------
def _trajectory(p, seed: int = 2004):
    """One real trajectory: a few consecutive free flights of a bouncing particle (bbb.simulate).

    Returns (c, j0, j1, mid): the recorded collisions (t, x, y, vx, vy, phase) of the chosen
    particle, the first and last collision index of the window, and the collision drawn with
    its v_perp / v_par frame.
    """
    from bbb import simulate
    from bbb.record import COLLISION_FIELDS

    run = simulate(p, 16, 3.0, seed, "launched", launch_speed=(60.0, 140.0),
                   record_collisions=200, record_from=1.0)
    rec = run.collisions_dense
    col = {n: i for i, n in enumerate(COLLISION_FIELDS)}
    best = None
    for i in range(rec.shape[0]):
        t, y, vy = rec[i, :, col["t"]], rec[i, :, col["y"]], rec[i, :, col["vy"]]
        x = rec[i, :, col["x"]]
        dt = np.diff(t)
        landing = y[:-1] + vy[:-1] * dt - 0.5 * p.g * dt * dt
        ok = np.isfinite(dt) & (np.abs(landing - y[1:]) <= 1e-6) & (dt >= 0.3 / p.f)
        for j0 in range(len(ok) - 4):
            if ok[j0:j0 + 4].all():
                span = abs(x[j0 + 4] - x[j0])
                score = -abs(span - 3.0 * p.S)  # a few arcs wide
                if best is None or score > best[0]:
                    best = (score, i, j0)
    if best is None:
        raise RuntimeError(f"no particle bounced freely four times in a row at f = {p.f:g} Hz")
    _, i, j0 = best
    c = {n: rec[i, :, k] for n, k in col.items()}
    return c, j0, j0 + 4, j0 + 2


def figure1(store: str | os.PathLike | StudyStore, tables: Mapping[str, pd.DataFrame] | None,
            out_dir: str | os.PathLike | None = None, *, f: float = 60.0,
            name: str = "fig1_geometry") -> Figure:
    """Fig. 1: arcs of radius R on spacing S from bbb.surface, the floor at one phase, one
    particle's real trajectory over four bounces (bbb.simulate with the store's parameters at
    ``f`` Hz), and the v_perp / v_par frame at one collision (panel b, true scale).

    Panel (a) exaggerates the vertical scale by the factor written on it.
    """
    from bbb.surface import depth, surface_normal

    st = as_store(store)
    p = st.study.params(f)
    c, j0, j1, jm = _trajectory(p)
    with rc_context(STYLE):
        fig = _new_figure(name, (PAGE, 2.3))
        ax, bx = fig.subplots(1, 2, gridspec_kw={"width_ratios": [2.3, 1.0], "wspace": 0.25})
        # the flights
        xs, ys = [], []
        for j in range(j0, j1):
            tt = np.linspace(0.0, c["t"][j + 1] - c["t"][j], 80)
            xs.append(c["x"][j] + c["vx"][j] * tt)
            ys.append(c["y"][j] + c["vy"][j] * tt - 0.5 * p.g * tt * tt)
        x_all, y_all = np.concatenate(xs), np.concatenate(ys)
        pad = 0.6 * p.S
        x_lo, x_hi = x_all.min() - pad, x_all.max() + pad
        xf = np.linspace(x_lo, x_hi, 2000)
        cells = np.floor(xf / p.S + 0.5)
        phase = c["phase"][jm]
        y_floor = -p.A * math.sin(2 * math.pi * phase)
        ax.plot(xf, y_floor - depth(xf - cells * p.S, p.R), color="0.2", lw=0.9,
                label=f"floor at phase {phase:.2f} (collision $\\star$)")
        ax.plot(xf, -depth(xf - cells * p.S, p.R), color="0.6", lw=0.6, ls="--",
                label="floor at rest height")
        for k in np.unique(cells):
            if x_lo < k * p.S < x_hi:
                ax.plot([k * p.S], [y_floor], marker="+", color="0.5", ms=3, mew=0.5)
        ax.plot(x_all, y_all, color="tab:red", lw=0.8, label="computed trajectory")
        ax.plot(c["x"][j0:j1 + 1], c["y"][j0:j1 + 1], "o", color="tab:red", ms=2.2)
        ax.plot([c["x"][jm]], [c["y"][jm]], marker="*", color="k", ms=7, ls="none")
        y_lo = min(y_floor, 0.0) - p.A - 0.05 * (y_all.max() - y_all.min())
        y_hi = y_all.max() + 0.35 * (y_all.max() - y_all.min())
        ax.set_xlim(x_lo, x_hi)
        ax.set_ylim(y_lo, y_hi)
        # vertical exaggeration: 1 mm of y drawn this many times longer than 1 mm of x
        bbox = ax.get_window_extent()
        exag = (bbox.height / (y_hi - y_lo)) / (bbox.width / (x_hi - x_lo))
        # amplitude marker
        xa = x_hi - 0.25 * pad
        ax.annotate("", xy=(xa, p.A), xytext=(xa, -p.A),
                    arrowprops={"arrowstyle": "<->", "lw": 0.6, "color": "0.3"})
        ax.text(xa - 0.05 * pad, 0.0, "2A", ha="right", va="center", fontsize=6.5, color="0.3")
        ax.text(0.01, 0.02, f"vertical scale exaggerated ×{exag:.0f}", transform=ax.transAxes,
                ha="left", va="bottom", fontsize=6, color="0.3")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.legend(loc="upper left", fontsize=5.5, ncol=2, handlelength=1.5, columnspacing=1.0)
        ax.set_title(f"(a)  R = {p.R:g} mm, S = {p.S:g} mm, A = {p.A:g} mm, f = {p.f:g} Hz",
                     loc="left")
        # (b) the frame at collision jm, true scale
        xc, yc = c["x"][jm], c["y"][jm]
        w = 0.3
        xz = np.linspace(xc - w, xc + w, 400)
        kz = np.floor(xz / p.S + 0.5)
        bx.plot(xz, y_floor - depth(xz - kz * p.S, p.R), color="0.2", lw=0.9)
        nx, ny = (float(v) for v in surface_normal(p, xc))
        L = 0.13
        dt = c["t"][jm] - c["t"][jm - 1]
        v_in = np.array([c["vx"][jm - 1], c["vy"][jm - 1] - p.g * dt])
        v_out = np.array([c["vx"][jm], c["vy"][jm]])
        arrow = {"arrowstyle": "-|>", "lw": 0.7, "mutation_scale": 6}
        bx.annotate("", xy=(xc + L * nx, yc + L * ny), xytext=(xc, yc),
                    arrowprops={**arrow, "color": "k"})
        bx.annotate("", xy=(xc + L * ny, yc - L * nx), xytext=(xc, yc),
                    arrowprops={**arrow, "color": "k"})
        bx.text(xc + L * nx + 0.01, yc + L * ny, r"$v_\perp$", fontsize=7, va="bottom")
        bx.text(xc + L * ny, yc - L * nx - 0.015, r"$v_\parallel$", fontsize=7, va="top",
                ha="center")
        u_in, u_out = v_in / np.hypot(*v_in), v_out / np.hypot(*v_out)
        bx.annotate("", xy=(xc, yc), xytext=(xc - L * u_in[0], yc - L * u_in[1]),
                    arrowprops={**arrow, "color": "tab:red", "ls": "--"})
        bx.annotate("", xy=(xc + L * u_out[0], yc + L * u_out[1]), xytext=(xc, yc),
                    arrowprops={**arrow, "color": "tab:red"})
        bx.text(xc - L * u_in[0], yc - L * u_in[1], r"$v^-$", color="tab:red", fontsize=7,
                ha="right", va="bottom")
        bx.text(xc + L * u_out[0], yc + L * u_out[1], r"$v^+$", color="tab:red", fontsize=7,
                ha="left", va="bottom")
        bx.plot([xc], [yc], marker="*", color="k", ms=7)
        bx.set_xlim(xc - w, xc + w)
        bx.set_ylim(yc - 0.45 * w, yc + 1.05 * w)
        bx.set_aspect("equal")
        bx.set_xlabel("x (mm)")
        bx.set_ylabel("y (mm)")
        bx.set_title(r"(b) collision $\star$, true scale", loc="left")
        return _save(fig, out_dir)


# -------------------------------------------------------------------------------------------
# Fig. 2: D(f)
# -------------------------------------------------------------------------------------------
def _spans(f: np.ndarray, flags: np.ndarray) -> list[tuple[float, float]]:
    """Intervals around the flagged frequencies: half-way to the neighbours (at most 0.5 Hz)."""
    order = np.argsort(f)
    f, flags = f[order], flags[order]
    gaps = np.diff(f)
    left = np.minimum(np.concatenate([[np.inf], gaps]) / 2, 0.5)
    right = np.minimum(np.concatenate([gaps, [np.inf]]) / 2, 0.5)
    return [(f[i] - left[i], f[i] + right[i]) for i in np.flatnonzero(flags)]


def _not_ergodic(table: pd.DataFrame) -> np.ndarray:
    if "ergodic" not in table:
        return np.zeros(len(table), bool)
    e = table["ergodic"].astype("boolean")
    return (e == False).fillna(False).to_numpy(bool)  # noqa: E712 -- pandas nullable boolean


def _draw_D(ax, main: pd.DataFrame, cols: tuple[str, str, str], ergo: pd.DataFrame | None,
            main_family: str, *, legend: bool, small: bool = False) -> list[tuple[float, float]]:
    """Shading, the main curve with error bars, other families outside its CI; returns the
    (f, top of error bar) of everything drawn, for placing labels."""
    f = main["f"].to_numpy(float)
    D, lo, hi = (main[c].to_numpy(float) for c in cols)
    labelled: set[str] = set()
    for tbl in (main, ergo):
        if tbl is None:
            continue
        several = len(_families_in(tbl)) > 1
        kind = "not ergodic (families / EB)" if several else "EB not converging (1 family)"
        for a, b in _spans(tbl["f"].to_numpy(float), _not_ergodic(tbl)):
            ax.axvspan(a, b, color="0.8" if several else "0.92", lw=0, zorder=0,
                       label=None if (kind in labelled or not legend) else kind)
            labelled.add(kind)
    ms = 1.4 if small else 1.8
    ax.errorbar(f, D, yerr=[D - lo, hi - D], fmt="o", ms=ms, color="k", ecolor="0.35",
                elinewidth=0.5, capsize=0.8, capthick=0.4, lw=0, zorder=3,
                label=(f"{main_family} (95 % CI)" if main_family else "95 % CI") if legend else None)
    ax.plot(f, D, color="k", lw=0.4, zorder=2)
    if "stationary" in main:  # D depends on the run length (bbb.analysis.stationarity): hollow marker
        moves = main["stationary"].astype("boolean").eq(False).fillna(False).to_numpy(bool)
        if moves.any():
            ax.plot(f[moves], D[moves], "o", ms=ms + 0.4, mfc="w", mec="k", mew=0.5, zorder=5,
                    label="D depends on run length" if legend else None)
    tops = list(zip(f, hi, strict=True))
    ref = (f"D_{main_family}", f"D_{main_family}_lo", f"D_{main_family}_hi")
    if ergo is not None and ref[0] in ergo:
        for i, fam in enumerate(x for x in _families_in(ergo) if x != main_family):
            d, dlo, dhi = (ergo[c].to_numpy(float) for c in (f"D_{fam}", f"D_{fam}_lo", f"D_{fam}_hi"))
            out = (d < ergo[ref[1]].to_numpy(float)) | (d > ergo[ref[2]].to_numpy(float))
            if out.any():
                fo = ergo["f"].to_numpy(float)[out]
                ax.errorbar(fo, d[out], yerr=[(d - dlo)[out], (dhi - d)[out]], fmt="s",
                            ms=ms + 0.6, mfc="none", color=_color(fam, i), elinewidth=0.5,
                            capsize=0.8, lw=0, zorder=4,
                            label=f"{fam}, outside {main_family} CI" if legend else None)
                tops += list(zip(fo, dhi[out], strict=True))
    return tops


def _letters(ax, tops: list[tuple[float, float]], letters: Mapping[str, float],
             f_grid: np.ndarray, lim: tuple[float, float] | None = None) -> None:
    ft = np.array([t[0] for t in tops])
    ht = np.array([t[1] for t in tops])
    for letter, fl in letters.items():
        if lim is not None and not lim[0] <= fl <= lim[1]:
            continue
        j = int(np.argmin(np.abs(f_grid - fl)))
        if abs(f_grid[j] - fl) <= 0.5:
            near = np.abs(ft - f_grid[j]) <= 0.8
            ax.annotate(f"({letter})", (f_grid[j], np.nanmax(ht[near])), xytext=(0, 2),
                        textcoords="offset points", ha="center", va="bottom", fontsize=6)


def figure2(store: str | os.PathLike | StudyStore | None, tables: Mapping[str, pd.DataFrame],
            out_dir: str | os.PathLike | None = None, *, name: str = "fig2_diffusion",
            letters: Mapping[str, float] | None = PANELS, main_family: str = "rest",
            inset: tuple[float, float] | None = (50.0, 67.0), legend_loc: str = "lower right"
            ) -> Figure:
    """Fig. 2: D(f) with its bootstrap 95 % CI on every point.

    tables["diffusion"]   -- the main curve (the ``main_family`` columns if it has several)
    tables["ergodicity"]  -- optional: other families' D, drawn with their CI where they lie
                             outside the main family's CI at the same f (same table)
    tables["locking"]     -- optional: adds a lower panel k(f) (k_max and k_peak) with the
                             integer and half-integer lines
    Shaded: frequencies whose ergodicity verdict is negative -- darker where the verdict
    compares several families, lighter where it rests on the EB of one family only.
    ``letters`` marks Fig. 3's panels at their frequencies (None: no letters); ``inset``
    (f range, Hz) repeats that range magnified in an inset (None: no inset); ``legend_loc``
    places the legend.
    """
    main = tables["diffusion"].sort_values("f")
    cols = main_columns(main, main_family)
    ergo = tables.get("ergodicity")
    title = None
    if store is not None:
        st = as_store(store)
        prm = st.study.params(float(main["f"].iloc[0]))
        acc = st.study.accuracy
        # a target-driven scene's particle count differs per f: state the target and the cap
        size = (f"D to ±{100 * acc.target_ci:g} %, ≤ {acc.n_particles}"
                if acc.target_ci is not None else f"{acc.n_particles}")
        title = (f"R = {prm.R:g} mm, α = {prm.alpha:g}, β = {prm.beta:g}, A = {prm.A:g} mm "
                 f"({size} particles × {acc.t_max:g} s)")
    lock = tables.get("locking")
    f = main["f"].to_numpy(float)
    with rc_context(STYLE):
        if lock is not None:
            fig = _new_figure(name, (COLUMN, 3.6))
            ax, kx = fig.subplots(2, 1, sharex=True,
                                  gridspec_kw={"height_ratios": [2.0, 1.2], "hspace": 0.08})
        else:
            fig = _new_figure(name, (COLUMN, 2.6))
            ax, kx = fig.subplots(), None
        tops = _draw_D(ax, main, cols, ergo, main_family, legend=True)
        top = max((t[1] for t in tops if np.isfinite(t[1])), default=1.0)
        lo_all = main[cols[1]].to_numpy(float)
        bottom = min(0.0, float(np.nanmin(lo_all))) if np.isfinite(lo_all).any() else 0.0
        ax.set_ylim(bottom, 1.1 * top)
        if letters:
            _letters(ax, tops, letters, f, lim=None if inset is None else (inset[1], np.inf))
        if inset is not None and np.any((f >= inset[0]) & (f <= inset[1])):
            # x0 leaves room for the inset's tick labels inside the main axes, clear of its
            # y axis and tick labels
            ix = ax.inset_axes([0.14, 0.57, 0.31, 0.40])
            sel = (main["f"] >= inset[0] - 0.5) & (main["f"] <= inset[1] + 0.5)
            esel = None if ergo is None else ergo[(ergo["f"] >= inset[0]) & (ergo["f"] <= inset[1])]
            itops = _draw_D(ix, main[sel], cols, esel, main_family, legend=False, small=True)
            itop = max((t[1] for t in itops if np.isfinite(t[1])), default=1.0)
            ix.set_xlim(inset[0] - 0.5, inset[1] + 0.5)
            ix.set_ylim(bottom, 1.18 * itop)
            ix.tick_params(labelsize=5.5, length=2)
            ix.xaxis.set_major_locator(MultipleLocator(5.0))
            if letters:
                _letters(ix, itops, letters, f, lim=inset)
        ax.set_ylabel(r"$D$ (mm$^2$/s)")
        ax.legend(loc=legend_loc, fontsize=5.5, handlelength=1.2)
        if title:
            ax.set_title(title, fontsize=6.5)
        if kx is not None:
            _k_panel(kx, lock, half=True, paper=False)
            kx.set_xlabel(r"$f$ (Hz)")
        else:
            ax.set_xlabel(r"$f$ (Hz)")
        return _save(fig, out_dir)


def _k_panel(ax, lock: pd.DataFrame, *, half: bool = True, paper: bool = True) -> None:
    """k = 2 v f / g against f: k_max (filled) and k_peak (open) per family, integer lines."""
    k_all = lock[["k_max", "k_peak"]].to_numpy(float)
    top = math.ceil(np.nanmax(k_all)) + 0.5 if np.isfinite(k_all).any() else 5.0
    for k in np.arange(1, top + 1):
        ax.axhline(k, color="0.55", lw=0.5, zorder=0)
        if half:
            ax.axhline(k - 0.5, color="0.7", lw=0.5, ls="--", zorder=0)
    for i, (fam, grp) in enumerate(lock.groupby("family", sort=False)):
        grp = grp.sort_values("f")
        col = _color(str(fam), i)
        ax.plot(grp["f"], grp["k_max"], "o", ms=2.0, color=col, label=f"{fam}: max $v_y^+$")
        ax.plot(grp["f"], grp["k_peak"], "^", ms=2.2, mfc="none", mew=0.5, color=col,
                label=f"{fam}: peak $v_y^+$")
    if paper:
        ax.plot(list(PAPER_K), list(PAPER_K.values()), "*", ms=6, mfc="none", mew=0.7,
                color="tab:red", label="paper (text)")
    ax.set_ylim(0, top)
    ax.set_ylabel(r"$k = 2 v_y^+ f / g$")
    ax.legend(loc="upper left", fontsize=5.5, ncol=2)


# -------------------------------------------------------------------------------------------
# Fig. 3: phase-space projections with the spiral approximation
# -------------------------------------------------------------------------------------------
def figure3(store: str | os.PathLike | StudyStore | Sequence[str | os.PathLike | StudyStore],
            tables: Mapping[str, pd.DataFrame] | None,
            out_dir: str | os.PathLike | None = None, *,
            name: str = "fig3_phase_space", panels: Mapping[str, float] = PANELS,
            spiral_panels: Sequence[str] = SPIRAL_PANELS, max_points: int = 25_000) -> Figure:
    """Fig. 3: post-collision (y, v_y⁺) at each panel's frequency, every family of every given
    store that holds that frequency (within 1 mHz), coloured by family; the flat-floor spiral
    of Eqs. (8)-(9) on ``spiral_panels``: t_0 = 1/(2f), t_1 = t_0 + t_c with
    t_c ∈ [0, t_max(f)], t_max the 0.99 quantile of the free-flight times of the plotted
    states (bbb.analysis.locking).  At most ``max_points`` points per panel and family are drawn
    (evenly thinned); t_max uses all.
    """
    stores = [as_store(s) for s in (store if isinstance(store, (list, tuple)) else [store])]
    with rc_context(STYLE):
        fig = _new_figure(name, (COLUMN, 5.0))
        axes = fig.subplots(3, 2, sharex=True, gridspec_kw={"hspace": 0.2, "wspace": 0.32})
        seen: dict[str, bool] = {}
        for ax, (letter, fp) in zip(axes.ravel(), panels.items(), strict=False):
            flights, p = [], None
            for st in stores:
                freqs = np.asarray(st.study.frequencies)
                if not np.any(np.abs(freqs - fp) < 1e-3):
                    continue
                p = st.study.params(fp)
                for i, fam in enumerate(st.study.families):
                    s = states(st, fp, fam.name)
                    y, v = s["y"].ravel(), s["vy"].ravel()
                    ok = np.isfinite(y) & np.isfinite(v)
                    y, v = y[ok], v[ok]
                    flights.append(flight_times(s["t"], s["y"], s["vy"], p.g))
                    step = max(1, y.size // max_points)
                    col = _color(fam.name, i)
                    ax.plot(y[::step], v[::step], ".", color=col, alpha=0.5, rasterized=True,
                            ms=0.6, mew=0)
                    if y.size and fam.name not in seen:
                        ax.plot([], [], "o", ms=2, color=col, label=fam.name)
                        seen[fam.name] = True
            ax.set_title(f"({letter}) f = {fp:g} Hz", loc="left", fontsize=7, pad=2)
            if p is None:
                ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center")
                continue
            ax.axhline(creep_speed(p.A, fp), color="0.6", lw=0.4, ls=":")
            if letter in spiral_panels:
                t_max = flight_time_max(np.concatenate(flights)) if flights else math.nan
                if math.isfinite(t_max):
                    tc = np.linspace(0.0, t_max, 4000)
                    ys, vs = spiral(p.A, fp, p.g, p.alpha, tc)
                    ax.plot(ys, vs, color="tab:red", lw=0.6)
                    ax.text(0.03, 0.97, f"Eqs. (8)-(9), $t_{{max}}$ = {1e3 * t_max:.1f} ms",
                            transform=ax.transAxes, ha="left", va="top", fontsize=5.5,
                            color="tab:red")
                    ax.set_ylim(top=ax.get_ylim()[1] + 0.12 * np.ptp(ax.get_ylim()))
        for ax in axes[-1]:
            ax.set_xlabel(r"$y$ (mm)")
        for ax in axes[:, 0]:
            ax.set_ylabel(r"$v_y^+$ (mm/s)")
        if seen:
            axes[0, 0].legend(loc="upper left", fontsize=5.5, markerscale=1.0, handlelength=0.8)
        return _save(fig, out_dir, dpi=200)  # dense scatter: keep the file small


# -------------------------------------------------------------------------------------------
# The locking plot
# -------------------------------------------------------------------------------------------
def figure_locking(store: str | os.PathLike | StudyStore | None,
                   tables: Mapping[str, pd.DataFrame],
                   out_dir: str | os.PathLike | None = None, *,
                   name: str = "fig_locking", paper: bool = True) -> Figure:
    """k = 2 v_y⁺ f / g against f from tables["locking"]: k from the maximal v_y⁺ (0.99
    quantile above the creeping band, filled circles) and from the dominant v_y⁺ peak (open
    triangles), per family; integer (solid) and half-integer (dashed) lines; the paper's
    values read off its spirals as stars (``paper``)."""
    lock = tables["locking"]
    with rc_context(STYLE):
        fig = _new_figure(name, (COLUMN, 2.5))
        ax = fig.subplots()
        _k_panel(ax, lock, half=True, paper=paper)
        ax.set_xlabel(r"$f$ (Hz)")
        if store is not None:
            st = as_store(store)
            prm = st.study.params(float(lock["f"].iloc[0]))
            ax.set_title(f"R = {prm.R:g} mm, α = {prm.alpha:g}, A = {prm.A:g} mm", fontsize=6.5)
        return _save(fig, out_dir)
