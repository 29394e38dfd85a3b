"""The impact-phase figures, drawn from the scene's ``impacts`` table only:

- ``fig_impacts_phase``: per family, the floor phase at the collisions against f as a heat
  map (the share per bin over the uniform share 1/24), the floor's upward half marked; and
  the share of impacts in the upward half against f with its interval (claim I1);
- ``fig_impacts_vx``: the correlation of the post-collision vx n collisions apart, about each
  particle's own mean, against f for n = 1 … lags (claim I2 reads n = 1), the pooled one
  beside it; and both against the lag at a few frequencies.

Intervals: 95 % bootstrap over particles (the table's); a blank statistic is left out and a
blank interval drawn without a bar, never as zero.  Units from :mod:`pipeline.tables.units`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import colors, rc_context

from ...plot.style import PAGE, STYLE, family_color, figure_files, new_figure, save_figure
from ...tables.units import column_unit
from ...workflow.observables.impacts import BINS
from .claims import F_FROM, SCENE

__all__ = ["CAPTIONS", "draw", "figure_phase", "figure_vx", "lags"]

CAPTIONS = {
    "fig_impacts_phase": (
        "Where in the floor's period the particles hit the paper's floor (scene impacts; "
        "collisions from 5 s on, up to 1000 per particle). Top, per family: the share of "
        f"impacts in each of {BINS} bins of the floor phase ω t mod 2π over the uniform share "
        f"1/{BINS} (1: uniform; white: no impacts, the particles rest on the floor); dashed: "
        "the floor (at −A sin ω t) moves up between them. Bottom: the share of impacts while "
        "the floor moves up, 95 % bootstrap intervals over particles (no bar: a blank interval); "
        f"dotted: 0.5, a uniform phase; shaded: f < {F_FROM:g} Hz, outside claim I1's scope."),
    "fig_impacts_vx": (
        "The horizontal velocity's memory across collisions (scene impacts). (a) The correlation "
        "of the post-collision vx n collisions apart about each particle's own mean against f, "
        "n = 1 … 5, from rest (solid) and launched (dashed), 95 % bootstrap intervals over "
        "particles (claim I2 reads n = 1, f ≥ "
        f"{F_FROM:g} Hz; shaded below). (b) The same against the lag at a few frequencies "
        "(filled), beside the correlation of the pooled pairs (open), which differences "
        "between the particles' mean vx push toward +1; from rest."),
}


def lags(t: pd.DataFrame) -> list[int]:
    """The lags the table holds (its ``vx_within_<n>`` columns), in order."""
    return sorted(int(m.group(1)) for c in t.columns if (m := re.fullmatch(r"vx_within_(\d+)", c)))


def _label(name: str, column: str) -> str:
    u = column_unit(column)
    return name if u in ("1", "") else f"{name} ({u})"


def _errorbar(ax, f, v, lo, hi, **kw) -> None:
    """Values with their intervals; a blank interval without a bar (never zero width)."""
    f, v, lo, hi = (np.asarray(a, float) for a in (f, v, lo, hi))
    ok = ~np.isnan(v)
    ax.plot(f[ok], v[ok], **kw)
    bar = ok & ~np.isnan(lo) & ~np.isnan(hi)
    kw = {k: x for k, x in kw.items() if k in ("color",)}
    ax.errorbar(f[bar], v[bar], yerr=[v[bar] - lo[bar], hi[bar] - v[bar]], fmt="none",
                elinewidth=0.6, capsize=1.5, **kw)


def _edges(v: np.ndarray) -> np.ndarray:
    if v.size == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def _shade_out_of_scope(ax, f: np.ndarray) -> None:
    if f.size and f.min() < F_FROM:
        ax.axvspan(f.min() - 1, F_FROM - 1, color="0.92", lw=0, zorder=0)


def figure_phase(t: pd.DataFrame, out_dir: str | os.PathLike | None):
    """The phase heat maps per family and the upward share against f."""
    families = list(dict.fromkeys(t["family"]))
    with rc_context(STYLE):
        fig = new_figure("fig_impacts_phase", (PAGE, 0.3 * PAGE * (len(families) + 1)),
                         layout="constrained")
        axes = fig.subplots(len(families) + 1, 1, sharex=True)
        phase = (np.arange(BINS + 1) / BINS) * 360.0
        cmap = colors.LinearSegmentedColormap.from_list("phase", ["white", "tab:blue", "k"])
        vmax = max(1.0, float(np.nanmax(t[[f"phase_{b}" for b in range(BINS)]].to_numpy(float)
                                         * BINS)))
        mesh = None
        for ax, fam in zip(axes, families, strict=False):
            s = t[t["family"] == fam].sort_values("f")
            f = s["f"].to_numpy(float)
            dens = s[[f"phase_{b}" for b in range(BINS)]].to_numpy(float).T * BINS
            mesh = ax.pcolormesh(_edges(f), phase, np.ma.masked_invalid(dens), cmap=cmap,
                                 norm=colors.Normalize(0.0, vmax), shading="flat")
            for y in (90.0, 270.0):
                ax.axhline(y, ls="--", color="tab:red", lw=0.7)
            ax.set_yticks([0, 90, 180, 270, 360])
            ax.set_ylabel("floor phase ω t mod 2π (°)")
            ax.set_title(f"family {fam}: impacts per phase bin / uniform share")
        if mesh is not None:
            fig.colorbar(mesh, ax=list(axes[:-1]), label="share × 24 (1: uniform)", shrink=0.9)
        ax = axes[-1]
        for i, fam in enumerate(families):
            s = t[t["family"] == fam].sort_values("f")
            _errorbar(ax, s["f"], s["up_share"], s["up_share_lo"], s["up_share_hi"], marker="o",
                      ms=2.5, color=family_color(fam, i), label=fam,
                      ls="-" if i == 0 else "--")
        ax.axhline(0.5, ls=":", color="k", lw=0.7)
        _shade_out_of_scope(ax, t["f"].to_numpy(float))
        ax.set_ylabel(_label("share of impacts, floor moving up", "up_share"))
        ax.set_xlabel(_label("f", "f"))
        ax.set_title("impacts while the floor moves up (claim I1)")
        ax.legend(loc="lower right")
        return save_figure(fig, out_dir)


def figure_vx(t: pd.DataFrame, out_dir: str | os.PathLike | None, at=(60.0, 70.0, 80.0, 90.0,
                                                                          100.0)):
    """The within-particle correlation against f for every lag; both against the lag at
    the frequencies ``at`` the table holds."""
    families = list(dict.fromkeys(t["family"]))
    ns = lags(t)
    with rc_context(STYLE):
        fig = new_figure("fig_impacts_vx", (PAGE, 0.38 * PAGE), layout="constrained")
        ax_f, ax_n = fig.subplots(1, 2, width_ratios=(1.6, 1.0))
        for i, fam in enumerate(families):
            s = t[t["family"] == fam].sort_values("f")
            for n in ns:
                c = f"vx_within_{n}"
                _errorbar(ax_f, s["f"], s[c], s[f"{c}_lo"], s[f"{c}_hi"], marker=".", ms=2.5,
                          color=f"C{n - 1}", ls="-" if i == 0 else "--",
                          label=f"n = {n}" if i == 0 else None)
        ax_f.axhline(0.0, ls=":", color="k", lw=0.7)
        _shade_out_of_scope(ax_f, t["f"].to_numpy(float))
        ax_f.set_xlabel(_label("f", "f"))
        ax_f.set_ylabel(_label("vx correlation n collisions apart",
                               "vx_within_1"))
        ax_f.set_title("(a) within-particle vx correlation vs f (claim I2: n = 1)")
        ax_f.legend(loc="lower right", ncol=2)
        rest = t[t["family"] == families[0]] if families else t
        x = np.asarray(ns, float)
        for j, f0 in enumerate(f for f in at if (rest["f"] == f).any()):
            r = rest[rest["f"] == f0].iloc[0]
            for name, mfc in (("vx_within", None), ("vx_corr", "none")):
                v, lo, hi = (np.array([r.get(f"{name}_{n}{s}", np.nan) for n in ns], float)
                             for s in ("", "_lo", "_hi"))
                _errorbar(ax_n, x + 0.06 * (j - 2), v, lo, hi, marker="o", ms=3,
                          color=f"C{j}", mfc=mfc or f"C{j}", ls="-" if mfc is None else ":",
                          label=f"{f0:g} Hz" if mfc is None else None)
        ax_n.axhline(0.0, ls=":", color="k", lw=0.7)
        ax_n.set_xticks(x)
        ax_n.set_xlabel("lag n (collisions)")
        ax_n.set_ylabel(_label("vx correlation", "vx_within_1"))
        ax_n.set_title(f"(b) vs lag, family {families[0] if families else '–'}: "
                       "within (filled), pooled (open)")
        ax_n.legend(loc="center right")
        return save_figure(fig, out_dir)


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """Draw both figures from the impacts table into ``out_dir``; returns their files (none
    without the table)."""
    t = tables.get(SCENE)
    if t is None or t.empty:
        return []
    figs = [figure_phase(t, out_dir), figure_vx(t, out_dir)]
    return [p for fig in figs for p in figure_files(out_dir, fig.get_label())]
