"""The contact-model figure: (a) D(f) per contact model near onset with 95 % bootstrap CIs,
from rest (filled) and launched (open); (b) the fraction of the run held (solid) and sliding
(dashed) from rest; (c) post-collision (y, v_y⁺) at 54 Hz from rest per model (Fig. 3a
style).  And D(f) over 46–99 Hz per model from rest.  Units: f Hz, D mm²/s, y mm, v mm/s."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import rc_context

from bbb.analysis.locking import CREEP_MARGIN, creep_speed

from ...plot.style import PAGE, STYLE, figure_files, new_figure, save_figure
from ...tables.collisions import as_store, states
from ..map_lines import point_index
from .claims import LABELS, LINES, MODELS, ONSET_RANGE, PROJ_F, line_tables

__all__ = ["CAPTIONS", "draw", "figure_contact", "figure_contact_high"]

COLORS = {"stick": "black", "slide": "tab:blue", "coulomb005": "tab:orange",
          "coulomb03": "tab:red"}
#: the band of the paper's 1/1 spot at 54 Hz drawn in panel (c), v_y⁺ in mm/s
SPOT = (90.0, 100.0)
_MODELS = ", ".join(f"{LABELS[m]} ({COLORS[m].removeprefix('tab:')})" for m in MODELS)
_CI = "bootstrap 95 % CIs over particles"

#: REPORT.md's captions of the figures, by file stem
CAPTIONS = {
    "fig_contact": (
        f"The onset claims under each contact model, {_MODELS}: (a) D(f) at "
        f"{ONSET_RANGE[0]:g}–{ONSET_RANGE[1]:g} Hz from rest (filled) and launched upward "
        f"(open), {_CI}; (b) the share of the run a particle started at rest spends held at "
        f"rest on the floor (solid) and sliding on an arc (dashed), {_CI} (bands), the rest in "
        f"flight; (c) post-collision states (y, v_y⁺) at {PROJ_F:g} Hz from rest, one panel per "
        f"model (Fig. 3a style), dotted: the upper edge of the creeping band "
        f"(1 + {CREEP_MARGIN:g}) A 2πf, green: v_y⁺ = {SPOT[0]:g}–{SPOT[1]:g} mm/s, where the "
        "paper's 1/1 spot lies. Scenes contact (a, b; each (f, family) to its target CI, the "
        "TOML says which) and contact_proj (c), maps with one line per model; claims 1–4 and "
        "16 per model in the contact section below."),
    "fig_contact_high": (
        f"D(f) from rest under each contact model over the whole grid of the scene contact, "
        f"{_MODELS}, {_CI}: above {ONSET_RANGE[1]:g} Hz the models' D part where the "
        "contact section below says they differ beyond their CIs (family-wise 5 %)."),
}


def _errorbar(ax, t: pd.DataFrame, cols: tuple[str, str, str], color: str, filled: bool,
              label: str | None = None) -> None:
    D, lo, hi = (t[c].to_numpy(float) for c in cols)
    ax.errorbar(t["f"], D, yerr=[np.clip(D - lo, 0, None), np.clip(hi - D, 0, None)], fmt="o-",
                ms=2.5, lw=0.8, capsize=0, color=color, mfc=color if filled else "none",
                label=label)


def figure_contact(tables: Mapping[str, pd.DataFrame | None],
                   proj: Mapping[str, Mapping[str, np.ndarray] | None],
                   out_dir: str | os.PathLike | None = None, name: str = "fig_contact"):
    """tables: {model: (diffusion table, contact table)} near onset; proj: {model: {"y", "vy"}
    post-collision arrays at 54 Hz from rest, or None}.  Returns the Figure (PNG + PDF written
    given ``out_dir``)."""
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 7.6))
        gs = fig.add_gridspec(3, len(MODELS), height_ratios=[1.3, 0.8, 1.0], hspace=0.42,
                              wspace=0.35)
        ax_d = fig.add_subplot(gs[0, :])
        ax_c = fig.add_subplot(gs[1, :], sharex=ax_d)
        for m in MODELS:
            diff, cont = tables.get(m, (None, None))
            c = COLORS[m]
            if diff is not None and "D_rest" in diff:
                t = diff[diff["f"] <= ONSET_RANGE[1]].sort_values("f")
                _errorbar(ax_d, t, ("D_rest", "D_rest_lo", "D_rest_hi"), c, True, LABELS[m])
                if "D_launched" in t:
                    _errorbar(ax_d, t, ("D_launched", "D_launched_lo", "D_launched_hi"), c, False)
            if cont is not None:
                t = cont[(cont["family"] == "rest") & (cont["f"] <= ONSET_RANGE[1])]
                t = t.sort_values("f")
                for col, ls in (("held_frac", "-"), ("slide_frac", "--")):
                    ax_c.fill_between(t["f"], t[f"{col}_lo"], t[f"{col}_hi"], color=c, alpha=0.2,
                                      lw=0)
                    ax_c.plot(t["f"], t[col], ls, color=c, lw=1)
        ax_d.plot([], [], "o", color="0.4", ms=3, label="from rest")
        ax_d.plot([], [], "o", color="0.4", mfc="none", ms=3, label="launched")
        ax_d.set_ylabel("D (mm²/s)")
        ax_d.set_ylim(bottom=0)
        ax_d.legend(fontsize="x-small", loc="upper left", ncol=2)
        ax_d.text(0.99, 0.92, "(a)", transform=ax_d.transAxes, ha="right")
        ax_c.plot([], [], "-", color="0.4", label="held")
        ax_c.plot([], [], "--", color="0.4", label="sliding")
        ax_c.set_ylim(-0.02, 1.02)
        ax_c.set_ylabel("share of run\nfrom rest")
        ax_c.set_xlabel("f (Hz)")
        ax_c.legend(fontsize="x-small", loc="upper right")
        ax_c.text(0.01, 0.85, "(b)", transform=ax_c.transAxes)
        first = None
        for i, m in enumerate(MODELS):
            ax = fig.add_subplot(gs[2, i], sharey=first)
            first = first or ax
            s = proj.get(m)
            ax.set_title(f"({'c' if i == 0 else ''}) {LABELS[m]}".replace("() ", ""),
                         loc="left", fontsize=6.5, pad=2)
            ax.set_xlabel("y (mm)")
            if i == 0:
                ax.set_ylabel(r"$v_y^+$ (mm/s), 54 Hz")
            else:
                ax.tick_params(labelleft=False)
            if s is None:
                ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center")
                continue
            y, v = s["y"].ravel(), s["vy"].ravel()
            ok = np.isfinite(y) & np.isfinite(v)
            ax.plot(y[ok], v[ok], ".", color=COLORS[m], ms=0.8, mew=0, alpha=0.5,
                    rasterized=True)
            ax.axhline(creep_speed(0.1, PROJ_F), color="0.6", lw=0.4, ls=":")
            ax.axhspan(*SPOT, color="tab:green", alpha=0.12, lw=0)
            ax.locator_params(axis="x", nbins=3)
        return save_figure(fig, out_dir, dpi=200)


def figure_contact_high(tables: Mapping[str, pd.DataFrame | None],
                        out_dir: str | os.PathLike | None = None,
                        name: str = "fig_contact_high"):
    """D(f) from rest per model over the whole grid ({model: diffusion table}), 95 % CIs."""
    with rc_context(STYLE):
        fig = new_figure(name, (PAGE, 3.2))
        ax = fig.subplots()
        for m in MODELS:
            t = tables.get(m)
            if t is not None and "D_rest" in t:
                _errorbar(ax, t.sort_values("f"), ("D_rest", "D_rest_lo", "D_rest_hi"), COLORS[m],
                          True, LABELS[m])
        ax.set_xlabel("f (Hz)")
        ax.set_ylabel("D (mm²/s), from rest")
        ax.set_ylim(bottom=0)
        ax.legend(fontsize="x-small", loc="upper left")
        return save_figure(fig, out_dir)


def projection(store, model: str) -> dict[str, np.ndarray] | None:
    """Post-collision y, v_y⁺ of the rest family at 54 Hz on ``model``'s line of the
    projection map's store, or None."""
    if store is None:
        return None
    st = as_store(store)
    pi = point_index(st.study, PROJ_F, LINES[model])
    if pi is None:
        return None
    return states(st, PROJ_F, "rest", ("y", "vy"), point=pi)


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """make_figures' hook: both figures from the maps' tables (``tables["contact_diffusion"]``,
    ``tables["contact"]``, ..., one curve per model: :func:`~.claims.line_tables`) and the
    projection map's store; adds its locking table to ``tables`` (as ``contact_proj_locking``,
    one row per model) for :func:`~.claims.report_lines`, claim 3.  Returns the files
    written."""
    from ...tables.collisions import locking_table

    path = stores.get("contact_proj")
    proj = {m: projection(path, m) for m in MODELS}
    if path is not None:
        tables["contact_proj_locking"] = locking_table(path)
    tables = line_tables(tables)
    near = {m: (tables.get(f"contact_{m}_diffusion"), tables.get(f"contact_{m}_contact"))
            for m in MODELS}
    f1 = figure_contact(near, proj, out_dir)
    f2 = figure_contact_high({m: tables.get(f"contact_{m}_diffusion") for m in MODELS}, out_dir)
    return figure_files(out_dir, f1.get_label()) + figure_files(out_dir, f2.get_label())
