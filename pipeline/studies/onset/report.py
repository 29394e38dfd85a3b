"""The onset section's own words and the facts they name, read off the two maps' tables."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

from .claims import MAP, SINE
from .lines import step_of
from .predictions import load

__all__ = ["WORDS", "facts", "further"]


def facts(tables: Mapping[str, pd.DataFrame], verdicts=None) -> dict:
    """What the words name: the predictions and the maps' sizes."""
    p = load()
    fc = ", ".join(f"{v['f_c']:.1f} Hz (α = {a})" for a, v in p["alpha"].items())
    out = {"f1": f"{p['f_liftoff']:.1f}", "fc": fc, "step": f"{step_of(MAP):g}"}
    for key, s in (("map", MAP), ("sine", SINE)):
        t = tables.get(f"{s}_diffusion")
        out[f"{key}_points"] = 0 if t is None else len(t)
    return out


#: the section's own words
WORDS = ("Two no-fit predictions of where motion from rest starts, registered before the maps "
         "ran (docs/physics.md, \"Why motion starts\"). (a) Horizontal: a vertical motion at "
         "the rest point loses horizontal stability -- at the arcs' cusp, a wedge, from the "
         "first lift-off f(Γ = 1) = {f1} Hz whatever R (O1); at the sine's smooth valley the "
         "chattering cycle stays horizontally stable wherever it exists (O1s). (b) Vertical: "
         "the chattering cycle from rest stops ending within its period at f_c = {fc} (exact "
         "flat-floor map; O2 on the arcs, O2s on the sine). Judged on the onset of every line "
         "of the D(f, R) map ({map_points} points) and of the sine floor's D(f, depth) map "
         "({sine_points} points), band ± the grid step ({step} Hz). "
         "pipeline/studies/onset/claims.py states the rules.")


def further(tables: Mapping[str, pd.DataFrame], verdicts=None) -> list[str]:
    """A table of every line: its onset and largest D beside both predictions (a line whose
    largest D is tiny has no diffusion in range: its 'onset' is 1 % of a transient's D)."""
    from .figures import onset_rows
    from .lines import AXES, grid_lines

    p = load()
    out = ["", "Every line: the onset (its CI), the line's largest D, and the predictions "
           f"f(Γ = 1) = {p['f_liftoff']:.1f} Hz (O1) and f_c(α) (O2, O2s).", "",
           "| scene | α | axis | onset (Hz) | CI (Hz) | largest D (mm²/s) | f_c(α) (Hz) |",
           "| --- | --- | --- | --- | --- | --- | --- |"]
    for scene in (MAP, SINE):
        t = tables.get(f"{scene}_diffusion")
        if t is None:
            out.append(f"| {scene} | – | – | not measured: no table | – | – | – |")
            continue
        axis = AXES[scene]
        lines = grid_lines(t, axis)
        for _, r in onset_rows(t, scene).iterrows():
            line = lines[(r["alpha"], r[axis])]
            top = float(line["D"].max()) if line["D"].notna().any() else float("nan")
            fc = p["alpha"][f"{r['alpha']:g}"]["f_c"]
            on = "none" if pd.isna(r["onset"]) else f"{r['onset']:g}"
            ci = "–" if pd.isna(r["onset"]) else f"[{r['onset_lo']:g}, {r['onset_hi']:g}]"
            out.append(f"| {scene} | {r['alpha']:g} | {axis} = {r[axis]:g} mm | {on} | {ci} | "
                       f"{top:.3g} | {fc:.1f} |")
    return out
