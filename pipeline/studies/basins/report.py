"""The basins section's own words and the facts they name, read off its tables."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

__all__ = ["WORDS", "facts", "FULL"]

#: cells per grid of the study's scene (scenes/basins.toml: 256 x 256)
FULL = 256 * 256


def facts(tables: Mapping[str, pd.DataFrame], verdicts=None) -> dict:
    """What the words name: frequencies, ensembles and particles of the states table, and the
    frequencies with a fractal boundary (S_bb > ln 2)."""
    t, e = tables.get("states"), tables.get("entropy")
    if t is None or t.empty:
        return {"freqs": 0, "f_lo": "–", "f_hi": "–", "families": "none", "particles": 0,
                "variant": "", "fractal": "none"}
    frac = (e[e["fractal"].astype(str) == "True"] if e is not None and not e.empty
            else pd.DataFrame())
    fr = "; ".join(f"{fam}: {', '.join(f'{f:g}' for f in g['f'])} Hz"
                   for fam, g in frac.groupby("family")) if len(frac) else "none"
    n = int(t["n_particles"].max())
    variant = ("" if n >= FULL else f" (fewer than the scene's {FULL}: these tables come from "
               "the coarse variant scenes/coarse/basins.toml, run within a 30 min budget on a "
               "loaded 2-core machine)")
    return {"freqs": t["f"].nunique(), "f_lo": f"{t['f'].min():g}", "f_hi": f"{t['f'].max():g}",
            "families": ", ".join(dict.fromkeys(t["family"])), "particles": n,
            "variant": variant, "fractal": fr}


WORDS = ("Each particle of two grids of initial conditions on the paper's floor (α = 0.7, "
         "R = 15 mm), floor phase × drop height 0–2 mm (dropped) and floor phase × launch speed "
         "0–200 mm/s (launched), both at 0.5 mm from an arc's centre, is labelled in every 0.5 s "
         "window of its 20 s run as stuck/creeping, locked 1/1, locked period-k, chaotic or "
         "diffusing by a classifier whose thresholds were calibrated on runs with known answers "
         "before any basin was computed (bbb/analysis/states_rule.json, "
         "benchmarks/results/states-calibration-2026-11-28.txt). {freqs} frequencies "
         "{f_lo}–{f_hi} Hz, ensembles {families}, {particles} cells per grid{variant}; shares with Wilson "
         "95 % intervals, lifetimes, escape rates and D with bootstrap 95 % intervals over "
         "particles (tables basins_*.csv). Boundaries with a basin entropy S_bb above ln 2 "
         "(fractal): {fractal}. D_mix(f, T) = Σ share_c(T)·D_c weighs each class of states "
         "(stuck, locked 1/1, locked period-k, irregular) by its share at time T and its own "
         "measured D; claim B1 re-judges claim 2 (a maximum near 54 Hz) on it, claim 2's verdict "
         "staying as judged. pipeline/studies/basins/claims.py states the rule.")
