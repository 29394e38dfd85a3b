"""The onset figure, drawn from the two maps' diffusion tables only:

- ``fig_onset_theory``: (a) the onset of diffusion from rest on every (α, R) line of the
  D(f, R) map against R, with its CI, beside the two predictions -- the first lift-off
  f(Γ = 1) (horizontal, O1) and f_c(α) (vertical, O2) -- and their band ± the grid step;
  (b) the same on every (α, depth) line of the sine floor.

A line without an onset is drawn as an open marker at the top of the axis (named in the
legend), never as a value.  Units: Hz, mm.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import rc_context

from ...plot.style import PAGE, STYLE, figure_files, new_figure, save_figure
from .claims import MAP, SINE
from .lines import AXES, grid_lines, onset, step_of
from .predictions import load

__all__ = ["CAPTIONS", "draw", "figure_onset", "onset_rows"]

CAPTIONS = {
    "fig_onset_theory": (
        "Onset theory against the map lines. The onset of diffusion from rest (the lowest f "
        "whose D_lo exceeds 1 % of the line's largest D; bars: its CI, from D_hi and D_lo "
        "crossing, ± half the grid step) on (a) every (α, R) line of the arcs' D(f, R) map "
        "(scene onset_map) and (b) every (α, depth) line of the sine floor (scene onset_sine). "
        "Dashed, one per α: the vertical prediction f_c(α), where the chattering cycle from "
        "rest stops ending within its period (exact flat-floor map), with its band ± the grid "
        "step shaded; dotted black: the horizontal prediction at the cusp, the first lift-off "
        "f(Γ = 1). Open markers at the top: a line without an onset in the scene's range."),
}
_COLORS = {0.5: "tab:green", 0.7: "tab:blue", 0.9: "tab:red"}


def onset_rows(table: pd.DataFrame | None, scene: str) -> pd.DataFrame:
    """One row per line of a map: alpha, the axis value, onset, onset_lo, onset_hi (Hz)."""
    axis = AXES[scene]
    rows = []
    for (a, v), line in grid_lines(table, axis).items():
        q = onset(line)
        rows.append({"alpha": a, axis: v, "onset": q.value, "onset_lo": q.lo, "onset_hi": q.hi})
    return pd.DataFrame(rows, columns=["alpha", axis, "onset", "onset_lo", "onset_hi"])


def _panel(ax, rows: pd.DataFrame, axis: str, preds: dict, step: float, top: float,
           logx: bool) -> None:
    for a in sorted(rows["alpha"].unique()) if len(rows) else []:
        c = _COLORS.get(round(a, 2), "k")
        fc = preds["alpha"][f"{a:g}"]["f_c"]
        ax.axhspan(fc - step, fc + step, color=c, alpha=0.12, lw=0)
        ax.axhline(fc, color=c, ls="--", lw=0.8)
        r = rows[rows["alpha"] == a].sort_values(axis)
        x, v = r[axis].to_numpy(float), r["onset"].to_numpy(float)
        lo = np.where(np.isfinite(r["onset_lo"]), r["onset_lo"], v)
        hi = np.where(np.isfinite(r["onset_hi"]), r["onset_hi"], v)
        ok = np.isfinite(v)
        ax.errorbar(x[ok], v[ok], yerr=[v[ok] - lo[ok], hi[ok] - v[ok]], fmt="o-", ms=3,
                    color=c, capsize=2, lw=0.8, label=f"α = {a:g} (f_c = {fc:.1f} Hz)")
        if (~ok).any():
            ax.plot(x[~ok], np.full((~ok).sum(), top), "o", mfc="none", color=c,
                    label=f"α = {a:g}: no onset ≤ {top:g} Hz")
    ax.axhline(preds["f_liftoff"], color="k", ls=":", lw=0.9,
               label=f"f(Γ = 1) = {preds['f_liftoff']:.1f} Hz")
    if logx:
        ax.set_xscale("log")
    ax.set_ylabel("onset f (Hz)")


def figure_onset(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None):
    preds = load()
    with rc_context(STYLE):
        fig = new_figure("fig_onset_theory", (PAGE, 0.85 * PAGE), layout="constrained")
        axes = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1.0]}, sharey=True)
        for ax, scene, logx, title, where in (
                (axes[0], MAP, True, "(a) arcs: onset against R", "upper center"),
                (axes[1], SINE, False, "(b) sine floor: against depth", "upper left")):
            t = tables.get(f"{scene}_diffusion")
            top = float(t["f"].max()) if t is not None and len(t) else 70.0
            _panel(ax, onset_rows(t, scene), AXES[scene], preds, step_of(scene), top, logx)
            ax.set_xlabel(f"{AXES[scene]} (mm)")
            ax.set_title(title)
            ax.legend(fontsize="x-small", loc=where)
        return save_figure(fig, out_dir)


def draw(tables: dict, stores: Mapping[str, str], out_dir: Path) -> list[Path]:
    """The study's figure (its tables are the scenes' reduce tables)."""
    if all(tables.get(f"{s}_diffusion") is None for s in (MAP, SINE)):
        return []
    fig = figure_onset(tables, out_dir)
    return figure_files(out_dir, fig.get_label())
