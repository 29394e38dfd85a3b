"""Synthetic mechanisms tables with known carriers, and each mechanisms claim's synthetic cases
(:class:`~pipeline.claims.claim.Case`), named by the claim records of :mod:`.claims`.

A table holds f0 and its grid neighbours f0 ∓ 2 Hz; the contrast columns of f0 against each
neighbour are set directly: the log contrast (signed for the extremum's kind), its memory share,
each with a CI of ± 0.05 -- the carrier rule (bbb.analysis.gk_contrast) reads only these."""

from __future__ import annotations

from functools import partial

import pandas as pd

from ...claims.claim import Case

__all__ = ["carrier_table", "carrier_cases", "lyapunov_cases"]

_CI = 0.05


def carrier_table(f0: float, kind: str, dn, up) -> pd.DataFrame:
    """Rows f0 − 2, f0, f0 + 2; ``dn``/``up``: (log contrast size, memory share) of f0 against
    that neighbour under both step choices, or "still" (the neighbour does not move)."""
    sign = 1.0 if kind == "max" else -1.0
    row = {"f": f0, "still": False, "f_dn": f0 - 2, "f_up": f0 + 2, "converged": True,
           "converged_coll": True}
    for side, spec in (("dn", dn), ("up", up)):
        total, share = (1.0, 0.9) if spec == "still" else spec
        t = sign * total
        for step in ("", "_coll"):
            for name, v in (("ln_D", t), ("ln_walk", t * (1 - share)), ("ln_mem", t * share),
                            ("share_mem", share)):
                row.update({f"{name}{step}_{side}": v, f"{name}{step}_{side}_lo": v - _CI,
                            f"{name}{step}_{side}_hi": v + _CI})
    nb = [{"f": f0 - 2, "still": dn == "still"}, {"f": f0 + 2, "still": up == "still"}]
    return pd.DataFrame([nb[0], row, nb[1]])


def _ctx(t: pd.DataFrame) -> dict:
    return {"tables": {"mechanisms": t, "mechanisms_diffusion": None}}


def carrier_cases(f0: float, kind: str, both: bool = False):
    """The cases of the carrier claim at f0 (M1–M5; ``both``: M1b–M5b, both sides required)."""
    return partial(_carrier_cases, f0, kind, both)


def _carrier_cases(f0: float, kind: str, both: bool) -> list[Case]:
    mem, walk = (1.0, 0.9), (1.0, 0.1)
    base = "memory on both sides"
    return [
        Case(base, _ctx(carrier_table(f0, kind, mem, mem)), "memory"),
        Case("random walk on both sides", _ctx(carrier_table(f0, kind, walk, walk)),
             "random walk", perturbs=base),
        Case("wrong sign below", _ctx(carrier_table(f0, kind, (-1.0, 0.9), mem)), "no extremum",
             perturbs=base),
        # the rule M1b–M5b mend: M1–M5 take the other side alone
        Case("neighbour below still", _ctx(carrier_table(f0, kind, "still", mem)),
             "not measured" if both else "memory", perturbs=base),
        Case("below not resolved", _ctx(carrier_table(f0, kind, (0.0, 0.9), mem)),
             "not resolved" if both else "memory", perturbs=base),
    ]


def _lam(ratio: float) -> pd.DataFrame:
    rows = [{"f": 60.0, "lam_move": 10.0, "lam_move_lo": 9.5, "lam_move_hi": 10.5,
             "n_lam_move": 32}]
    rows += [{"f": f, "lam_move": 10.0 * ratio, "lam_move_lo": 10.0 * ratio - 0.5,
              "lam_move_hi": 10.0 * ratio + 0.5, "n_lam_move": 32} for f in (66.0, 70.0, 74.0)]
    return pd.DataFrame(rows)


def lyapunov_cases() -> list[Case]:
    """M6's rule: λ of the moving particles over f ≥ 66 Hz against 60 Hz."""
    return [Case("λ twice as large in the spiral regime", _ctx(_lam(2.0)), "agrees"),
            Case("λ half as large there", _ctx(_lam(0.5)), "disagrees",
                 perturbs="λ twice as large in the spiral regime")]
