"""What an interval of D says: its status and, where calibrated, its coverage (D in mm²/s).

Every CI of D that `bbb reduce` reports and that the stopping rule of target-driven scenes
reads ends here (:func:`d_interval`, via ``bootstrap_D(..., detail=True)``), so that an
interval never claims more than its data hold:

====================  ====================================================================
status                the interval [lo, hi]
====================  ====================================================================
``ok``                the bootstrap CI over particles; coverage: the nominal ``ci``
``rare movers``       widened by the rare-mover rule (:mod:`bbb.analysis.stats.rare`); coverage: the
                      rule's calibrated coverage at the sample's n_eff (below nominal where
                      few particles move; read from ``rare_movers_calibration.json``, made by
                      ``benchmarks/calibrations/rare_movers.py --json``)
``no mover``          no D_i > 0: the data bound the share of movers (< ``mover_share_hi``
                      at level ci, :func:`bbb.analysis.stats.rare.mover_share_bound`), not D: hi is
                      NaN (no upper bound), lo the sample's D; coverage NaN.  Also (set by
                      `bbb reduce`) where some D_i > 0 but no particle left its cell: [lo, hi]
                      is then the CI the stopping rule read, of motion within the cells, not
                      of diffusion, and the note says so
``estimator failed``  the interval lies below 0: D < 0 significantly, impossible for a
                      diffusion coefficient (e.g. particles still settling within the fit
                      window, so their MSD falls with the lag): D is not measured and (D, lo,
                      hi) must not be shown as a value with a CI; coverage NaN
``no spread``         every particle has the same D_i > 0 (identical trajectories): the
                      sample holds no spread to bound D by: lo = hi = NaN; coverage NaN
====================  ====================================================================

A zero-width interval cannot come out of here: k = 0 movers is ``no mover``, identical D_i
``no spread``, and the interval of a sample with any spread has width.
"""

from __future__ import annotations

import json
import math
from functools import cache
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .rare import effective_movers, is_rare, mover_share_bound, rare_mover_interval

__all__ = ["OK", "RARE", "NO_MOVER", "FAILED", "NO_SPREAD", "STATUSES", "DInterval", "d_interval",
           "rare_coverage", "CALIBRATION"]

OK, RARE, NO_MOVER, FAILED, NO_SPREAD = ("ok", "rare movers", "no mover", "estimator failed",
                                         "no spread")
STATUSES = (OK, RARE, NO_MOVER, FAILED, NO_SPREAD)
#: the rare-mover rule's calibration (benchmarks/calibrations/rare_movers.py --json), read by rare_coverage
CALIBRATION = Path(__file__).with_name("rare_movers_calibration.json")


class DInterval(NamedTuple):
    """D with its interval and what the interval means (module docstring).

    D, lo, hi      -- mm²/s; hi NaN for ``no mover``
    status         -- one of :data:`STATUSES`
    n              -- particles
    n_eff          -- effective movers (Σ c_i)² / Σ c_i², c_i = max(D_i, 0)
    coverage       -- the interval's coverage: nominal ``ci`` (ok), calibrated (rare movers),
                      NaN (no mover, estimator failed; or a level the rule was not calibrated at)
    mover_share_hi -- ``no mover`` only: upper bound on the share of movers, else NaN
    """

    D: float
    lo: float
    hi: float
    status: str
    n: int
    n_eff: float
    coverage: float
    mover_share_hi: float

    @property
    def valued(self) -> bool:
        """Whether (D, lo, hi) may be shown as a value with its CI (not a failed estimator)."""
        return self.status != FAILED

    def note(self) -> str:
        """One line for a table or a report: what the interval means."""
        if self.status == NO_MOVER and not math.isnan(self.hi):
            return (f"no mover among {self.n}: none left its cell, mover share < "
                    f"{100 * self.mover_share_hi:.2g} % (one-sided); D [{self.lo:.3g}, "
                    f"{self.hi:.3g}] mm²/s is motion within the cells, not diffusion")
        if self.status == NO_MOVER:
            return (f"no mover among {self.n}: mover share < {100 * self.mover_share_hi:.2g} % "
                    "(one-sided); D not bounded above by the data")
        if self.status == FAILED:
            return (f"estimator failed: fit D = {self.D:.3g} [{self.lo:.3g}, {self.hi:.3g}] "
                    "mm²/s < 0 significantly (the MSD falls with the lag); D not measured")
        if self.status == NO_SPREAD:
            return (f"no spread: all {self.n} particles have D_i = {self.D:.4g} mm²/s; no "
                    "interval from the sample")
        if self.status == RARE:
            cov = "not calibrated" if math.isnan(self.coverage) else f"{self.coverage:.2f}"
            return f"rare movers (n_eff {self.n_eff:.3g}): calibrated coverage {cov}"
        return OK


def d_interval(d_i: ArrayLike, boot: tuple[float, float, float], ci: float, *,
               rare: bool = True) -> DInterval:
    """The interval of D = mean(D_i) and its status, from the per-particle D_i (mm²/s) and the
    bootstrap CI ``boot`` = (D, lo, hi) at level ``ci``; ``rare`` applies the rare-mover rule
    (its hull with the Fay-Feuer gamma interval where :func:`bbb.analysis.stats.rare.is_rare`)."""
    d = np.asarray(d_i, dtype=np.float64).ravel()
    D, lo, hi = (float(v) for v in boot)
    if not np.any(d > 0.0):
        if hi < 0.0:
            return DInterval(D, lo, hi, FAILED, d.size, 0.0, math.nan, math.nan)
        return DInterval(D, lo, math.nan, NO_MOVER, d.size, 0.0, math.nan,
                         mover_share_bound(d.size, ci))
    n_eff = effective_movers(d)
    if not np.ptp(d) > 0.0:
        return DInterval(D, math.nan, math.nan, NO_SPREAD, d.size, n_eff, math.nan, math.nan)
    status, coverage = OK, ci
    if rare and is_rare(d):
        r_lo, r_hi = rare_mover_interval(d, ci)
        lo, hi = min(lo, r_lo), max(hi, r_hi)
        status, coverage = RARE, rare_coverage(n_eff, ci)
    if hi < 0.0:
        return DInterval(D, lo, hi, FAILED, d.size, n_eff, math.nan, math.nan)
    return DInterval(D, lo, hi, status, d.size, n_eff, coverage, math.nan)


@cache
def _calibration() -> dict:
    return json.loads(CALIBRATION.read_text())


def rare_coverage(n_eff: float, ci: float) -> float:
    """The rare-mover rule's measured coverage (dimensionless) for samples whose n_eff lies in
    the calibration's bin around ``n_eff`` (pooled over its synthetic populations, 128-4096
    particles, light and heavy tails: docs/statistics.md); NaN if ``ci`` is not the level it
    was calibrated at or no bin holds n_eff."""
    cal = _calibration()
    if not math.isclose(ci, cal["ci"], abs_tol=1e-9):
        return math.nan
    for b in cal["coverage_by_n_eff"]:
        top = math.inf if b["n_eff_to"] is None else b["n_eff_to"]
        if b["n_eff_from"] <= n_eff < top:
            return float(b["rule"])
    return math.nan
