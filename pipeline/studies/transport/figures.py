"""The transport figures: (a) drift v(f) and (b) D(f) about the drift, with their bootstrap
CIs, one curve per (tilt φ, throw ψ); hollow markers where the drift is not steady (the
ensemble accelerates: v and D are window means there), crossed where D about the drift is
not diffusive (its MSD still steepens over the fit lags: particles running at different
speeds, or velocity memory as long as the lags).  And the sliding regime: v(f) on one
floor per contact model, with the lift-off frequency marked, and the time held and sliding.
And the transport map: v over (throw ψ, f) on the floor tilted against its throw, one panel
per contact model, with the sign changes, the measured hopping boundary and Γ_v = 1 on top.
Units: f Hz, v mm/s, D mm²/s, ψ degrees."""

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

from ...plot.heatmap import cell_edges
from ...plot.style import STYLE, figure_files, new_figure, save_figure
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
from .reversal import (
    AIRBORNE_MIN,
    MODEL_LABELS,
    REVERSAL_LINES,
    REVERSAL_MODELS,
    REVERSAL_THROWS,
    REVERSAL_TILT,
    airborne,
    f_reversals,
    hopping_boundary,
    throw_cuts,
    throw_number_frequency,
    throw_reversals,
)

__all__ = ["CAPTIONS", "draw", "figure_transport", "figure_sliding", "figure_reversal"]

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
        "and thrown (φ = 2°, 5° with ψ = 60°, 30°), judged only by claim T3b (their signs). Scene "
        "transport, a map of tilt φ × throw ψ (one line per floor)."),
    "fig_transport_sliding": (
        "The sliding regime: drift v(f) on a level floor of the paper's arcs thrown at ψ = 30°, "
        "under the stick model and Coulomb friction μ = 0.3, bootstrap 95 % CIs; dashed: the "
        "lowest lift-off frequency of this floor (bbb.analysis.liftoff_onset), shaded below it; (b) the "
        "fraction of the run each model spends held at rest on the floor (dashed) and sliding "
        "(solid), bootstrap 95 % CIs over particles, the rest in flight. Scene "
        "transport_sliding, a map with one line per contact model (claim T5)."),
    "fig_transport_reversal": (
        "The transport map: drift v over (throw ψ, f) on a floor tilted by φ = 2° (downhill "
        "towards −x) whose throw carries particles uphill (towards +x), (a) stick, (b) Coulomb "
        "friction μ = 0.3; red uphill, blue downhill, a symmetric-log colour scale centred at "
        "v = 0 (white: no current), hatched where the drift is not steady (window means). Black "
        "bars: where v changes sign along f (from the last significant frequency of one sign "
        "to the first of the other, Bonferroni over the line); grey bars: along ψ at a fixed "
        "f; green bars: the measured sliding/hopping boundary (the airborne share crosses "
        f"H = {AIRBORNE_MIN:g}, calibrated on flat floors); dashed: conveyor theory's throw "
        "number Γ_v = Γ sin ψ / cos φ = 1. Scene transport_reversal (claims T3, T6)."),
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
        for i, sc in enumerate(COMBINED, start=len(HOPPING)):  # drawn without CIs (only T3b reads them)
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


def _bar(ax, a: float, b: float, y: float, color: str, horizontal: bool = True, **kw) -> None:
    xs, ys = ([a, b], [y, y]) if horizontal else ([y, y], [a, b])
    ax.plot(xs, ys, "-", color=color, lw=2.2, solid_capstyle="butt", **kw)
    ax.plot(xs, ys, "|" if horizontal else "_", color=color, ms=6, mew=1.2, **kw)


def figure_reversal(tables: Mapping[str, pd.DataFrame | None],
                    contact: Mapping[str, pd.DataFrame | None] | None = None,
                    out_dir: str | os.PathLike | None = None,
                    name: str = "fig_transport_reversal"):
    """v over (ψ, f), one panel per contact model, from ``tables[line]`` (each line of
    transport_reversal: its diffusion table), the sign changes along f and ψ, the hopping
    boundary from ``contact[line]`` (contact tables) and Γ_v = 1; returns the Figure (PNG + PDF
    given ``out_dir``)."""
    contact = contact or {}
    by_model = {c: {ln: vals for ln, vals in REVERSAL_LINES.items() if vals["contact"] == c}
                for c, _ in REVERSAL_MODELS}
    vs = [np.abs(t["v"].to_numpy(float)) for t in tables.values() if t is not None and "v" in t]
    vs = np.concatenate(vs + [np.array([1.0])])
    vmax = float(vs[np.isfinite(vs)].max())
    norm = SymLogNorm(linthresh=1.0, vmin=-vmax, vmax=vmax)
    psi = np.array(sorted(REVERSAL_THROWS))
    _, ey = cell_edges(psi)
    with rc_context(STYLE):
        fig = new_figure(name, (7.0, 5.8), layout="constrained")
        axes = fig.subplots(len(by_model), 1, sharex=True)
        mesh = None
        for k, (ax, (model, lines)) in enumerate(zip(axes, by_model.items(), strict=True)):
            f_all = sorted({float(x) for ln in lines if tables.get(ln) is not None
                            for x in tables[ln]["f"]})
            if not f_all:
                continue
            _, ex = cell_edges(f_all)
            z = np.full((psi.size, len(f_all)), np.nan)
            unsteady = np.zeros_like(z, dtype=bool)
            for ln, vals in lines.items():
                t = tables.get(ln)
                if t is None or "v" not in t:
                    continue
                j = int(np.flatnonzero(psi == vals["throw"])[0])
                for r in t.itertuples(index=False):
                    i = f_all.index(float(r.f))
                    z[j, i] = r.v
                    unsteady[j, i] = "steady" in t and not (pd.isna(r.steady) or bool(r.steady))
            mesh = ax.pcolormesh(ex, ey, np.ma.masked_invalid(z), cmap="RdBu_r", norm=norm,
                                 gid="map")
            if unsteady.any():
                ax.add_collection(PatchCollection(
                    [Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j])
                     for j, i in zip(*np.nonzero(unsteady), strict=True)],
                    facecolor="none", edgecolor="0.15", lw=0, hatch="////", gid="hatch:steady"))
            cell = np.diff(ey).min()
            for ln, vals in lines.items():
                r = f_reversals(tables.get(ln))
                for a, b, _ in (r[0] if r else []):
                    _bar(ax, a, b, vals["throw"] + 0.2 * cell, "k", gid="reversal:f")
                c = contact.get(ln)
                if c is not None and len(c):
                    air = airborne(c)
                    bd = hopping_boundary(air["f"], air["air_lo"], air["air_hi"], AIRBORNE_MIN)
                    if bd is not None:
                        _bar(ax, bd[0], bd[1], vals["throw"] - 0.2 * cell, "C2", gid="hopping")
            cuts = throw_cuts({ln: (vals, tables.get(ln)) for ln, vals in lines.items()})
            for _, f, (a, b, _) in throw_reversals(cuts):
                _bar(ax, a, b, f, "0.45", horizontal=False, gid="reversal:psi")
            p = np.linspace(ey[0], ey[-1], 200)
            ax.plot([throw_number_frequency(REVERSAL_TILT, x) for x in p], p, "--", color="k",
                    lw=1.0, gid="throw_number")
            ax.set_xlim(ex[0], ex[-1])
            ax.set_ylim(ey[0], ey[-1])
            ax.set_yticks(psi)
            ax.set_ylabel("throw ψ (°)")
            ax.set_title(f"({'ab'[k]}) φ = {REVERSAL_TILT:g}°, {MODEL_LABELS[model]}",
                         fontsize="small", loc="left")
        axes[-1].set_xlabel("f (Hz)")
        if mesh is not None:
            fig.colorbar(mesh, ax=list(axes), label="drift v (mm/s), > 0 uphill")
        axes[0].legend(handles=[
            Line2D([], [], color="k", lw=2.2, label="sign change along f"),
            Line2D([], [], color="0.45", lw=2.2, label="sign change along ψ"),
            Line2D([], [], color="C2", lw=2.2, label="hopping boundary (measured)"),
            Line2D([], [], color="k", ls="--", lw=1.0, label="Γ_v = 1"),
            Patch(facecolor="white", edgecolor="0.2", hatch="////", label="not steady")],
            fontsize="x-small", loc="lower left", bbox_to_anchor=(0.0, 1.08), ncols=5,
            borderaxespad=0.0, handlelength=1.6, columnspacing=0.8)
        return save_figure(fig, out_dir)


def draw(tables: Mapping[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: the figures from the maps' tables ``tables["transport_diffusion"]``,
    ``tables["transport_sliding_<table>"]``, ``tables["transport_reversal_<table>"]``, one
    curve (or map row) per line (:func:`~.claims.line_tables`);
    the files written."""
    lines = line_tables(tables)
    figs = [figure_transport({sc: lines.get(f"{sc}_diffusion") for sc in HOPPING + COMBINED},
                             out_dir),
            figure_sliding({sc: lines.get(f"{sc}_diffusion") for sc, _, _ in SLIDING}, out_dir,
                           contact={sc: lines.get(f"{sc}_contact") for sc, _, _ in SLIDING}),
            figure_reversal({sc: lines.get(f"{sc}_diffusion") for sc in REVERSAL_LINES},
                            {sc: lines.get(f"{sc}_contact") for sc in REVERSAL_LINES}, out_dir)]
    return [p for fig in figs for p in figure_files(out_dir, fig.get_label())]
