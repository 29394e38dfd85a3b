"""The accuracy study's figure: error versus cost, one point per variant, the Pareto front
joined (``figures/accuracy.png``).  Error: RMS of |D − D_ref| over the reference's 95 % CI
half-width; cost: CPU time in s.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["accuracy_figure", "plot_accuracy"]


def plot_accuracy(summary: pd.DataFrame, path: str | os.PathLike) -> Path:
    """Draw :func:`accuracy_figure` and write it to ``path`` (PNG, 130 dpi)."""
    fig = accuracy_figure(summary)
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(p, dpi=130)
    return p


def accuracy_figure(summary: pd.DataFrame):
    """Error (RMS of |D - D_ref| / CI_ref half-width) versus CPU time, one point per variant,
    the Pareto front joined; presets as large markers, knob variants small.  A Figure made
    without pyplot; each variant's name goes to the first free spot around its marker."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    s = summary[summary.variant != "reference"].copy()
    fig = Figure(figsize=(7.5, 5))
    FigureCanvasAgg(fig)
    fig.set_label("accuracy")
    ax = fig.subplots()
    labels = []
    for kind, mk, size in (("preset", "o", 80), ("knob", "s", 35)):
        k = s[s.kind == kind]
        ax.scatter(k.cpu_s, k.err_rms, marker=mk, s=size, label=kind + "s",
                   c=np.where(k.pareto, "tab:red", "tab:blue"), zorder=3)
        labels += [(r.variant, r.cpu_s, r.err_rms) for _, r in k.iterrows()]
    front = s[s.pareto].sort_values("cpu_s")
    ax.plot(front.cpu_s, front.err_rms, "-", color="tab:red", lw=1.2, label="Pareto front",
            zorder=2)
    ax.axhline(1.0, color="0.6", ls=":", lw=1)
    ax.set_xscale("log")
    if (s.err_rms > 0).all():
        ax.set_yscale("log")
    ax.set_xlabel("CPU time of the study's frequencies, s (sum of task simulation times)")
    ax.set_ylabel("error: RMS |D - D_ref| / (95 % CI half-width of D_ref),\n"
                  "stationary frequencies")
    ax.set_title("Accuracy versus cost (knob variants: reference numerics, one knob changed)",
                 fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    _place_labels(fig, ax, labels)
    return fig


def _place_labels(fig, ax, labels) -> None:
    """Annotate (text, x, y) points, each at the first of a few offsets around its marker
    where it overlaps no label placed before it (points of labels that share a spot, such as
    two variants of equal cost and error, would otherwise be printed over each other)."""
    renderer = fig.canvas.get_renderer()
    offsets = [((4, 4), "left", "bottom"), ((4, -4), "left", "top"),
               ((-4, 4), "right", "bottom"), ((-4, -4), "right", "top"),
               ((4, 12), "left", "bottom"), ((4, -12), "left", "top")]
    placed = []
    for text, x, y in labels:
        for (dx, dy), ha, va in offsets:
            a = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points",
                            fontsize=8, ha=ha, va=va)
            box = a.get_window_extent(renderer)
            if not any(box.overlaps(b) for b in placed):
                break
            a.remove()
        else:
            a = ax.annotate(text, (x, y), xytext=offsets[0][0], textcoords="offset points",
                            fontsize=8)
            box = a.get_window_extent(renderer)
        placed.append(box)
