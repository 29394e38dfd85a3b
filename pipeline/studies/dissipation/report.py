"""The D(f, α) study's hooks for make_figures: the tables its claims read beyond the reduce
tables (the locking map's k table, the cuts against the committed Fig. 2 curves), its figures,
the context its claims are judged in and the facts its section's words name."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import pandas as pd

from ...tables.collisions import as_store, locking_table
from .claims import CUTS, LOCKING, MAP, OWN_SEEDS, OWN_SEEDS_CUT, R25, cut_line
from .cuts import compare_cut
from .figures import figure_cuts, figure_map, files
from .lines import judged_lines, listed_alphas

__all__ = ["SCENES", "OWN_SEEDS", "FIG2_FILES", "WORDS", "draw", "cuts_table", "context", "facts"]

SCENES = (MAP, LOCKING, R25, OWN_SEEDS)
#: each cut: (the scene of its line, the committed scene it is compared with)
_CUT_SCENES = {"figure2": (MAP, "figure2"), "figure2_matyas2004": (R25, "figure2_matyas2004"),
               OWN_SEEDS_CUT: (OWN_SEEDS, "figure2")}
#: the committed curves the cuts are compared with: the CSVs the paper's study writes beside
#: REPORT.md (a committed file is the interface between studies, not an import)
FIG2_FILES = {"figure2": "diffusion_figure2.csv",
              "figure2_matyas2004": "diffusion_figure2_matyas2004.csv"}


def _d_resolved(store: str) -> float:
    return float(as_store(store).study.accuracy.d_resolved or 0.0)


def cuts_table(tables: Mapping[str, pd.DataFrame], refs: Mapping[str, pd.DataFrame],
               stores: Mapping[str, str]) -> pd.DataFrame | None:
    """The cuts compared frequency by frequency (:func:`.cuts.compare_cut`, a column ``cut``
    naming the cut: the committed scene, or ``figure2_own_seeds`` for the own-seed line
    against Fig. 2), for every cut whose line and committed table exist."""
    parts = []
    for name, (scene, ref_scene) in _CUT_SCENES.items():
        line = (cut_line(tables, name) if name in CUTS
                else tables.get(f"{scene}_diffusion"))
        ref = refs.get(ref_scene)
        if line is None or ref is None or scene not in stores or ref_scene not in stores:
            continue
        parts.append(compare_cut(line, ref, _d_resolved(stores[scene]),
                                 _d_resolved(stores[ref_scene])).assign(cut=name))
    return pd.concat(parts, ignore_index=True) if parts else None


def draw(tables: dict[str, pd.DataFrame], stores: Mapping[str, str],
         out_dir: str | os.PathLike) -> list[Path]:
    """Add the locking map's table and the cuts to ``tables``, draw the figures into
    ``out_dir``; returns their files.  The committed Fig. 2 curves are read from ``out_dir``
    (make_figures writes them before drawing the further studies)."""
    out = Path(out_dir)
    if stores.get(LOCKING) and Path(stores[LOCKING]).exists():
        tables[f"{LOCKING}_locking"] = locking_table(stores[LOCKING])
    refs = {n: pd.read_csv(out / FIG2_FILES[n]) for n in CUTS if (out / FIG2_FILES[n]).is_file()}
    cmp_ = cuts_table(tables, refs, stores)
    if cmp_ is not None:
        tables[f"{MAP}_cuts"] = cmp_
    return files(out, [figure_map(tables, out), figure_cuts(tables, refs, out)])


def context(tables: Mapping[str, pd.DataFrame], stores=None) -> dict:
    """The context the claims are judged in: the tables and the α lines the map's scene lists."""
    return {"tables": tables, "listed": listed_alphas(MAP)}


def facts(tables: Mapping[str, pd.DataFrame], verdicts=None) -> dict:
    """What the section's words name: the map's points and its judged α lines."""
    t = tables.get(f"{MAP}_diffusion")
    return {"points": 0 if t is None else len(t),
            "lines": len(judged_lines(t, listed_alphas(MAP)))}


#: the section's own words
WORDS = ("D from rest over f × α at the paper's arcs: {points} points, {lines} α lines judged "
         "(the scene's; refinement added the others' points); the flat-floor thresholds Γ₁, Γ' "
         "from bbb.analysis.period1; pipeline/studies/dissipation/claims.py states the rules.")
