"""The D(f) table of a store with positions: one row per frequency, D with bootstrap CIs,
ergodicity verdicts, stationarity and, on a conveyor, transport.

``diffusion.parquet`` / ``diffusion.csv`` (stores with positions), one row per frequency:

f            floor frequency, Hz
Gamma        peak floor acceleration A (2 pi f)^2 / g
D, D_lo, D_hi  D of all families pooled, mm^2/s, from the fit MSD(lag) = 2 D lag + c to the
             time-and-ensemble averaged MSD (bbb.analysis.stats), with its bootstrap CI over particles
             (pipeline.execute.intervals.row_intervals: with one family the very CI its stopping rule read);
             D_hi NaN where no particle moved (the data bound the share of movers, not D); all
             three NaN where the estimator failed (CI below 0)
D_status     what the CI means (bbb.analysis.stats.interval): "ok", or per pooled/family the notes
             "rare movers (n_eff ..): calibrated coverage ..", "no mover among N: mover share
             < .. %" (no particle of the pool / family left its cell, see n_moving; a failed
             estimator stays "estimator failed"), "estimator failed: fit D = .. [.., ..] mm^2/s
             < 0 significantly"
D_cover      the pooled CI's coverage: the nominal level, or the rare-mover rule's calibrated
             coverage at the sample's n_eff (bbb/analysis/stats/rare_movers_calibration.json) where it
             applies; NaN where no mover or the estimator failed
mover_share_hi  (no mover only) the one-sided upper bound on the share of moving particles
D_last       the single-origin MSD(t_end) / (2 t_end), mm^2/s, over the whole run (paper Eq. 10)
n_particles, n_moving  particles analysed (of done chunks), and those that left their cell:
             farther than S from their position at the start of the analysed part at some
             time of it (bbb.analysis.moving.displaced; rounding-level changes of x never count)
t_max        simulated time, s
fit_from, fit_to  lag range of the fit, s;  eb_lag: lag of EB, s
EB           ergodicity-breaking parameter Var(δ²)/<δ²>² at eb_lag, all families pooled
EB_threshold eb_tolerance x its value for Brownian motion at that lag and run length
EB_decay     EB over the first half of the analysed run / EB over all of it (same lag, pooled):
             ~2 for ergodic motion (EB ~ 1/T), ~1 for a population mixing different D
EB_decay_threshold  the smallest passing EB_decay, halfway between 1 and the Brownian ratio
ergodic      bbb.analysis.stats.ergodic_verdict under its rule (docs/statistics.md): by default (a) the
             families' D agree within their CIs and (b) the spread CV_D <= cv_max; NA (with
             families_agree .. spread_ok) where n_moving = 0: EB then measures motion within
             the cells (or rounding), and the verdict column says so
families_agree, eb_ok  the outcomes of (a) and of the rule's EB part (b) ((a) is true with a
             single family)
rule         the rule's name;  level_ok, decay_ok, spread_ok  each EB component on its own
CV2_D, CV2_D_lo, CV2_D_hi  estimated squared CV of the per-particle D, 2 EB - EB(T/2), pooled,
             signed (noise takes it below 0), with its two-sided bootstrap CI over particles
CV_D, CV_D_upper  sqrt(CV2_D) where CV2_D > 0 (else NaN), and the square root of CV2_D's
             one-sided 95 % upper bound (a larger spread is excluded; NaN where that bound is
             <= 0); cv_max the rule's limit on CV
rule_fp, rule_fn  the rule's worst measured false-positive / false-negative rates on
             synthetic populations of the nearest calibrated size
D_<fam>, D_<fam>_lo, D_<fam>_hi, EB_<fam>, EB_decay_<fam>  the same per initial-condition family
             (D's CI: the one the family's stopping rule read; NaN / D_status as for D)
D_half1, D_half2  D of the first and the second half of the analysed run (pooled), mm^2/s,
             fitted over the same fractions of a half (bbb.analysis.stationarity)
dD, dD_lo, dD_hi  D_half2 - D_half1 with its paired bootstrap CI over particles, mm^2/s
dD_tol       what that CI must clear to flag: 5 % of D plus 1e-6 mm^2/s
stationary   False where D depends on the run length (the CI of dD lies beyond +-dD_tol)
verdict      the verdict's reasons, '; '-joined
stop         (target-driven stores only) why sampling stopped: "target met" (CI half-width
             <= target_ci * D), "resolved to ±d_resolved" (half-width <= d_resolved before the
             target was met: D known to +-d_resolved only, at any size of D; docs/accuracy.md),
             "cap" or "open"; "family: reason; ..." with several families
v, v_lo, v_hi  (scenes with tilt or throw only) drift velocity, mm/s, with its bootstrap CI
             over particles (bbb.analysis.transport: slope of the mean displacement over the fit
             lags); v_lo, v_hi NaN unless v_status is "ok" or "by construction"
v_status     what v means (bbb.analysis.transport.v_status): "ok" (a steady drift), "accelerating"
             (steady False: v is the mean velocity over the analysed run, not a drift; read a),
             "no mover" (n_moving = 0: v's CI, D_drift and Pe NaN), "by construction" (mirror
             symmetry: v = 0 exactly), "not measured" (dv could not be estimated)
a, a_lo, a_hi  the acceleration 2 dv / T_a (T_a the analysed duration), mm/s^2, with dv's CI
             scaled alike: exact for a uniform acceleration
v_by         how the particles count (the families' mirror key, Study.pairing): "mirror
             symmetry" -- on a level floor vibrated vertically every particle's mirror image
             counts, so v = v_lo = v_hi = 0 and dv = 0 exactly, by construction (not an
             estimate); "pairs" -- simulated mirror pairs, every bootstrap of the row (D, v,
             D_drift, dv, dD, the MSD slope ratio; not EB) resamples pairs; "independent"
D_drift, D_drift_lo, D_drift_hi  D about the drift (MSD of x - v t), mm^2/s, with its CI;
             there the column D still holds the raw MSD's D, drift included; NaN where its CI
             lies below 0 (an estimator failure, as for D)
D_drift_status  "ok", or the failed fit's numbers, or "no mover among N: .."
Pe           Péclet number v S / D_drift; NaN unless v_status is "ok" or "by construction"
dv, dv_lo, dv_hi  v of the analysed run's second half minus its first half, mm/s, paired CI
dv_tol       the band that CI must leave to flag, mm/s: 5 % of |v| + k SE(v) + 1e-6 mm/s
             (k calibrated, bbb/transport_rules.json)
steady       False where the CI of dv lies beyond +-dv_tol: an acceleration (a particle
             running away downhill), not a drift -- v and D_drift are then window means; NA
             where untested (no mover, dv not measured)
msd_slope_ratio, msd_slope_ratio_lo, msd_slope_ratio_hi  slope of the MSD about the drift over
             the upper half of the fit lags / over the lower half, with its bootstrap CI: 1
             for diffusion (any intercept), up to ~2 for particles running at different speeds
diffusive    False where that CI lies above 1 + a calibrated tolerance: the MSD about the
             drift still steepens over the fit lags (particles at different speeds, or velocity
             memory as long as the lags), so D_drift is a window slope (NA: nothing moves)

Units of every column: :mod:`pipeline.tables.units`.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..execute.intervals import row_intervals
from ..store.layout import STOP_LEGEND
from ..store.study_store import StudyStore
from ..workflow.identity import child_seed, reduce_seed
from ..workflow.study import Study
from .notes import ACCEL_TEXT, DRIFT_TEXT

__all__ = ["diffusion_table"]

#: the ergodicity verdict's booleans: NA on a row where no particle left its cell
_VERDICTS = ("ergodic", "families_agree", "eb_ok", "level_ok", "decay_ok", "spread_ok")
#: what the verdict column says there
NO_MOVER_VERDICT = ("no particle left its cell: EB and D agreement of motion within the "
                    "cells, ergodicity not tested")


def diffusion_table(store: StudyStore, done: np.ndarray) -> pd.DataFrame:
    """One row per point (columns in the module docstring; a grid's axes follow f)."""
    from bbb.analysis import stats
    from bbb.analysis.moving import displaced
    from bbb.analysis.transport import ACCELERATING

    study = store.study
    an, acc = study.analysis, study.accuracy
    times = study.sample_times()
    T = an.duration(acc.t_max)
    fit_from, fit_to, eb_lag = an.fit_from * T, an.fit_to * T, an.eb_lag * T
    fit = dict(fit_from=fit_from, fit_to=fit_to, discard=an.discard)
    stops = store.stops()
    rows = []
    conveyor = bool({"tilt", "throw"} & (study.overrides.keys() | {a for a, _ in study.grid})) \
        or not study.mirror_symmetric
    for fi, point in enumerate(study.points):
        f = point.f
        parts = {mi: (store.read_done("positions", fi, mi, done[fi, mi]),  # (particle, time)
                      int(done[fi, mi].sum())) for mi in range(len(study.families))}
        fam_ci, pooled = row_intervals(study, fi, parts)
        fams = {study.families[mi].name: parts[mi][0] for mi in fam_ci}
        row: dict = {**point.columns(), "Gamma": point.params.gamma}
        if not fams:
            rows.append(row)
            continue
        x = np.concatenate(list(fams.values()))
        pairing, units = _pairing(study, fams, point if study.grid else None)
        seed = reduce_seed(study, f)
        est = stats.diffusion_coefficient(x, times, **fit)
        moved = {name: displaced(xf, point.params.S, an.discard) for name, xf in fams.items()}
        n_moving = sum(int(m.sum()) for m in moved.values())
        named = {study.families[mi].name: r for mi, r in fam_ci.items()}
        named = {name: _unless_moved(r, int(moved[name].sum()), an.ci) for name, r in named.items()}
        pooled = named[next(iter(named))] if len(named) == 1 else _unless_moved(pooled, n_moving,
                                                                                 an.ci)
        verdict = stats.ergodic_verdict(
            fams, times, lag=eb_lag, tolerance=an.eb_tolerance, ci=an.ci,
            n_resamples=acc.n_resamples, seed=int(seed.generate_state(1)[0]), family_ci=named,
            mover_share={name: float(m.mean()) for name, m in moved.items()}, **fit)
        eb_pooled = verdict.eb.get("(pooled)", next(iter(verdict.eb.values())))
        key = "(pooled)" if "(pooled)" in verdict.eb else next(iter(verdict.eb))
        decay = _ratio(verdict.eb_half.get(key, math.nan), verdict.eb[key])
        row.update(_d_columns("D", pooled))
        row.update(
            D_status=_status_text(pooled, named), D_cover=pooled.coverage,
            mover_share_hi=pooled.mover_share_hi,
            D_last=est.D_last, n_particles=x.shape[0],
            n_moving=n_moving, t_max=acc.t_max,
            fit_from=est.fit_from, fit_to=est.fit_to, eb_lag=verdict.lag, EB=eb_pooled,
            EB_threshold=verdict.eb_threshold, EB_decay=decay,
            EB_decay_threshold=verdict.eb_decay_threshold, ergodic=bool(verdict.ergodic),
            families_agree=bool(verdict.agreement_ok), eb_ok=bool(verdict.eb_ok),
            rule=verdict.rule, level_ok=bool(verdict.level_ok), decay_ok=bool(verdict.decay_ok),
            spread_ok=bool(verdict.spread_ok), CV2_D=verdict.cv2_hat.get(key, math.nan),
            CV2_D_lo=verdict.cv2_lo, CV2_D_hi=verdict.cv2_hi,
            CV_D=verdict.cv_hat.get(key, math.nan), CV_D_upper=verdict.cv_upper,
            cv_max=verdict.cv_max, rule_fp=verdict.error_rates.get("fp", math.nan),
            rule_fn=verdict.error_rates.get("fn", math.nan),
        )
        for name, d in verdict.D.items():
            row.update(_d_columns(f"D_{name}", d))
            row.update({f"EB_{name}": verdict.eb.get(name, math.nan),
                        f"EB_decay_{name}": _ratio(verdict.eb_half.get(name, math.nan),
                                                   verdict.eb.get(name, math.nan))})
        row["verdict"] = "; ".join(verdict.reasons)
        if n_moving == 0:  # EB of rounding-level motion: no verdict (module docstring)
            row.update(dict.fromkeys(_VERDICTS, pd.NA))
            row["verdict"] = f"n/a: {NO_MOVER_VERDICT}; " + row["verdict"]
        if stops is not None:
            row["stop"] = _stop_text(study, stops[1][fi])
        row.update(_stationarity_columns(x, times, an, acc, seed, units))
        if conveyor:  # a conveyor (even at tilt = 0), at every point of a grid
            row.update(_transport_columns(x, times, point.params.S, study, seed, fit, pairing,
                                          units))
            if row["v_lo"] > 0 or row["v_hi"] < 0:  # D is the raw MSD's slope: v² t included
                row["D_status"] += f"; {DRIFT_TEXT}"
            elif row["v_status"] == ACCELERATING:  # its CI blank; D holds the acceleration
                row["D_status"] += f"; {ACCEL_TEXT}"
        rows.append(row)
    df = pd.DataFrame(rows)
    for col in (*_VERDICTS, "stationary", "steady", "diffusive"):
        if col in df:
            df[col] = df[col].astype("boolean")
    return df


def _unless_moved(r, n_moving: int, ci: float):
    """D's interval ``r`` (bbb.analysis.stats.interval.DInterval), or, where none of its
    particles left its cell (``n_moving`` = 0), the same D and CI with the status "no mover"
    and the bound on the share of movers: the CI stays the one the stopping rule read (one CI
    for the stop and the table), and the note says it is motion within the cells, not
    diffusion.  A failed estimator stays failed (D blank)."""
    from bbb.analysis.stats.interval import FAILED, NO_MOVER
    from bbb.analysis.stats.rare import mover_share_bound

    if r is None or n_moving > 0 or r.status in (FAILED, NO_MOVER):
        return r
    return r._replace(status=NO_MOVER, coverage=math.nan,
                      mover_share_hi=mover_share_bound(r.n, ci))


def _d_columns(prefix: str, r) -> dict:
    """D and its CI as columns ``prefix``, ``prefix_lo``, ``prefix_hi``: NaN where the
    estimator failed (its numbers stay in D_status), never a value with a CI then."""
    if not r.valued:
        return {prefix: math.nan, f"{prefix}_lo": math.nan, f"{prefix}_hi": math.nan}
    return {prefix: r.D, f"{prefix}_lo": r.lo, f"{prefix}_hi": r.hi}


def _status_text(pooled, families: dict) -> str:
    """D_status: "ok", or the notes of the pooled CI and of each family whose CI is not plain
    (one family: its CI is the pooled one, noted once)."""
    from bbb.analysis.stats.interval import OK

    if len(families) == 1:
        return pooled.note()
    notes = [(name, r) for name, r in (("pooled", pooled), *families.items()) if r.status != OK]
    return "; ".join(f"{name}: {r.note()}" for name, r in notes) or OK


def _stop_text(study: Study, reasons: np.ndarray) -> str:
    """Why each family of one frequency stopped sampling (pipeline.store.layout.STOP_LEGEND)."""
    texts = [STOP_LEGEND[int(r)] for r in reasons]
    if len(texts) == 1:
        return texts[0]
    return "; ".join(f"{fam.name}: {t}" for fam, t in zip(study.families, texts, strict=True))


def _pairing(study: Study, fams: dict[str, np.ndarray], point=None
             ) -> tuple[str, np.ndarray | None]:
    """How the pooled particles of one frequency count (bbb.analysis.transport.PAIRING) and, with mirror
    pairs, the pair labels of the pooled rows (:func:`pipeline.execute.intervals.pair_units`).  Images
    count by symmetry only when every family is mirrored; pairs are all or none on a conveyor
    (pipeline.workflow.load)."""
    from ..execute.intervals import pair_units

    by_name = {fam.name: fam for fam in study.families}
    kinds = {study.pairing(by_name[name], point) for name in fams}
    if kinds != {"pairs"}:
        return ("mirror symmetry" if kinds == {"mirror symmetry"} else "independent"), None
    return "pairs", pair_units(study, [(by_name[name], pos.shape[0]) for name, pos in fams.items()],
                               point)


def _stationarity_columns(x: np.ndarray, times: np.ndarray, an, acc,
                          seed: np.random.SeedSequence, units: np.ndarray | None = None) -> dict:
    from bbb.analysis.stationarity import stationarity

    try:
        s = stationarity(x, times, n_resamples=acc.n_resamples, ci=an.ci,
                         seed=child_seed(seed, "stationarity"),
                         discard=an.discard, fit_from=an.fit_from, fit_to=an.fit_to,
                         units=units)
    except ValueError:  # a half too short for two fit lags: no check, not a flag
        return {}
    return {"D_half1": s.D_half1, "D_half2": s.D_half2, "dD": s.dD, "dD_lo": s.dD_lo,
            "dD_hi": s.dD_hi, "dD_tol": s.tolerance, "stationary": s.stationary}


def _transport_columns(x: np.ndarray, times: np.ndarray, S: float, study: Study,
                       seed: np.random.SeedSequence, fit: dict, pairing: str = "independent",
                       units: np.ndarray | None = None) -> dict:
    """The transport columns of one point, whose scatterer spacing is S (mm)."""
    from bbb.analysis.transport import transport

    an = study.analysis
    t = transport(x, times, S, n_resamples=study.accuracy.n_resamples,
                  ci=an.ci, method=an.ci_method, seed=child_seed(seed, "transport"),
                  pairing=pairing, units=units, **fit)
    return {"v": t.v, "v_lo": t.v_lo, "v_hi": t.v_hi, "v_by": t.v_by, "D_drift": t.D,
            "D_drift_lo": t.D_lo, "D_drift_hi": t.D_hi, "D_drift_status": t.D_status, "Pe": t.Pe, "dv": t.dv,
            "dv_lo": t.dv_lo, "dv_hi": t.dv_hi, "dv_tol": t.dv_tol, "steady": t.steady,
            "msd_slope_ratio": t.curvature, "msd_slope_ratio_lo": t.curvature_lo,
            "msd_slope_ratio_hi": t.curvature_hi, "diffusive": t.diffusive,
            "v_status": t.v_status, "a": t.a, "a_lo": t.a_lo, "a_hi": t.a_hi}


def _ratio(a: float, b: float) -> float:
    return a / b if b > 0 else math.nan  # EB = 0 (identical trajectories) or NaN (none move)
