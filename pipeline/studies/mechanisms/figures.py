"""The mechanisms figure: (a) D(f) beside its Green–Kubo parts D_0 and D_∞, per floor period
and per collision; (b) the split of the log contrast at each paper extremum against its grid
neighbours, random walk and memory, with paired bootstrap CIs; (c) the memory share with the
rule's edges; (d) the largest Lyapunov exponent λ(f), of all, moving and confined particles;
(e) the creeping fraction.  Still frequencies (nothing left its cell, or all creeps) shaded.

Drawn from the reduce tables of the mechanisms scene only: ``diffusion`` (D from the MSD) and
``mechanisms`` (:mod:`pipeline.tables.mechanisms`).  Units: f Hz, D mm²/s, λ 1/s.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import rc_context

from bbb.analysis.gk_contrast import calibrated_rule

from ...plot.style import STYLE, figure_files, new_figure, save_figure
from .claims import EXTREMA, SIDES, STEPS, neighbour_moves, side_contrast

__all__ = ["CAPTIONS", "draw", "figure_mechanisms"]

#: REPORT.md's captions of the figures, by file stem
CAPTIONS = {
    "fig_mechanisms": (
        "Mechanisms behind D(f) (scene mechanisms, particles from rest; shaded: still "
        "frequencies, where no particle left its cell or every recorded state creeps). (a) D "
        "from the MSD (black) beside the Green–Kubo random walk D_0 and the converged sum D_∞, "
        "per floor period (open) and per collision (filled), bootstrap 95 % CIs over particles. "
        "(b) At each of the paper's extrema (▲ max, ▼ min), the log contrast ln D_∞(f0)/D_∞(f_nb) "
        "against the lower and the upper grid neighbour split into random walk (ln of the D_0 "
        "ratio) and memory (ln of the D_∞/D_0 ratio), with paired bootstrap CIs at the "
        f"calibrated level {calibrated_rule()['ci']:.0%} (bbb/gk_contrast_rule.json); (c) the "
        "memory share of each contrast, the rule's edges 1 − θ and θ dotted (claims M1–M5); "
        "contrasts with a still neighbour are left out. (d) The largest Lyapunov exponent λ of "
        "all measured particles, of the moving ones (x spans ≥ S) and of the confined ones "
        "(rattling at a cusp or held), 95 % CIs; hollow markers without bars where the CI is "
        "degenerate (claim M6). (e) Fraction of post-collision states in the creeping band."),
}

_KIND_MARK = {"max": "▲", "min": "▼"}


def _shade_still(axes, mech: pd.DataFrame) -> None:
    if "still" not in mech:
        return
    f = mech["f"].to_numpy(float)
    half = 0.5 * (np.min(np.diff(f)) if f.size > 1 else 1.0)
    for x in f[mech["still"].fillna(False).to_numpy(bool)]:
        for ax in axes:
            ax.axvspan(x - half, x + half, color="0.9", lw=0, zorder=0)


def _panel_d(ax, mech: pd.DataFrame, diff: pd.DataFrame | None) -> None:
    f = mech["f"].to_numpy()
    if diff is not None and "D" in diff:
        d = diff.sort_values("f")
        ax.errorbar(d["f"], d["D"], yerr=[d["D"] - d["D_lo"], d["D_hi"] - d["D"]], fmt="o-",
                    ms=3, color="k", label="D (MSD)")
    for col, color, label in (("D_inf", "C0", "D$_\\infty$"), ("D_0", "C1", "D$_0$")):
        for step, mfc, name in (("", "none", "per period"), ("_coll", None, "per collision")):
            c = f"{col}{step}"
            if c not in mech:
                continue
            ax.errorbar(f, mech[c], yerr=[mech[c] - mech[f"{c}_lo"], mech[f"{c}_hi"] - mech[c]],
                        fmt="s" if col == "D_inf" else "v", ms=3, color=color,
                        mfc=mfc or color, lw=0.8, label=f"{label} {name}")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylabel("D (mm²/s)")
    ax.legend(fontsize="x-small", ncol=3, loc="lower right")


def _panels_contrast(ax_l, ax_s, mech: pd.DataFrame) -> list[str]:
    """(b) the parts of each extremum's contrasts, (c) the memory shares; returns x labels."""
    labels, x = [], 0
    for f0, kind in EXTREMA:
        r = mech[np.isclose(mech["f"], f0)]
        if r.empty:
            continue
        r = r.iloc[0]
        for side in SIDES:
            if not neighbour_moves(mech, r, side):  # no neighbour, or a still one: no split
                continue
            labels.append(f"{f0:g} {_KIND_MARK[kind]}\nvs {r[f'f_{side}']:g}")
            for si, (step, name) in enumerate(STEPS.items()):
                if f"ln_D{step}_{side}" not in mech:
                    continue
                c = side_contrast(r, step, side)
                dx = -0.2 if step == "_coll" else 0.2
                mfc = None if step == "_coll" else "none"
                for qi, (attr, color, qname) in enumerate((("total", "k", "ln D ratio"),
                                                           ("walk", "C1", "random walk"),
                                                           ("memory", "C0", "memory"))):
                    v, lo, hi = getattr(c, attr)
                    ax_l.errorbar(x + dx + 0.1 * (qi - 1), v, yerr=[[v - lo], [hi - v]], fmt="o",
                                  ms=3, color=color, mfc=mfc or color, lw=0.8,
                                  label=f"{qname}, {name}" if x == 0 else None)
                v, lo, hi = c.share
                ax_s.errorbar(x + dx, v, yerr=[[v - lo], [hi - v]], fmt="D", ms=3, color=f"C{si + 2}",
                              mfc=mfc or f"C{si + 2}", lw=0.8, label=name if x == 0 else None)
            x += 1
    for ax in (ax_l, ax_s):
        ax.set_xticks(range(len(labels)))
        ax.set_xticklabels(labels, fontsize="x-small")
        ax.set_xlim(-0.6, len(labels) - 0.4)
    ax_l.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    ax_l.set_ylabel("log contrast")
    ax_l.legend(fontsize="xx-small", ncol=3, loc="best")
    theta = float(calibrated_rule()["theta"])
    for y in (1.0 - theta, theta):
        ax_s.axhline(y, color="0.4", ls=":", lw=0.8)
    for y, text in ((0.5 * (1.0 + theta) + 0.5, "memory"), (0.5, "both"),
                    (0.5 * (1.0 - theta) - 0.5, "random walk")):
        ax_s.text(0.995, y, text, transform=ax_s.get_yaxis_transform(), va="center",
                  ha="right", fontsize="x-small", color="0.4")
    ax_s.set_ylim(-1.0, 2.0)
    ax_s.set_ylabel("memory share")
    ax_s.legend(fontsize="xx-small", loc="lower left")
    return labels


def _panel_lambda(ax, mech: pd.DataFrame) -> None:
    f = mech["f"].to_numpy()
    for col, color, label in (("lam", "C3", "all"), ("lam_move", "k", "moving"),
                              ("lam_conf", "C4", "confined")):
        if col not in mech:
            continue
        v = mech[col].to_numpy(float)
        ax.plot(f, v, "-", lw=0.6, color=color)
        ok = mech[f"{col}_lo"].notna().to_numpy() & np.isfinite(v)
        ax.errorbar(f[ok], v[ok], yerr=[v[ok] - mech[f"{col}_lo"][ok], mech[f"{col}_hi"][ok]
                                        - v[ok]], fmt="o", ms=3, color=color, label=label)
        bad = ~ok & np.isfinite(v)
        if bad.any():
            ax.plot(f[bad], v[bad], "o", ms=4, mfc="none", color=color,
                    label=f"{label}: CI degenerate")
    ax.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    ax.set_ylabel("λ (1/s)")
    ax.legend(fontsize="x-small", ncol=2, loc="lower right")


def figure_mechanisms(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
                      name: str = "fig_mechanisms"):
    """The five-panel figure (returns the Figure; writes PNG + PDF given ``out_dir``)."""
    mech = tables["mechanisms"].sort_values("f").reset_index(drop=True)
    diff = tables.get("diffusion")
    with rc_context(STYLE):
        fig = new_figure(name, (7.0, 11.0))
        gs = fig.add_gridspec(5, 1, height_ratios=(1.2, 1.0, 0.8, 1.0, 0.5))
        ax_d = fig.add_subplot(gs[0])
        ax_l, ax_s = fig.add_subplot(gs[1]), fig.add_subplot(gs[2])
        ax_lam = fig.add_subplot(gs[3], sharex=ax_d)
        ax_c = fig.add_subplot(gs[4], sharex=ax_d)
        _panel_d(ax_d, mech, diff)
        if "ln_D_dn" in mech:
            _panels_contrast(ax_l, ax_s, mech)
        if "lam" in mech:
            _panel_lambda(ax_lam, mech)
        if "frac_creep" in mech:
            ax_c.plot(mech["f"], mech["frac_creep"], "o-", ms=3, color="C2")
        ax_c.set_ylim(-0.02, 1.02)
        ax_c.set_ylabel("creeping\nfraction")
        ax_c.set_xlabel("f (Hz)")
        _shade_still((ax_d, ax_lam, ax_c), mech)
        for ax in (ax_d, ax_lam, ax_c):
            for f0, _ in EXTREMA:
                ax.axvline(f0, color="0.8", lw=0.8, ls="--", zorder=0)
        for ax, letter in zip((ax_d, ax_l, ax_s, ax_lam, ax_c), "abcde", strict=True):
            ax.text(0.01, 0.9, f"({letter})", transform=ax.transAxes)
        return save_figure(fig, out_dir)


def draw(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: draw the figure from ``tables["mechanisms"]`` (and the scene's
    diffusion table ``tables["mechanisms_diffusion"]``); returns the files written."""
    fig = figure_mechanisms({"mechanisms": tables["mechanisms"],
                             "diffusion": tables.get("mechanisms_diffusion")}, out_dir)
    return figure_files(out_dir, fig.get_label())
