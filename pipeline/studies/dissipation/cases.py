"""Synthetic D(f, α) maps with known onsets, maxima and ergodicity, and each map claim's
synthetic cases (:class:`~pipeline.claims.claim.Case`: the verdict its rule must give, and
the perturbations that must flip it), named by the claim records of :mod:`.claims`."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...claims.claim import Case
from ...store.layout import STOP_LEGEND, ZERO
from .lines import threshold_frequency

__all__ = ["ALPHAS", "F", "line", "dmap", "lock", "cut_table"]

ALPHAS = (0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75, 0.80, 0.85, 0.90, 0.95)
F = np.arange(46.0, 100.5, 1.0)
#: a grid low enough for Γ₁'s frequencies (14–58 Hz)
F_WIDE = np.arange(10.0, 100.5, 1.0)
RULE_FN = 0.0  # the calibrated rate of calling an ergodic population non-ergodic (rule_fn)


def line(f_on: float, f_max: float, alpha: float, rel: float = 0.03,
         nonergodic=lambda f, f_on: False, f_grid=F) -> pd.DataFrame:
    """One α line: D = 0 (resolved to ±d_resolved) below f_on; above it a peak of 300 mm²/s at f_max on
    a rise to 3000 mm²/s at 100 Hz, CI ± rel; ``ergodic`` False where nonergodic(f, f_on)
    (None there: no verdict)."""
    rows = []
    for f in f_grid:
        if f < f_on:
            D, lo, hi, stop = 1e-7, 0.0, 2e-7, STOP_LEGEND[ZERO]
        else:
            D = (300.0 * np.exp(-0.5 * ((f - f_max) / 1.5) ** 2)
                 + 3000.0 * ((f - f_on) / max(54.0, 100.0 - f_on)) ** 2 + 50.0)
            lo, hi, stop = D * (1 - rel), D * (1 + rel), "target met"
        bad = nonergodic(f, f_on)
        rows.append({"f": f, "alpha": alpha, "D": D, "D_lo": lo, "D_hi": hi, "stop": stop,
                     "ergodic": np.nan if bad is None else float(not bad), "rule_fn": RULE_FN})
    return pd.DataFrame(rows)


def _at(name: str):
    return lambda a: float(np.ceil(threshold_frequency(name, a)))


def dmap(onset_of=None, max_of=lambda a, on: on + 5.0, nonergodic=lambda f, f_on: False,
         refined: bool = True, f_grid=F, alphas=ALPHAS) -> pd.DataFrame:
    """A map over ``alphas`` × ``f_grid`` (onsets at f(Γ') by default); with ``refined``, a few
    points at an α midpoint as refinement adds."""
    onset_of = onset_of or _at("gamma_prime")
    parts = [line(onset_of(a), max_of(a, onset_of(a)), a, nonergodic=nonergodic, f_grid=f_grid)
             for a in alphas]
    if refined:
        extra = line(60.0, 65.0, 0.425, f_grid=f_grid)
        parts.append(extra[extra["f"].isin([60.0, 61.0, 62.0])])
    return pd.concat(parts, ignore_index=True)


def lock(f_of_2) -> pd.DataFrame:
    """A locking map whose k_max reaches 2 at f_of_2(α), rising linearly from 30 Hz."""
    rows = []
    for a in ALPHAS:
        for f in F:
            k = 2.0 * (f - 30.0) / (f_of_2(a) - 30.0)
            rows.append({"f": f, "alpha": a, "k_max": k, "k_max_lo": k - 0.02,
                         "k_max_hi": k + 0.02})
    return pd.DataFrame(rows)


def cut_table(shift: float, name: str = "figure2") -> pd.DataFrame:
    """The α = 0.7 line of :func:`dmap` against itself times ``shift`` (:mod:`.cuts`)."""
    from .cuts import compare_cut

    ln = dmap(refined=False).query("alpha == 0.7")
    ref = ln.assign(D=ln["D"] * shift, D_lo=ln["D_lo"] * shift, D_hi=ln["D_hi"] * shift)
    return compare_cut(ln, ref, 9.0, 9.0).assign(cut=name)


def _map(m: pd.DataFrame) -> dict:
    return {"tables": {"dissipation_diffusion": m}, "listed": ALPHAS}


# -- the cases, one provider per claim --------------------------------------------------------
def onset_trend_cases() -> list[Case]:
    """A1's rule (a level and a trend)."""
    late = dmap(onset_of=lambda a: _at("gamma_prime")(a) + 6)
    return [Case("onset at f(Γ')", _map(dmap()), "agrees"),
            Case("onset fixed at 58 Hz", _map(dmap(onset_of=lambda a: 58.0)), "disagrees",
                 perturbs="onset at f(Γ')"),
            Case("onset 6 Hz above f(Γ')", _map(late), "partly", perturbs="onset at f(Γ')"),
            # the flaw A1b mends: a threshold 400 Hz off still moves with the onset
            Case("threshold 400 Hz off", _map(dmap()), "partly", perturbs="onset at f(Γ')",
                 options={"shift": 400.0})]


def onset_trend_g1_cases() -> list[Case]:
    """A2's rule on maps wide enough for f(Γ₁)."""
    at = dmap(onset_of=_at("gamma_1"), f_grid=F_WIDE)
    return [Case("onset at f(Γ₁)", _map(at), "agrees"),
            Case("onset at f(Γ')", _map(dmap()), "partly", perturbs="onset at f(Γ₁)"),
            Case("onset fixed at 58 Hz", _map(dmap(onset_of=lambda a: 58.0)), "disagrees",
                 perturbs="onset at f(Γ₁)")]


def _level_cases(name: str, f_grid) -> list[Case]:
    at = dmap(onset_of=_at(name), f_grid=f_grid)
    missing = at[~np.isclose(at["alpha"], 0.55)]
    return [Case("onset at the threshold", _map(at), "agrees"),
            Case("threshold 400 Hz off", _map(at), "disagrees", perturbs="onset at the threshold",
                 options={"shift": 400.0}),
            Case("onset 6 Hz above on every line",
                 _map(dmap(onset_of=lambda a: _at(name)(a) + 6, f_grid=f_grid)), "disagrees",
                 perturbs="onset at the threshold"),
            Case("one listed line missing", _map(missing), "not measured",
                 perturbs="onset at the threshold")]


def onset_level_cases() -> list[Case]:
    """A1b's rule (the level on every line)."""
    return _level_cases("gamma_prime", F)


def onset_level_g1_cases() -> list[Case]:
    """A2b's rule (the level on every line), on maps wide enough for f(Γ₁)."""
    return _level_cases("gamma_1", F_WIDE)


def first_max_cases() -> list[Case]:
    """A3's rule."""
    moving = dmap(onset_of=lambda a: 50.0, max_of=lambda a, on: 60.0 + 20 * (0.7 - a))
    fixed = dmap(onset_of=lambda a: 50.0, max_of=lambda a, on: 60.0)
    return [Case("maximum moving with α, at 60 Hz for α = 0.7", _map(moving), "agrees"),
            Case("maximum fixed at 60 Hz", _map(fixed), "partly", perturbs=(
                "maximum moving with α, at 60 Hz for α = 0.7"))]


def loops_cases() -> list[Case]:
    """A4's rule."""
    def ctx(m):
        return {"tables": {"dissipation_locking_locking": m}, "listed": ALPHAS}
    return [Case("loops later at more dissipation", ctx(lock(lambda a: 80.0 - 20 * a)), "agrees"),
            Case("loops at one frequency", ctx(lock(lambda a: 66.0)), "disagrees",
                 perturbs="loops later at more dissipation")]


def _near(f, f_on):
    return f < f_on + 2


def ergodicity_cases() -> list[Case]:
    """A5's rule (missing verdicts counted as ergodic: the flaw A5b mends)."""
    return [Case("broken just above the onset only", _map(dmap(nonergodic=_near)), "agrees"),
            Case("broken at every third f", _map(dmap(nonergodic=lambda f, o: int(f) % 3 == 0)),
                 "partly", perturbs="broken just above the onset only"),
            Case("ergodic everywhere", _map(dmap()), "inconclusive",
                 perturbs="broken just above the onset only")]


def ergodicity_null_cases() -> list[Case]:
    """A5b's rule."""
    def also_beyond(f, f_on):
        return _near(f, f_on) or int(f) % 10 == 0

    def beyond_unknown(f, f_on):
        return True if _near(f, f_on) else None
    # 'not above the null' can only fail to be shown wrong: its CI reaches above 0 even at 0
    # of 485, so the best this rule gives is 'agrees within the CI'
    return [Case("broken just above the onset only", _map(dmap(nonergodic=_near)),
                 "agrees within the CI"),
            Case("also broken at every tenth f beyond", _map(dmap(nonergodic=also_beyond)),
                 "partly", perturbs="broken just above the onset only"),
            Case("ergodic everywhere", _map(dmap()), "inconclusive",
                 perturbs="broken just above the onset only"),
            Case("no verdict beyond the window", _map(dmap(nonergodic=beyond_unknown)),
                 "not measured", perturbs="broken just above the onset only")]


def _cuts(shift: float, name: str = "figure2") -> dict:
    return {"tables": {"dissipation_cuts": cut_table(shift, name)}}


def cuts_cases() -> list[Case]:
    """A6's rule."""
    return [Case("a cut equal to its scene", _cuts(1.0), "agrees"),
            Case("a cut 20 % off", _cuts(1.2), "disagrees", perturbs="a cut equal to its scene")]


def cuts_consistency_cases() -> list[Case]:
    """A6b's rule (a consistency check)."""
    return [Case("a cut equal to its scene", _cuts(1.0), "consistent"),
            Case("a cut 20 % off", _cuts(1.2), "inconsistent",
                 perturbs="a cut equal to its scene")]


def own_seed_cut_cases() -> list[Case]:
    """A6c's rule: the own-seed cut, when there is one."""
    return [Case("own-seed cut equal to Fig. 2", _cuts(1.0, "figure2_own_seeds"), "agrees"),
            Case("own-seed cut 20 % off", _cuts(1.2, "figure2_own_seeds"), "disagrees",
                 perturbs="own-seed cut equal to Fig. 2"),
            Case("only the shared-seed cuts", _cuts(1.0), "not measured",
                 perturbs="own-seed cut equal to Fig. 2")]
