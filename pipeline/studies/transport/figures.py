"""The transport figure: (a) drift v(f) and (b) D(f) about the drift, with their bootstrap
CIs, one curve per (tilt φ, throw ψ).  Units: f Hz, v mm/s, D mm²/s."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import pandas as pd
from matplotlib import rc_context

from ..klages2004.figures import STYLE, _new_figure, _save, figure_files
from .claims import LABELS, SCENES

__all__ = ["draw", "figure_transport"]


def figure_transport(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
                     name: str = "fig_transport"):
    """Two panels from ``tables[scene]`` (diffusion tables with v, D_drift); returns the Figure
    (writes PNG + PDF given ``out_dir``)."""
    with rc_context(STYLE):
        fig = _new_figure(name, (7.0, 5.6))
        ax_v, ax_d = fig.subplots(2, 1, sharex=True)
        for i, sc in enumerate(SCENES):
            t = tables.get(sc)
            if t is None or "v" not in t:
                continue
            t = t.sort_values("f")
            kw = dict(fmt="o-", ms=2.5, lw=1, capsize=0, color=f"C{i}", label=LABELS[sc])
            ax_v.errorbar(t["f"], t["v"], yerr=[t["v"] - t["v_lo"], t["v_hi"] - t["v"]], **kw)
            ax_d.errorbar(t["f"], t["D_drift"], yerr=[t["D_drift"] - t["D_drift_lo"],
                                                      t["D_drift_hi"] - t["D_drift"]], **kw)
        ax_v.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        ax_v.set_ylabel("drift v (mm/s)")
        ax_v.legend(fontsize="small", ncol=2)
        ax_v.text(0.01, 0.92, "(a)", transform=ax_v.transAxes)
        ax_d.set_yscale("symlog", linthresh=1.0)
        ax_d.set_ylabel("D about the drift (mm²/s)")
        ax_d.set_xlabel("f (Hz)")
        ax_d.text(0.01, 0.92, "(b)", transform=ax_d.transAxes)
        return _save(fig, out_dir)


def draw(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: the figure from ``tables["<scene>_diffusion"]``; the files written."""
    fig = figure_transport({sc: tables.get(f"{sc}_diffusion") for sc in SCENES}, out_dir)
    return figure_files(out_dir, fig.get_label())
