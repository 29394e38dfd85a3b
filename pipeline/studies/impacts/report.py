"""The impact-phase section's own words and the facts they name, read off the impacts table."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

from .claims import F_FROM, SCENE, in_scope

__all__ = ["WORDS", "facts"]


def facts(tables: Mapping[str, pd.DataFrame], verdicts=None) -> dict:
    """What the words name: the table's frequencies and families, the judged (f, family)
    pairs, the particles and impacts counted there."""
    t = tables.get(SCENE)
    if t is None or t.empty:
        return {"freqs": 0, "f_lo": "–", "f_hi": "–", "families": "none", "judged": 0,
                "particles": 0, "impacts": 0, "f_from": f"{F_FROM:g}"}
    s = in_scope(t, F_FROM)
    return {"freqs": t["f"].nunique(), "f_lo": f"{t['f'].min():g}", "f_hi": f"{t['f'].max():g}",
            "families": ", ".join(dict.fromkeys(t["family"])), "judged": len(s),
            "particles": int(s["n_particles"].max()) if len(s) else 0,
            "impacts": int(s["n_impacts"].sum()) if len(s) else 0, "f_from": f"{F_FROM:g}"}


#: the section's own words
WORDS = ("The floor phase ω t mod 2π at each collision (24 bins; the floor, at −A sin ω t, moves "
         "up for ω t mod 2π in (π/2, 3π/2)) and the correlation of the post-collision vx 1 … 5 "
         "collisions apart, on the paper's floor at {freqs} frequencies {f_lo}–{f_hi} Hz, "
         "families {families}; judged at the {judged} (f, family) pairs with f ≥ {f_from} Hz "
         "({particles} particles each, {impacts} impacts in all), intervals 95 % bootstrap "
         "over particles. I1 reads the share of impacts in the upward half period, I2 the "
         "lag-1 correlation about each particle's own mean (the pooled one, drawn beside it, "
         "is pushed toward +1 by the particles' different mean vx). "
         "pipeline/studies/impacts/claims.py states the rules.")
