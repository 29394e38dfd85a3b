"""The basins section's own words and the facts they name, read off its tables."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

__all__ = ["WORDS", "facts", "FULL", "further"]

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
    if not len(frac):
        # a box holding two labels has an entropy of at most ln 2: the test is blind there
        fr = ("none; S_bb > ln 2 needs boxes where three or more final states meet, so where two "
              "basins interleave, however finely, this test cannot find a fractal boundary (the "
              "uncertainty exponent is not measured)")
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


def further(tables: Mapping[str, pd.DataFrame], verdicts=None) -> list[str]:
    """A paragraph read off the states table: how the shares and D of the irregular
    particles change through 52-57 Hz (what D_mix is made of there)."""
    t = tables.get("states")
    if t is None or t.empty:
        return []
    parts = []
    for fam, g in t.groupby("family", sort=False):
        g = g.set_index("f")
        at = [f for f in (52.0, 54.0, 56.0, 57.0) if f in g.index]
        if not at:
            continue
        stuck = ", ".join(f"{g.loc[f, 'final_stuck']:.0%} at {f:g}" for f in at)
        d = ", ".join(f"{g.loc[f, 'D_irregular']:.0f}" for f in at)
        parts.append(f"{fam}: ending stuck/creeping {stuck} Hz; D of the irregular particles "
                     f"{d} mm²/s there")
    if not parts:
        return []
    locked = float(t[["final_locked_1", "final_locked_k"]].to_numpy().max())
    lock = ("Neither locked state survives the run anywhere on these grids (final shares 0)"
            if locked == 0 else f"Locked states end at most {locked:.1%} of a grid")
    return ["What D_mix is made of near 54 Hz (tables basins_states.csv, fig_basins_dmix): "
            + "; ".join(parts) + f". {lock}; where the share that ends stuck grows and D of the "
            "particles still irregular falls, every mixture of these states falls with them "
            "(claim B1's verdict says whether any peaks near 54 Hz); the protocol study's "
            "curves are grey in fig_basins_dmix.", ""]
