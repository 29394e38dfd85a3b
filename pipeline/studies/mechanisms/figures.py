"""The mechanisms figure: (a) D(f) beside its Green–Kubo truncations D_0, D_1 and the converged
D_∞; (b) the largest Lyapunov exponent λ(f) with its CI; (c) the creeping fraction.

Drawn from the reduce tables of the mechanisms scene only: ``diffusion`` (D from the MSD) and
``mechanisms`` (:mod:`pipeline.mechanisms`).  Units: f Hz, D mm²/s, λ 1/s.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import rc_context

from ..figure_style import STYLE, figure_files, new_figure, save_figure

__all__ = ["draw", "figure_mechanisms"]


def figure_mechanisms(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
                      name: str = "fig_mechanisms"):
    """The three-panel figure (returns the Figure; writes PNG + PDF given ``out_dir``)."""
    mech = tables["mechanisms"].sort_values("f")
    diff = tables.get("diffusion")
    f = mech["f"].to_numpy()
    with rc_context(STYLE):
        fig = new_figure(name, (7.0, 6.2))
        ax_d, ax_l, ax_c = fig.subplots(3, 1, sharex=True)
        if diff is not None and "D" in diff:
            d = diff.sort_values("f")
            ax_d.errorbar(d["f"], d["D"], yerr=[d["D"] - d["D_lo"], d["D_hi"] - d["D"]], fmt="o-",
                          ms=3, color="k", label="D (MSD)")
        for col, style, label in (("D_inf", "s--", "D$_\\infty$ (Green–Kubo)"),
                                  ("D_1", "^:", "D$_1$"), ("D_0", "v:", "D$_0$ (random walk)")):
            if col in mech:
                ax_d.errorbar(f, mech[col], yerr=[mech[col] - mech[f"{col}_lo"],
                                                  mech[f"{col}_hi"] - mech[col]],
                              fmt=style, ms=3, label=label)
        ax_d.set_yscale("symlog", linthresh=1.0)
        ax_d.set_ylabel("D (mm²/s)")
        ax_d.legend(fontsize="small", ncol=2)
        ax_d.text(0.01, 0.92, "(a)", transform=ax_d.transAxes)
        if "lam" in mech:
            ax_l.errorbar(f, mech["lam"], yerr=[mech["lam"] - mech["lam_lo"],
                                                mech["lam_hi"] - mech["lam"]],
                          fmt="o-", ms=3, color="C3")
        ax_l.set_ylabel("λ (1/s)")
        ax_l.text(0.01, 0.88, "(b)", transform=ax_l.transAxes)
        if "frac_creep" in mech:
            ax_c.plot(f, mech["frac_creep"], "o-", ms=3, color="C2")
        ax_c.set_ylim(-0.02, 1.02)
        ax_c.set_ylabel("creeping fraction")
        ax_c.set_xlabel("f (Hz)")
        ax_c.text(0.01, 0.88, "(c)", transform=ax_c.transAxes)
        for ax in (ax_d, ax_l, ax_c):
            for x in np.unique(f[np.isin(f, (54.0, 58.0, 60.0, 62.0, 80.0))]):
                ax.axvline(x, color="0.85", lw=0.8, zorder=0)
        return save_figure(fig, out_dir)


def draw(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: draw the figure from ``tables["mechanisms"]`` (and the scene's
    diffusion table ``tables["mechanisms_diffusion"]``); returns the files written."""
    fig = figure_mechanisms({"mechanisms": tables["mechanisms"],
                             "diffusion": tables.get("mechanisms_diffusion")}, out_dir)
    return figure_files(out_dir, fig.get_label())
