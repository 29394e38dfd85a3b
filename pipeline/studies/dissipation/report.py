"""The D(f, α) study's hooks for make_figures: the tables its claims read beyond the reduce
tables (the locking map's k table, the cuts against the committed Fig. 2 curves), its figures,
and its REPORT.md section."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import pandas as pd

from ...claims.claim import evaluate
from ...claims.markdown import markdown_table
from ...tables.collisions import as_store, locking_table
from ..klages2004.committed import TABLE_FILES
from .claims import CLAIMS, CUTS, LOCKING, MAP, R25, cut_line
from .cuts import compare_cut
from .figures import figure_cuts, figure_map, files
from .lines import judged_lines, listed_alphas

__all__ = ["SCENES", "draw", "cuts_table", "report_lines"]

SCENES = (MAP, LOCKING, R25)
_CUT_SCENE = {"figure2": MAP, "figure2_matyas2004": R25}


def _d_resolved(store: str) -> float:
    return float(as_store(store).study.accuracy.d_resolved or 0.0)


def cuts_table(tables: Mapping[str, pd.DataFrame], refs: Mapping[str, pd.DataFrame],
               stores: Mapping[str, str]) -> pd.DataFrame | None:
    """The cuts compared frequency by frequency (:func:`.cuts.compare_cut`, a column ``cut``
    naming the committed scene), for every cut whose map line and committed table exist."""
    parts = []
    for name in CUTS:
        line, ref = cut_line(tables, name), refs.get(name)
        if line is None or ref is None or name not in stores:
            continue
        parts.append(compare_cut(line, ref, _d_resolved(stores[_CUT_SCENE[name]]),
                                 _d_resolved(stores[name])).assign(cut=name))
    return pd.concat(parts, ignore_index=True) if parts else None


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """Add the locking map's table and the cuts to ``tables``, draw the figures into
    ``out_dir``; returns their files.  The committed Fig. 2 curves are read from ``out_dir``
    (make_figures writes them before drawing the further studies)."""
    out = Path(out_dir)
    if stores.get(LOCKING) and Path(stores[LOCKING]).exists():
        tables[f"{LOCKING}_locking"] = locking_table(stores[LOCKING])
    refs = {n: pd.read_csv(out / TABLE_FILES[n]) for n in CUTS if (out / TABLE_FILES[n]).is_file()}
    cmp_ = cuts_table(tables, refs, stores)
    if cmp_ is not None:
        tables[f"{MAP}_cuts"] = cmp_
    return files(out, [figure_map(tables, out), figure_cuts(tables, refs, out)])


def report_lines(tables: Mapping[str, pd.DataFrame]) -> list[str]:
    """The REPORT.md section: the map's claim rows."""
    listed = listed_alphas(MAP)
    rows = evaluate(CLAIMS, {"tables": tables, "listed": listed})
    n = len(judged_lines(tables.get(f"{MAP}_diffusion"), listed))
    t = tables.get(f"{MAP}_diffusion")
    pts = 0 if t is None else len(t)
    L = ["", "## D(f, α): dissipation (scenes dissipation, dissipation_locking, dissipation_r25)",
         "", f"D from rest over f × α at the paper's arcs: {pts} points, {n} α lines judged "
         "(the scene's; refinement added the others' points); the flat-floor thresholds Γ₁, Γ' from "
         "bbb.analysis.period1; pipeline/studies/dissipation/claims.py states the rules.", ""]
    return L + markdown_table(rows, prefix="A")
