"""The ratchet figures, drawn from the map's tables only:

- ``fig_ratchet_map``: per α, the signed drift v over (f, peak position p) -- a diverging
  colour map centred at v = 0 (red: towards +x, blue: towards −x), symmetric log scale; a
  point whose v is not significant (Bonferroni over its line) dotted, a point whose drift is
  not steady hatched, each current reversal as a bar over its interval on its line;
- ``fig_ratchet_lines``: per α, v(f) for each p with its 95 % bootstrap interval (mirror
  partners p and 1 − p in one colour, p < 0.5 solid, p > 0.5 dashed; p = 0.5 black), the
  reversal intervals shaded;
- ``fig_ratchet_mechanism``: on the lines p < 0.5, one column per α, the collisions per floor
  period, the phase locking ρ of the collisions (mechanism.resultant) and the lag-1 vx
  correlation against f, the reversal intervals shaded.

A blank value is left out (a blank interval drawn without a bar), never drawn as zero.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import rc_context
from matplotlib.collections import PatchCollection
from matplotlib.colors import SymLogNorm
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from ...claims.signs import significant_signs
from ...plot.heatmap import cell_edges
from ...plot.style import PAGE, STYLE, figure_files, new_figure, save_figure
from .claims import CENTRE, SCENE, TABLE, line_reversals, map_lines
from .mechanism import (
    BINS,
    CONVEYOR_FILES,
    STATES_TABLE,
    conveyor_reversals,
    resultant,
    reversal_table,
)
from .reversal_states import STATES_SCENE, states_table

__all__ = ["CAPTIONS", "draw", "figure_map", "figure_lines", "figure_mechanism"]

CAPTIONS = {
    "fig_ratchet_map": (
        "Ratchet transport on a level sawtooth floor vibrated vertically (scene ratchet; teeth "
        "0.3 mm deep on S = 2 mm, the peak a fraction p of S from the left valley): the drift v "
        "over f and p, one panel per restitution α; red: towards +x, blue: towards −x, white: "
        "v = 0 (symmetric log scale, linear within ± 0.1 mm/s). Dotted: v not significant "
        "(Bonferroni over the line, α = 0.05); hatched: drift not steady; black bars: the "
        "current reversals along f, each over its interval (claim R4). p = 0.5 is the "
        "symmetric control (claim R2); p and 1 − p are mirror images (claim R3)."),
    "fig_ratchet_lines": (
        "The ratchet drift v(f) per peak position p with 95 % bootstrap intervals over "
        "particles (no bar: a blank interval), one panel per α; a mirror pair p, 1 − p in one "
        "colour (p < 0.5 solid, p > 0.5 dashed), p = 0.5 black; shaded: the intervals of the "
        "current reversals (claim R4)."),
    "fig_ratchet_mechanism": (
        "What the collisions do around the ratchet's current reversals, on the off-centre "
        "lines with p < 0.5 (their mirror partners' are alike), one column per α: (top) "
        "collisions per floor period (none where the particles rest: left out of the log "
        "axis); (middle) the phase locking ρ of the collisions (length "
        "of the mean resultant of the floor phase at the collisions from 5 s on: 1 all at one "
        "phase, 0 spread evenly); (bottom) the lag-1 correlation of the post-collision vx "
        "about each particle's own mean (near +1: a walking state keeps its velocity). "
        "Shaded: the reversal intervals, in the line's colour."),
}


def _line_color(p: float, peaks) -> str:
    if np.isclose(p, CENTRE):
        return "k"
    lows = sorted({round(min(x, 1 - x), 9) for x in peaks if not np.isclose(x, CENTRE)})
    return f"C{lows.index(round(min(p, 1 - p), 9)) % 10}"


def figure_map(t: pd.DataFrame, out_dir: str | os.PathLike | None,
               name: str = "fig_ratchet_map"):
    """v over (f, p), one panel per α, from the map's diffusion table ``t``."""
    alphas = sorted(t["alpha"].unique())
    peaks = np.array(sorted(t["peak"].unique()), float)
    fs = np.array(sorted(t["f"].unique()), float)
    _, ex = cell_edges(fs)
    _, ey = cell_edges(peaks)
    v = t["v"].to_numpy(float)
    vmax = max(float(np.nanmax(np.abs(v))) if np.isfinite(v).any() else 1.0, 0.2)
    norm = SymLogNorm(linthresh=0.1, vmin=-vmax, vmax=vmax)
    lines = map_lines(t)
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 0.3 * PAGE * len(alphas) + 0.6), layout="constrained")
        axes = np.atleast_1d(fig.subplots(len(alphas), 1, sharex=True))
        mesh = None
        for ax, a in zip(axes, alphas, strict=True):
            z = np.full((peaks.size, fs.size), np.nan)
            dots, hatch = [], []
            for r in t[np.isclose(t["alpha"], a)].itertuples(index=False):
                j, i = int(np.argmin(abs(peaks - r.peak))), int(np.argmin(abs(fs - r.f)))
                z[j, i] = r.v
                if "steady" in t and not (pd.isna(r.steady) or bool(r.steady)):
                    hatch.append((j, i))
            for (la, p), ln in lines.items():
                if not np.isclose(la, a):
                    continue
                s = significant_signs(ln["v"], ln["v_lo"], ln["v_hi"])
                j = int(np.argmin(abs(peaks - p)))
                dots += [(j, int(np.argmin(abs(fs - f)))) for f in ln["f"][s == 0]]
            mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(z), cmap="RdBu_r", norm=norm,
                                 gid="map")
            if dots:
                ax.plot([fs[i] for _, i in dots], [peaks[j] for j, _ in dots], ".", ms=1.8,
                        color="0.35", gid="not_significant")
            if hatch:
                ax.add_collection(PatchCollection(
                    [Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j])
                     for j, i in hatch], facecolor="none", edgecolor="0.15", lw=0,
                    hatch="////", gid="hatch:steady"))
            for (la, p), ln in lines.items():
                if np.isclose(la, a) and not np.isclose(p, CENTRE):
                    for fa, fb, _ in line_reversals(ln)[0]:
                        ax.plot([fa, fb], [p, p], "-", color="k", lw=2.2,
                                solid_capstyle="butt", gid="reversal")
                        ax.plot([fa, fb], [p, p], "|", color="k", ms=6, mew=1.2)
            ax.axhline(CENTRE, color="0.5", lw=0.5, ls=":")
            ax.set_yticks(peaks)
            ax.set_ylabel("peak position p")
            ax.set_title(f"α = {a:g}", fontsize="small", loc="left")
            ax.set_xlim(ex[0], ex[-1])
        axes[-1].set_xlabel("f (Hz)")
        if mesh is not None:
            fig.colorbar(mesh, ax=list(axes), label="drift v (mm/s), > 0 towards +x")
        axes[0].legend(handles=[Line2D([], [], color="k", lw=2.2, label="current reversal"),
                                Line2D([], [], color="0.35", marker=".", ls="",
                                       label="v not significant"),
                                Patch(facecolor="white", edgecolor="0.2", hatch="////",
                                      label="not steady")],
                       fontsize="x-small", loc="lower left", bbox_to_anchor=(0.0, 1.12),
                       ncols=3, borderaxespad=0.0)
        return save_figure(fig, out_dir)


def _shade_reversals(ax, found, color) -> None:
    for fa, fb, _ in found:
        ax.axvspan(fa, fb, color=color, alpha=0.15, lw=0, gid="reversal")


def figure_lines(t: pd.DataFrame, out_dir: str | os.PathLike | None,
                 name: str = "fig_ratchet_lines"):
    """v(f) with its CI per p, one panel per α."""
    alphas = sorted(t["alpha"].unique())
    peaks = sorted(t["peak"].unique())
    lines = map_lines(t)
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 0.3 * PAGE * len(alphas) + 0.4), layout="constrained")
        axes = np.atleast_1d(fig.subplots(len(alphas), 1, sharex=True))
        for ax, a in zip(axes, alphas, strict=True):
            for p in peaks:
                ln = t[np.isclose(t["alpha"], a) & np.isclose(t["peak"], p)].sort_values("f")
                if ln.empty:
                    continue
                c = _line_color(p, peaks)
                f, v, lo, hi = (ln[k].to_numpy(float) for k in ("f", "v", "v_lo", "v_hi"))
                ok = np.isfinite(v)
                ax.plot(f[ok], v[ok], ls="--" if p > CENTRE else "-", marker=".", ms=3,
                        color=c, label=f"p = {p:g}", gid=f"v:{p:g}")
                bar = ok & np.isfinite(lo) & np.isfinite(hi)
                ax.errorbar(f[bar], v[bar], yerr=[v[bar] - lo[bar], hi[bar] - v[bar]],
                            fmt="none", elinewidth=0.6, capsize=1.2, color=c)
                if (a, p) in lines and not np.isclose(p, CENTRE):
                    _shade_reversals(ax, line_reversals(lines[(a, p)])[0], c)
            ax.axhline(0.0, color="k", lw=0.5, ls=":")
            ax.set_ylabel("drift v (mm/s)")
            ax.set_title(f"α = {a:g}", fontsize="small", loc="left")
        axes[-1].set_xlabel("f (Hz)")
        axes[0].legend(fontsize="x-small", ncols=len(peaks), loc="lower left",
                       bbox_to_anchor=(0.0, 1.12), borderaxespad=0.0)
        return save_figure(fig, out_dir)


def figure_mechanism(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None,
                     name: str = "fig_ratchet_mechanism"):
    """Collisions per period, phase locking ρ and the lag-1 vx correlation against f on the
    lines p < 0.5, one column per α, the reversal intervals shaded."""
    t = tables.get(TABLE)
    imp, cnt = tables.get(f"{SCENE}_impacts"), tables.get(f"{SCENE}_counters")
    lines = map_lines(t)
    peaks = sorted({p for _, p in lines})
    alphas = sorted({a for a, _ in lines})
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 0.62 * PAGE), layout="constrained")
        axes = np.array(fig.subplots(3, len(alphas), sharex=True, sharey="row", squeeze=False))
        for col, a in enumerate(alphas):
            ax_n, ax_r, ax_v = axes[:, col]
            for p in (x for x in peaks if x < CENTRE - 1e-9):
                c, label = _line_color(p, peaks), f"p = {p:g}"
                if cnt is not None:
                    s = cnt[np.isclose(cnt["alpha"], a) & np.isclose(cnt["peak"], p)
                            ].sort_values("f")
                    per = (s["collisions_per_s"] / s["f"]).to_numpy(float, copy=True)
                    per[per <= 0] = np.nan  # at rest: 0 has no place on the log axis (caption)
                    ax_n.plot(s["f"], per, marker=".", ms=2.5, color=c, label=label,
                              gid=f"per_period:{a:g}:{p:g}")
                if imp is not None:
                    s = imp[np.isclose(imp["alpha"], a) & np.isclose(imp["peak"], p)
                            ].sort_values("f")
                    rho = [resultant([r[f"phase_{b}"] for b in range(BINS)])[0]
                           for _, r in s.iterrows()]
                    ax_r.plot(s["f"], rho, marker=".", ms=2.5, color=c, gid=f"rho:{a:g}:{p:g}")
                    if "vx_within_1" in s:
                        ax_v.plot(s["f"], s["vx_within_1"], marker=".", ms=2.5, color=c,
                                  gid=f"vx:{a:g}:{p:g}")
                if (a, p) in lines:
                    for ax in (ax_n, ax_r, ax_v):
                        _shade_reversals(ax, line_reversals(lines[(a, p)])[0], c)
            ax_n.set_title(f"α = {a:g}", fontsize="small", loc="left")
            ax_v.axhline(0.0, color="k", lw=0.5, ls=":")
            ax_v.set_xlabel("f (Hz)")
        axes[0, 0].set_yscale("log")
        axes[0, 0].set_ylabel("collisions / period")
        axes[1, 0].set_ylabel("phase locking ρ")
        axes[1, 0].set_ylim(0, 1)
        axes[2, 0].set_ylabel("vx lag-1 corr.")
        axes[0, 0].legend(fontsize="x-small")
        return save_figure(fig, out_dir)


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """Add the states scene's table (the states reached, from its store when there is one),
    the reversal table (the collisions and states at each reversal) and the conveyor's reversals
    (from the transport study's committed tables in ``out_dir``) to ``tables``, draw the three
    figures into ``out_dir``; returns their files (none without the map's table)."""
    t = tables.get(TABLE)
    if t is None or t.empty:
        return []
    states = stores.get(STATES_SCENE)
    if states and Path(states).exists():
        tables[STATES_TABLE] = states_table(states)
    tables[f"{SCENE}_reversals"] = reversal_table(tables)
    out = Path(out_dir)
    committed = {n: pd.read_csv(out / n) for n in CONVEYOR_FILES if (out / n).is_file()}
    if committed:
        tables[f"{SCENE}_conveyor"] = conveyor_reversals(committed)
    figs = [figure_map(t, out_dir), figure_lines(t, out_dir), figure_mechanism(tables, out_dir)]
    return [p for fig in figs for p in figure_files(out_dir, fig.get_label())]
