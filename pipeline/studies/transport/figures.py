"""The transport figures: (a) drift v(f) and (b) D(f) about the drift, with their bootstrap
CIs, one curve per (tilt φ, throw ψ); hollow markers where the drift is not steady (the
ensemble accelerates: v and D are window means there), crossed where D about the drift is
not diffusive (its MSD still steepens over the fit lags: particles running at different
speeds, or velocity memory as long as the lags).  And the sliding regime: v(f) on one
floor per contact model, with the lift-off frequency marked, and the time held and sliding.
Units: f Hz, v mm/s, D mm²/s."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import pandas as pd
from matplotlib import rc_context

from ..figure_style import STYLE, figure_files, new_figure, save_figure
from .claims import (
    COMBINED,
    HOPPING,
    LABELS,
    SLIDING,
    SLIDING_GEOMETRY,
    SLIDING_LABELS,
    line_tables,
    sliding_liftoff,
)

__all__ = ["CAPTIONS", "draw", "figure_transport", "figure_sliding"]

#: REPORT.md's captions of the figures, by file stem
CAPTIONS = {
    "fig_transport": (
        "Transport on a vibro-conveyor at the paper's parameters: (a) drift v(f) and (b) D about "
        "the drift, bootstrap 95 % CIs over particles, one curve per (tilt φ, throw ψ); hollow "
        "markers where the drift is not steady (window means), crossed where D about the drift "
        "is not diffusive (its MSD still steepens over the fit lags: particles running at "
        "different speeds, some stuck, or velocity memory as long as the lags; bbb.analysis.transport). "
        "On the level floor (φ = 0°, ψ = 90°) every particle's mirror image counts: v = 0 "
        "exactly, by construction, without a CI. Dashed, without CIs: the floors both tilted "
        "and thrown (φ = 2°, 5° with ψ = 60°, 30°), drawn, not judged by the claims. Scene "
        "transport, a map of tilt φ × throw ψ (one line per floor)."),
    "fig_transport_sliding": (
        "The sliding regime: drift v(f) on a level floor of the paper's arcs thrown at ψ = 30°, "
        "under the stick model and Coulomb friction μ = 0.3, bootstrap 95 % CIs; dashed: the "
        "lowest lift-off frequency of this floor (bbb.analysis.liftoff), shaded below it; (b) the "
        "fraction of the run each model spends held at rest on the floor (dashed) and sliding "
        "(solid), bootstrap 95 % CIs over particles, the rest in flight. Scene "
        "transport_sliding, a map with one line per contact model (claim T5)."),
}


def figure_transport(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
                     name: str = "fig_transport"):
    """Two panels from ``tables[line]`` (each line's diffusion table with v, D_drift: the five
    judged floors with CIs, the combined ones dashed); returns the Figure (writes PNG + PDF
    given ``out_dir``)."""
    with rc_context(STYLE):
        fig = new_figure(name, (7.0, 5.6))
        ax_v, ax_d = fig.subplots(2, 1, sharex=True)
        for i, sc in enumerate(HOPPING):
            t = tables.get(sc)
            if t is None or "v" not in t:
                continue
            t = t.sort_values("f")
            c = f"C{i}"
            ax_v.plot(t["f"], t["v"], "-", lw=1, color=c, label=LABELS[sc])
            ax_d.plot(t["f"], t["D_drift"], "-", lw=1, color=c)
            steady = t["steady"].fillna(True).astype(bool) if "steady" in t else True
            for sel, mfc in ((t[steady], c), (t[~steady], "none")):  # hollow: not steady
                kw = dict(fmt="o", ms=3, capsize=0, color=c, mfc=mfc)
                ax_v.errorbar(sel["f"], sel["v"], yerr=[sel["v"] - sel["v_lo"],
                                                        sel["v_hi"] - sel["v"]], **kw)
                ax_d.errorbar(sel["f"], sel["D_drift"], yerr=[sel["D_drift"] - sel["D_drift_lo"],
                                                              sel["D_drift_hi"] - sel["D_drift"]],
                              **kw)
            if "diffusive" in t:  # crossed: D about the drift is a window slope there
                bad = t[~t["diffusive"].fillna(True).astype(bool)]
                for ax, col in ((ax_v, "v"), (ax_d, "D_drift")):
                    ax.plot(bad["f"], bad[col], "x", ms=7, mew=1.2, color=c, zorder=5)
        for i, sc in enumerate(COMBINED, start=len(HOPPING)):  # drawn, not judged: no CIs
            t = tables.get(sc)
            if t is None or "v" not in t:
                continue
            t = t.sort_values("f")
            kw = dict(ls="--", lw=0.8, marker=".", ms=2.5, color=f"C{i}")
            ax_v.plot(t["f"], t["v"], label=LABELS[sc], **kw)
            ax_d.plot(t["f"], t["D_drift"], **kw)
        ax_v.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        ax_v.set_yscale("symlog", linthresh=1.0)
        ax_v.set_ylabel("drift v (mm/s)")
        ax_d.legend(*ax_v.get_legend_handles_labels(), fontsize="x-small", loc="center left",
                    bbox_to_anchor=(0.0, 0.62))
        ax_v.text(0.01, 0.92, "(a)", transform=ax_v.transAxes)
        ax_d.set_yscale("symlog", linthresh=1.0)
        ax_d.set_ylim(bottom=0.0)  # D of particles at rest is 0 within rounding (±1e-5)
        ax_d.set_ylabel("D about the drift (mm²/s)")
        ax_d.set_xlabel("f (Hz)")
        ax_d.text(0.01, 0.92, "(b)", transform=ax_d.transAxes)
        return save_figure(fig, out_dir)


def figure_sliding(tables: Mapping[str, pd.DataFrame], out_dir: str | os.PathLike | None = None,
                   name: str = "fig_transport_sliding",
                   contact: Mapping[str, pd.DataFrame] | None = None):
    """(a) Drift v(f) with its CI per contact model on the sliding scenes' floor, the lift-off
    frequency dashed (sliding regime to its left); (b), given ``contact`` (the scenes' contact
    tables), the fraction of time held at rest (dashed) and sliding (solid) per model, with
    their CIs: what is left is flight.  Returns the Figure (PNG + PDF given ``out_dir``)."""
    f_lift = sliding_liftoff()
    contact = {sc: t for sc, t in (contact or {}).items() if t is not None and len(t)}
    with rc_context(STYLE):
        fig = new_figure(name, (7.0, 5.6 if contact else 3.4))
        axes = fig.subplots(2, 1, sharex=True) if contact else [fig.subplots()]
        ax = axes[0]
        for i, (sc, _, _) in enumerate(SLIDING):
            t = tables.get(sc)
            if t is None or "v" not in t:
                continue
            t = t.sort_values("f")
            ax.errorbar(t["f"], t["v"], yerr=[t["v"] - t["v_lo"], t["v_hi"] - t["v"]], fmt="o-",
                        ms=3, lw=1, capsize=0, color=f"C{i}", label=SLIDING_LABELS[sc])
        if contact:
            ax_c = axes[1]
            for i, (sc, _, _) in enumerate(SLIDING):
                t = contact.get(sc)
                if t is None:
                    continue
                t = t.sort_values("f")
                for col, ls, what in (("slide_frac", "-", "sliding"), ("held_frac", "--", "held")):
                    ax_c.plot(t["f"], t[col], ls, lw=1, color=f"C{i}",
                              label=f"{SLIDING_LABELS[sc]}: {what}")
                    ax_c.fill_between(t["f"], t[f"{col}_lo"], t[f"{col}_hi"], color=f"C{i}",
                                      alpha=0.2, lw=0)
            ax_c.set_ylim(-0.02, 1.02)
            ax_c.set_ylabel("fraction of time")
            # both in the band where contact fractions sit at 0 or 1 (sliding regime, above
            # the low-Γ slips): clear of every curve
            ax_c.legend(fontsize="x-small", loc="center", bbox_to_anchor=(0.5, 0.55), ncols=2)
            ax_c.text(0.5, 0.3, "the rest: in flight", transform=ax_c.transAxes, ha="center",
                      fontsize="x-small", color="0.4")
        for a in axes:
            x0, x1 = a.get_xlim()
            a.axvspan(x0, f_lift, color="0.92", zorder=0)
            a.set_xlim(x0, x1)
            a.axvline(f_lift, color="0.4", ls="--", lw=0.8)
        ax.text(f_lift, 0.96, f" lift-off {f_lift:.1f} Hz", transform=ax.get_xaxis_transform(),
                va="top", fontsize="x-small")
        ax.text(0.01, 0.96, "sliding regime", transform=ax.transAxes, va="top",
                fontsize="x-small")
        ax.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        axes[-1].set_xlabel("f (Hz)")
        ax.set_ylabel("drift v (mm/s)")
        ax.set_title(f"φ = {SLIDING_GEOMETRY['tilt']:g}°, ψ = {SLIDING_GEOMETRY['throw']:g}°, "
                     "the paper's arcs", fontsize="small")
        ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(0.0, 0.9))
        if contact:
            ax.text(0.01, 0.06, "(a)", transform=ax.transAxes)
            axes[1].text(0.01, 0.92, "(b)", transform=axes[1].transAxes)
        return save_figure(fig, out_dir)


def draw(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: the figures from the maps' tables ``tables["transport_diffusion"]``,
    ``tables["transport_sliding_<table>"]``, one curve per line (:func:`~.claims.line_tables`);
    the files written."""
    lines = line_tables(tables)
    figs = [figure_transport({sc: lines.get(f"{sc}_diffusion") for sc in HOPPING + COMBINED},
                             out_dir),
            figure_sliding({sc: lines.get(f"{sc}_diffusion") for sc, _, _ in SLIDING}, out_dir,
                           contact={sc: lines.get(f"{sc}_contact") for sc, _, _ in SLIDING})]
    return [p for fig in figs for p in figure_files(out_dir, fig.get_label())]
