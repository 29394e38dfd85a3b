"""The protocol figures: (1) D over f × protocol, one map per definition of "moving" (rows:
initial ensemble and run length T), with the relative CI beside each map; (2) the
decomposition D_all = share × D_moving of the mixture of all families, per T: the share that
moves, D of the moving particles, D of all.  Units: f Hz, D mm²/s, T s, shares 1."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import pandas as pd
import xarray as xr
from matplotlib import rc_context

from ...plot.heatmap import plot_map
from ...plot.style import PAGE, STYLE, figure_files, new_figure, save_figure
from .claims import verdicts_table
from .tables import DEFINITIONS, MIXTURE, protocol_table

__all__ = ["CAPTIONS", "LANDMARKS", "protocol_dataset", "figure_protocol_map",
           "figure_decomposition", "draw"]

#: Hz: the paper's onset, maximum, minimum and VHO maximum, drawn as dotted lines
LANDMARKS = (50.0, 54.0, 58.0, 60.0)
_T_COLORS = ("tab:red", "tab:orange", "tab:green", "tab:blue")
_WHAT = {"all": "all particles (bbb reduce's D)",
         "displaced": "particles displaced beyond one arc period",
         "moving_time": "D per unit of time moving (0.5 s blocks)"}

CAPTIONS = {
    "fig_protocol": (
        "D(f) under each measuring protocol, scene protocol (46–62 Hz, five initial-condition "
        "families of 512 particles, their mixture): one map per definition of the moving "
        "particles (top: all particles; middle: those displaced beyond one arc period S over "
        "the analysed window; bottom: D per unit of time spent moving), rows the initial "
        "ensemble and the analysis run length T (the first T s of each run); beside each map "
        "the 95 % CI's half-width relative to D. Blank: no D (fewer than two moving particles "
        "or no moving time). Dotted: 50, 54, 58 and 60 Hz, the paper's onset, maximum, minimum "
        "and VHO maximum. Verdicts per protocol in the protocol section below."),
    "fig_protocol_decomposition": (
        "The decomposition D_all = share × D_moving for the mixture of all families, per run "
        "length T (colours): top, particles displaced beyond one arc period; bottom, time "
        "counted in moving 0.5 s blocks. Left: the share that moves (Wilson 95 % CI, or the "
        "bootstrap over particles for the time share); middle: D of the moving particles; "
        "right: D of all particles and share × D_moving (dashed), bootstrap 95 % CIs over "
        "particles; open markers where |D_all − share × D_moving| exceeds the half-width of "
        "D_all's CI."),
}


def protocol_dataset(curves: pd.DataFrame, definition: str) -> xr.Dataset:
    """One definition's D, D_lo, D_hi over (protocol, frequency), protocol 'ensemble, T s'."""
    t = curves[curves["definition"] == definition].copy()
    t["protocol"] = [f"{e}, {T:g} s" for e, T in zip(t["ensemble"], t["T"], strict=True)]
    order = list(dict.fromkeys(t.sort_values(["T"], kind="stable")["protocol"]))
    order = sorted(order, key=lambda p: (p.split(", ")[0] == MIXTURE,
                                         list(dict.fromkeys(t["ensemble"])).index(
                                             p.split(", ")[0]), float(p.split(", ")[1][:-2])))
    ds = t.set_index(["protocol", "f"])[["D", "D_lo", "D_hi"]].to_xarray()
    ds = ds.rename({"f": "frequency"}).reindex(protocol=order[::-1])
    ds["frequency"].attrs["units"] = "Hz"
    for v in ("D", "D_lo", "D_hi"):
        ds[v].attrs["units"] = "mm^2/s"
    return ds


def figure_protocol_map(curves: pd.DataFrame, out_dir: str | os.PathLike | None = None,
                        name: str = "fig_protocol"):
    """The maps of D over (f, protocol), one row per definition; returns the Figure."""
    with rc_context(STYLE):
        n = len(DEFINITIONS)
        rows = len(set(zip(curves["ensemble"], curves["T"], strict=True)))
        fig = new_figure(name, (PAGE, n * (0.9 + 0.12 * rows)), layout="constrained")
        axes = fig.subplots(n, 2, width_ratios=[1.6, 1], squeeze=False)
        for i, d in enumerate(DEFINITIONS):
            plot_map(protocol_dataset(curves, d), "frequency", "protocol", "D", ax=axes[i, 0],
                     ci_ax=axes[i, 1])
            axes[i, 0].set_title(_WHAT[d], loc="left")
            for ax in axes[i]:
                for f0 in LANDMARKS:
                    ax.axvline(f0, color="white", lw=0.5, ls=":")
                ax.set_ylabel("")
                ax.tick_params(axis="y", labelsize=5)
            axes[i, 1].tick_params(labelleft=False)
        return save_figure(fig, out_dir, dpi=200)


def _band(ax, t: pd.DataFrame, col: str, color: str, ls: str = "-") -> None:
    ax.fill_between(t["f"], t[f"{col}_lo"], t[f"{col}_hi"], color=color, alpha=0.15, lw=0)
    ax.plot(t["f"], t[col], ls, color=color, lw=0.9)


def figure_decomposition(curves: pd.DataFrame, out_dir: str | os.PathLike | None = None,
                         name: str = "fig_protocol_decomposition", ensemble: str = MIXTURE):
    """Share, D_moving and D_all (with share × D_moving) per T for ``ensemble``, one row per
    definition of moving; returns the Figure."""
    defs = [d for d in DEFINITIONS if d != "all"]
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 2.3 * len(defs)), layout="constrained")
        axes = fig.subplots(len(defs), 3, sharex=True, squeeze=False)
        Ts = sorted(set(curves["T"].astype(float)))
        for i, d in enumerate(defs):
            for j, T in enumerate(Ts):
                c = _T_COLORS[j % len(_T_COLORS)]
                t = curves[(curves["ensemble"] == ensemble) & (curves["T"] == T)
                           & (curves["definition"] == d)].sort_values("f")
                if t.empty:
                    continue
                _band(axes[i, 0], t, "share", c)
                _band(axes[i, 1], t, "D", c)
                _band(axes[i, 2], t, "D_all", c)
                axes[i, 2].plot(t["f"], t["share"] * t["D"], "--", color=c, lw=0.7)
                bad = ~t["approx_ok"].astype(bool).to_numpy()
                axes[i, 2].plot(t["f"][bad], t["D_all"][bad], "o", mfc="none", color=c, ms=3)
                axes[i, 0].plot([], [], color=c, label=f"T = {T:g} s")
            axes[i, 0].set_ylabel(f"share moving\n({d})")
            axes[i, 1].set_ylabel("D of the moving (mm²/s)")
            axes[i, 2].set_ylabel("D of all (mm²/s)")
            axes[i, 0].set_ylim(-0.02, 1.02)
            for ax in axes[i]:
                for f0 in LANDMARKS:
                    ax.axvline(f0, color="0.6", lw=0.4, ls=":")
            axes[i, 1].set_ylim(bottom=0)
            axes[i, 2].set_ylim(bottom=0)
        axes[0, 0].legend(loc="lower right")
        for ax in axes[-1]:
            ax.set_xlabel("f (Hz)")
        fig.suptitle(f"{ensemble}: D_all = share × D_moving", fontsize=8)
        return save_figure(fig, out_dir, dpi=200)


def _as_committed(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` as it reads back from its committed CSV (six significant digits), so that the
    verdicts drawn here and those the report regenerates from the CSV are the same."""
    from io import StringIO

    from ...tables.files import FLOAT_FORMAT

    return pd.read_csv(StringIO(df.to_csv(index=False, float_format=FLOAT_FORMAT)))


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: reads the protocol store into the table ``protocol_curves`` and
    judges it into ``protocol_verdicts`` (both added to ``tables``, so both are committed),
    then draws both figures.  Returns the files written."""
    path = stores.get("protocol")
    if path is None:
        return []
    curves = _as_committed(protocol_table(path))
    tables["protocol_curves"] = curves
    tables["protocol_verdicts"] = verdicts_table(curves)
    f1 = figure_protocol_map(curves, out_dir)
    f2 = figure_decomposition(curves, out_dir)
    return figure_files(out_dir, f1.get_label()) + figure_files(out_dir, f2.get_label())


