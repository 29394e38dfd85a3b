"""The house style of every figure, the engine's and the studies': matplotlib rc settings for
a journal column (3.4 in wide) or the full page width (7 in), the families' colours, and
figures made outside pyplot (no backend chosen, so a notebook's inline plotting is left
alone) that save as ``<name>.<format>`` for each format asked (default PNG and PDF).  Here,
in the engine, because the engine never imports a study and the studies draw in its style.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from matplotlib.figure import Figure

__all__ = ["COLUMN", "PAGE", "STYLE", "FAMILY_COLORS", "FORMATS", "family_color",
           "figure_files", "new_figure", "save_figure"]

COLUMN, PAGE = 3.4, 7.0  # inches
#: the file formats a figure is written in unless told otherwise
FORMATS = ("png", "pdf")
STYLE = {
    "font.family": "serif",
    "font.serif": ["DejaVu Serif"],
    "mathtext.fontset": "dejavuserif",
    "font.size": 8,
    "axes.labelsize": 8,
    "axes.titlesize": 8,
    "legend.fontsize": 6.5,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "lines.linewidth": 0.8,
    "legend.frameon": False,
    "savefig.dpi": 300,
    "savefig.bbox": "tight",
    "savefig.pad_inches": 0.02,
    "pdf.fonttype": 42,
}
FAMILY_COLORS = {"rest": "black", "launched": "tab:blue", "dropped": "tab:green"}
_OTHER_COLORS = ["tab:orange", "tab:purple", "tab:brown", "tab:pink"]


def family_color(family: str, i: int = 0) -> str:
    """The colour of ``family``: its own if it has one, else the ``i``-th of the others."""
    return FAMILY_COLORS.get(family, _OTHER_COLORS[i % len(_OTHER_COLORS)])


def figure_files(out_dir: str | os.PathLike, name: str,
                 formats: Sequence[str] = FORMATS) -> list[Path]:
    """The files a figure function given ``out_dir`` writes: ``<name>.<format>`` for each
    of ``formats`` (default ``<name>.png``, ``<name>.pdf``)."""
    out = Path(out_dir)
    return [out / f"{name}.{fmt}" for fmt in formats]


def new_figure(name: str, figsize: tuple[float, float], layout: str | None = None) -> Figure:
    """A Figure outside pyplot (no backend, no global figure list), labelled ``name``
    (``layout``: matplotlib's, e.g. ``"constrained"``; None: none)."""
    fig = Figure(figsize=figsize, layout=layout)
    fig.set_label(name)
    return fig


def save_figure(fig: Figure, out_dir: str | os.PathLike | None, dpi: int | None = None,
                formats: Sequence[str] = FORMATS) -> Figure:
    """Write ``<label>.<format>`` for each of ``formats`` (default PNG and PDF) to ``out_dir``
    unless it is None (``dpi``: of the PNG and of rasterized PDF layers); returns the figure.
    Call inside ``rc_context(STYLE)``: the savefig settings (tight bounding box, dpi, fonts)
    are read from it."""
    if out_dir is not None:
        Path(out_dir).mkdir(parents=True, exist_ok=True)
        for p in figure_files(out_dir, fig.get_label(), formats):
            fig.savefig(p, **({"dpi": dpi} if dpi else {}))
    return fig
