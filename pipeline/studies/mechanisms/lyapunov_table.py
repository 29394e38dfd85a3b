"""The REPORT table of λ where particles move: per frequency, λ of all measured particles, of
the moving ones and of the confined ones (pipeline.tables.mechanisms: moving = x spans ≥ S in λ's
window), and where a CI is degenerate, named instead of printed as an interval."""

from __future__ import annotations

import math

import pandas as pd

from ...claims.markdown import md_cell

__all__ = ["lam_text", "lyapunov_lines"]


def lam_text(row: pd.Series, name: str) -> str:
    """λ of group ``name`` ("lam", "lam_move", "lam_conf") with its CI, or why there is none."""
    v = row.get(name, math.nan)
    if pd.isna(v):
        return "—"
    if bool(row.get(f"{name}_degenerate", False)):
        n = int({"lam": row["n_lyapunov"] - row["n_collapsed"], "lam_move": row["n_lam_move"],
                 "lam_conf": row["n_lam_conf"]}[name])
        return (f"{v:.3g} (CI degenerate: {int(row[f'{name}_distinct'])} distinct values to 4 "
                f"digits, {int(row[f'{name}_tie'])} of {n} equal)")
    return f"{v:.3g} [{row[f'{name}_lo']:.3g}, {row[f'{name}_hi']:.3g}]"


def lyapunov_lines(t: pd.DataFrame | None) -> list[str]:
    """The section's λ table: the frequencies that are still, have confined particles or a
    degenerate CI; one line for the others."""
    if t is None or "lam_move" not in t:
        return []
    flagged = t[t["still"].fillna(False).astype(bool) | (t["n_lam_conf"] > 0)
                | t[[c for c in t if c.endswith("_degenerate")]].fillna(False).any(axis=1)]
    L = ["", "λ (1/s) where particles move: a λ particle *moves* when its x at the period ends "
         "of λ's window spans at least one arc spacing S, else it is *confined* (rattling at a "
         "cusp apex, or held). *still*: no particle of the scene left its cell, or every "
         "recorded state creeps (shaded in fig_mechanisms). A CI is *degenerate* with fewer "
         "than 5 distinct per-particle values, or one value shared by more than half of them.",
         "", "| f (Hz) | still | moving / confined | λ, all | λ, moving | λ, confined |",
         "| --- | --- | --- | --- | --- | --- |"]
    for _, r in flagged.iterrows():
        L.append(f"| {r['f']:g} | {'yes' if r['still'] else ''} | {int(r['n_lam_move'])} / "
                 f"{int(r['n_lam_conf'])} | " + " | ".join(md_cell(lam_text(r, n)) for n in
                                                        ("lam", "lam_move", "lam_conf")) + " |")
    rest = t[~t.index.isin(flagged.index)]
    if not rest.empty:
        L += ["", f"At the other {len(rest)} frequencies ({rest['f'].min():g}–{rest['f'].max():g} "
              "Hz) every λ particle moves and the CIs are regular (mechanisms table)."]
    return L
