"""The basins figures:

- ``fig_basins_grids``: the final state of every grid cell (floor phase × drop height, floor
  phase × launch speed) at a few frequencies (drawn from the store; without it, not drawn);
- ``fig_basins_shares``: the share of each final state against f with Wilson intervals, and
  the basin entropy of the boundary boxes against ln 2;
- ``fig_basins_lifetimes``: the transients' median lifetime and escape rate against f, and
  the share of particles still irregular against time at a few frequencies;
- ``fig_basins_dmix``: D_mix(f, T) at T = 5, 10, 20 s per ensemble with bootstrap intervals,
  beside the committed per-protocol D(f) of the protocol study (figures/protocol_curves.csv,
  definition 'all') where present.

Blank values are left out and blank intervals drawn without a bar, never as zero.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import colormaps, colors, rc_context
from matplotlib.patches import Patch, Rectangle

from bbb.analysis import states as st
from bbb.analysis.basins import LOG2

from ...plot.style import PAGE, STYLE, family_color, figure_files, new_figure, save_figure
from .tables import NOT_COMPUTED, PEAK_TIMES, SCENE

__all__ = ["CAPTIONS", "draw"]

_STATE_COLORS = {"unknown": "#bbbbbb", "stuck": "#4d4d4d", "locked_1": "#1f77b4",
                 "locked_k": "#9467bd", "chaotic": "#ff7f0e", "diffusing": "#d62728"}
_ABSENT_HATCH, _ABSENT_EDGE = "////", "#999999"
_SHOW_F = (48.0, 52.0, 54.0, 56.0, 58.0, 60.0)

CAPTIONS = {
    "fig_basins_grids": (
        "Basins on the paper's floor (α = 0.7, R = 15 mm), scene basins: the state each grid "
        "cell ends in after 20 s (the last 0.5 s window's label, calibrated classifier), rows: "
        "dropped (floor phase × drop height 0–2 mm) and launched (floor phase × launch speed "
        "0–200 mm/s), both at 0.5 mm from an arc's centre; columns: frequencies."),
    "fig_basins_shares": (
        "Share of each final state against f (Wilson 95 % intervals), per ensemble; bottom: "
        "the basin entropy of the boundary boxes S_bb (4 × 4 cells), dotted: ln 2, above which "
        "the boundary is fractal (Daza et al. 2016)."),
    "fig_basins_lifetimes": (
        "Transients: (a) median lifetime of the particles that settle (stuck or locked), "
        "bootstrap 95 % intervals (no bar: a blank interval); (b) the escape rate from the "
        "transient after the first window; (c) the share of particles in an irregular state "
        "(chaotic or diffusing) against time at a few frequencies (dropped)."),
    "fig_basins_dmix": (
        "D_mix(f, T) = Σ share_c(T)·D_c of the states' classes (stuck, locked 1/1, locked "
        "period-k, irregular), bootstrap 95 % intervals, at T = 5, 10, 20 s per ensemble "
        "(claim B1 locates its maximum), beside the committed protocol curves D(f) (grey, "
        "definition 'all', same T where present). Shaded: 54 ± 2 Hz."),
}


def draw(tables: dict, stores, out: Path) -> list[Path]:
    made = []
    with rc_context(STYLE):
        if stores.get(SCENE) and os.path.exists(stores[SCENE]):
            made += _grids(stores[SCENE], out)
        made += _shares(tables, out)
        made += _lifetimes(tables, out)
        made += _dmix(tables, out)
    return made


def _grids(path: str, out: Path) -> list[Path]:
    from ...store.study_store import StudyStore
    from .tables import grids

    g = grids(StudyStore.open(path))
    fams = list(dict.fromkeys(k[1] for k in g))
    fs = [f for f in _SHOW_F if any(k[0] == f for k in g)] or sorted({k[0] for k in g})[:6]
    if not fams or not fs:
        return []
    cmap = colors.ListedColormap([_STATE_COLORS[n] for n in st.LABELS])
    # a cell whose chunk is not done has no state: left transparent over a hatch, never a colour
    cmap.set_bad((0.0, 0.0, 0.0, 0.0))
    absent = False
    fig, axes = _fig("fig_basins_grids", len(fams), len(fs),
                     (PAGE, 0.9 * PAGE * len(fams) / len(fs) + 0.6))
    for i, fam in enumerate(fams):
        for j, f in enumerate(fs):
            ax = axes[i][j]
            grid = g.get((f, fam))
            if grid is None:
                ax.set_axis_off()
                continue
            missing = grid == NOT_COMPUTED
            if missing.any():
                absent = True
                ax.add_patch(Rectangle((0, 0), 1, 1, fill=False, hatch=_ABSENT_HATCH,
                                       edgecolor=_ABSENT_EDGE, lw=0, zorder=0))
            ax.imshow(np.ma.masked_where(missing, grid).T, origin="lower", cmap=cmap, vmin=-0.5,
                      vmax=len(st.LABELS) - 0.5, extent=(0, 1, 0, 1), aspect="auto", interpolation="nearest")
            ax.set_xticks([0, 0.5, 1])
            ax.set_yticks([])
            if i == 0:
                ax.set_title(f"{f:g} Hz")
            if i == len(fams) - 1:
                ax.set_xlabel("floor phase")
            if j == 0:
                ax.set_ylabel("height 0–2 mm" if fam == "dropped" else "speed 0–200 mm/s"
                              if fam == "launched" else fam)
    handles = [Patch(color=_STATE_COLORS[n], label=n) for n in st.LABELS]
    if absent:
        handles.append(Patch(facecolor="white", edgecolor=_ABSENT_EDGE, hatch=_ABSENT_HATCH,
                             label="not computed"))
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), frameon=False)
    return _save(fig, out)


def _shares(tables, out: Path) -> list[Path]:
    s, ent = tables.get("states"), tables.get("entropy")
    if s is None or s.empty:
        return []
    fams = list(dict.fromkeys(s["family"]))
    fig, axes = _fig("fig_basins_shares", 2, len(fams), (PAGE, 0.75 * PAGE), sharex=True)
    for j, fam in enumerate(fams):
        t = s[s["family"] == fam].sort_values("f")
        ax = axes[0][j]
        for name in st.LABELS:
            col = f"final_{name}"
            if col not in t or not (t[col] > 0).any():
                continue
            _errorbar(ax, t["f"], t[col], t[f"{col}_lo"], t[f"{col}_hi"], _STATE_COLORS[name], name)
        ax.set_title(fam)
        ax.set_ylim(-0.02, 1.02)
        if j == 0:
            ax.set_ylabel("share of final states")
        ax.legend(fontsize="x-small", frameon=False)
        ax = axes[1][j]
        if ent is not None and not ent.empty:
            e = ent[ent["family"] == fam].sort_values("f")
            ax.plot(e["f"], e["S_bb"], "o-", color=family_color(fam), ms=3)
        ax.axhline(LOG2, ls=":", color="k", lw=0.8)
        ax.set_xlabel("f (Hz)")
        if j == 0:
            ax.set_ylabel("S_bb")
    return _save(fig, out)


def _lifetimes(tables, out: Path) -> list[Path]:
    s, sh = tables.get("states"), tables.get("shares")
    if s is None or s.empty:
        return []
    fig, axes = _fig("fig_basins_lifetimes", 1, 3, (PAGE, 0.36 * PAGE))
    for fam in dict.fromkeys(s["family"]):
        t = s[s["family"] == fam].sort_values("f")
        c = family_color(fam)
        _errorbar(axes[0][0], t["f"], t["lifetime_median"], t["lifetime_median_lo"],
                  t["lifetime_median_hi"], c, fam)
        _errorbar(axes[0][1], t["f"], t["escape_rate"], t["escape_rate_lo"], t["escape_rate_hi"],
                  c, fam)
    axes[0][0].set(xlabel="f (Hz)", ylabel="median lifetime (s)")
    axes[0][1].set(xlabel="f (Hz)", ylabel="escape rate (1/s)")
    axes[0][0].legend(fontsize="x-small", frameon=False)
    ax = axes[0][2]
    if sh is not None and not sh.empty:
        fams = list(dict.fromkeys(sh["family"]))
        d = sh[sh["family"] == fams[0]]
        cmap = colormaps["viridis"]
        fs = [f for f in _SHOW_F if f in set(d["f"])]
        for k, f in enumerate(fs):
            a = d[(d["f"] == f) & d["state"].isin(["chaotic", "diffusing"])]
            irr = a.groupby("T")["share"].sum()
            ax.plot(irr.index, irr.to_numpy(), color=cmap(k / max(1, len(fs) - 1)), label=f"{f:g} Hz")
        ax.set(xlabel="t (s)", ylabel=f"share irregular ({fams[0]})", ylim=(-0.02, 1.02))
        ax.legend(fontsize="x-small", frameon=False)
    return _save(fig, out)


def _dmix(tables, out: Path) -> list[Path]:
    d = tables.get("dmix")
    if d is None or d.empty:
        return []
    fams = list(dict.fromkeys(d["family"]))
    fig, axes = _fig("fig_basins_dmix", 1, len(PEAK_TIMES), (PAGE, 0.36 * PAGE), sharey=True)
    proto = _protocol_curves(Path(out))
    for j, T in enumerate(PEAK_TIMES):
        ax = axes[0][j]
        ax.axvspan(52.0, 56.0, color="0.92", zorder=0)
        if proto is not None:
            for _ens, c in proto[np.isclose(proto["T"], T)].groupby("ensemble"):
                c = c.sort_values("f")
                ax.plot(c["f"], c["D"], color="0.6", lw=0.8, zorder=1)
        for fam in fams:
            t = d[(d["family"] == fam) & np.isclose(d["T"], T)].sort_values("f")
            _errorbar(ax, t["f"], t["D_mix"], t["D_mix_lo"], t["D_mix_hi"], family_color(fam), fam)
        ax.set(title=f"T = {T:g} s", xlabel="f (Hz)")
        if j == 0:
            ax.set_ylabel("D_mix (mm²/s)")
            ax.legend(fontsize="x-small", frameon=False)
    return _save(fig, out)


def _protocol_curves(out: Path) -> pd.DataFrame | None:
    """The protocol study's committed curves beside the report (definition 'all'), if there."""
    for p in (out / "protocol_curves.csv", Path(__file__).resolve().parents[3] / "figures"
              / "protocol_curves.csv"):
        if p.is_file():
            c = pd.read_csv(p)
            return c[c["definition"] == "all"]
    return None


def _errorbar(ax, x, y, lo, hi, color, label):
    x, y, lo, hi = (np.asarray(v, dtype=float) for v in (x, y, lo, hi))
    ok = np.isfinite(y)
    ax.plot(x[ok], y[ok], "o-", color=color, ms=3, lw=1, label=label)
    bar = ok & np.isfinite(lo) & np.isfinite(hi)
    ax.vlines(x[bar], lo[bar], hi[bar], color=color, lw=0.8)



def _fig(name: str, rows: int, cols: int, size, **kw):
    fig = new_figure(name, size, layout="constrained")
    return fig, fig.subplots(rows, cols, squeeze=False, **kw)


def _save(fig, out: Path) -> list[Path]:
    save_figure(fig, out)
    return figure_files(out, fig.get_label())
