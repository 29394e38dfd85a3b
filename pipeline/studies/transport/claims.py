"""The transport claims as data (judged by :mod:`pipeline.claims.claim` from the diffusion table
of each line of the map scenes, with its v, D_drift columns; :mod:`bbb.analysis.transport`).
Claims T1, T2, T4 are judged on five floors of the map ``transport`` (the level floor
vibrated vertically, two tilts, two throws: :data:`HOPPING`); T3 also on its four floors both
tilted and thrown (:data:`COMBINED`) and on every line of the map ``transport_reversal``
(φ = 2° against throws ψ = 90°…30°, stick and Coulomb; :mod:`.reversal`); T5 on the sliding
map; T6 on transport_reversal.

Rules, fixed before the data (calibrated on synthetic curves in
tests/pipeline/studies/transport/test_claims.py):

significant v   :mod:`pipeline.claims.signs`: v ≠ 0 at a point of a curve when |v| exceeds
                z_n standard errors, z_n = Φ⁻¹(1 − α / (2 n)) Bonferroni over the n points of
                the curve, α = 0.05, and |v| > V_MIN = 1e-6 mm/s.
steady only     every rule uses the frequencies whose drift is steady (bbb.analysis.transport: not
                steady when the CI of v(second half) − v(first half) lies beyond ±(5 % of |v|
                + k SE(v) + 1e-6 mm/s), k calibrated on synthetic steady and accelerating
                drifts, bbb/transport_rules.json); where the ensemble accelerates (runs away
                downhill) v and D are window means, not transport coefficients.  The rows say
                how many frequencies were left out.
diffusive only  an extremum of v(f) or of D_drift(f) at a frequency whose D about the drift is
                not diffusive (bbb.analysis.transport: the CI of the MSD's slope ratio, upper over
                lower half of the fit lags, lies above 1 + a calibrated tolerance) is not
                counted: the MSD about the drift still steepens over the fit lags -- particles
                running at different speeds (some stuck), or velocity memory as long as the
                lags -- so D_drift is a window slope, not a diffusion coefficient, and v may
                average a population that does not mix.  The rows name them.
reversal        a sign change between consecutive significant points (those in between not
                significant), located as the interval between the last significant point of
                one sign and the first of the other (:mod:`pipeline.claims.signs`).  T3 counts
                them along f on every conveyor line (:data:`GEOMETRIES`) and along ψ at each
                fixed f on the tilted floors (the cuts of the lines sharing tilt and contact
                model, ψ from 90° down); it agrees with ≥ 1.
hopping         T6, per line of transport_reversal: the sliding/hopping boundary, from the last
                frequency whose airborne share (1 − time held − time sliding) is significantly
                below H to the first significantly above it (H read from hopping.json, checked
                on flat floors where the answer is Γ_v = 1: :mod:`.hopping_calibration`), minus
                the f of Γ_v = Γ sin ψ / cos φ = 1, must lie within ± one frequency step.
extrema         bbb.analysis.extrema.find_extrema (Bonferroni over all pairs, family-wise α = 0.05)
                on v(f) and on D_drift(f), min_depth = V_MIN resp. D_MIN = 1e-6 mm²/s.
                "Extrema of the transport rate": ≥ 1 extremum of v(f) per conveyor scene.
                "D irregular": ≥ 2 extrema of D_drift(f) (a curve with a maximum and a
                minimum is not monotonic) per conveyor scene; the row also gives the count
                at φ = 0, ψ = 90°.
no current      at φ = 0, ψ = 90° (mirror symmetric): no frequency with a significant v.  With
                mirror pairs (the default there) every particle's image counts and v = 0
                exactly: the claim then holds by construction, a property of the design, not
                a measurement, and the row says so.  With independent particles the rule fails
                by chance on a measured fraction of current-free curves (its design
                false-alarm rate, benchmarks/calibrations/transport_mirror.py -> mirror.json).
sliding         on the sliding scenes' floor (φ = 0°, ψ = 30°), below its lift-off frequency
                (bbb.analysis.liftoff: no particle at rest anywhere on the floor can lift off there),
                the frequencies with a significant v: 0 under stick (a stuck particle rides
                with the floor, v = 0 up to rounding) and ≥ 1 under Coulomb friction.

Registered later, each beside the claim whose rule or scope it changes (ids in :data:`CLAIMS`):

T1b             T1 as what it is: with mirror pairs v = 0 exactly, 'by construction'; with
                independent particles T1's rule.
T3              restored to the rule and scope it was registered and first judged with: a sign
                change of v along f on the four conveyor floors of scene transport (φ = 2°, 5°
                at ψ = 90°; φ = 0° at ψ = 60°, 30°).  T3b is the rule of the reversal section
                above, registered after T3's data (the floors tilted against their throw,
                scene transport_reversal, and sign changes along ψ added).
T6b             the sliding/hopping boundary by lift-offs per floor period (a lift-off starts a
                flight from contact; a chatter of bounces that never rest counts none): the
                first frequency whose lift-offs per period reach L, L read from liftoffs.json
                (benchmarks/calibrations/hopping_liftoffs.py checks it on flat floors, where the answer is
                Γ_v = 1), and the frequency before it bound the boundary; judged as T6 (± one
                frequency step), on every line of transport_reversal (a line without counters:
                not measured).

k = 2 v_y⁺ f / g needs post-collision states, which these positions-only scenes do not
record: the extrema are reported by frequency.

Size: over 400 lines because a registered claim stays once judged: the frozen rules of
T1, T3, T6 and their measures sit beside the ids that supersede them (one study's claims, one
module).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from importlib import resources

import numpy as np
import pandas as pd

from bbb import Params
from bbb.analysis.extrema import find_extrema
from bbb.analysis.liftoff_onset import liftoff_frequency
from bbb.analysis.transport import SYMMETRY

from ...claims.claim import (
    BY_CONSTRUCTION,
    Band,
    Claim,
    Measured,
    Part,
    Quantity,
    measure,
)
from ...claims.signs import V_MIN, reversals, significant_signs, steady_rows
from ..map_lines import split_lines
from .cases import (
    d_extrema_cases,
    hopping_cases,
    liftoff_cases,
    no_current_cases,
    no_current_construction_cases,
    reversal_cases,
    reversal_f_cases,
    sliding_cases,
    v_extrema_cases,
)
from .reversal import (
    AIRBORNE_MIN,
    F_STEP,
    REVERSAL_LINES,
    REVERSAL_MAP,
    airborne,
    f_ranges,
    f_reversals,
    floor_label,
    hopping_boundary,
    judge_boundary,
    liftoff_boundary,
    line_label,
    throw_cuts,
    throw_number_frequency,
    throw_reversals,
)

__all__ = ["SCENES", "MAP", "SLIDING_MAP", "LINES", "HOPPING", "COMBINED", "CONVEYORS",
           "LABELS", "SLIDING", "SLIDING_LABELS", "SLIDING_GEOMETRY", "GEOMETRIES",
           "line_tables", "sliding_liftoff", "CLAIMS", "context", "WORDS"]

from .lines import (  # noqa: E402  (the lines, importable from here as before)
    COMBINED,
    CONVEYORS,
    GEOMETRIES,
    HOPPING,
    LABELS,
    LINES,
    MAP,
    SCENES,
    SLIDING,
    SLIDING_GEOMETRY,
    SLIDING_LABELS,
    SLIDING_MAP,
)

D_MIN = 1e-6  # mm²/s
#: the mirror-pair benchmark: variance saved per scene, T1's false alarms without pairs
MIRROR: dict = json.loads(resources.files(__package__).joinpath("mirror.json")
                          .read_text(encoding="utf-8"))
#: T6b's threshold: lift-offs per floor period (benchmarks/calibrations/hopping_liftoffs.py, flat floors)
LIFTOFFS: dict = json.loads(resources.files(__package__).joinpath("liftoffs.json")
                            .read_text(encoding="utf-8"))
LIFTOFF_MIN = float(LIFTOFFS["threshold"])


def _table(ctx, scene: str) -> pd.DataFrame | None:
    """The scene's rows with a steady drift, sorted by f (attrs["unsteady"]: the others' f)."""
    return steady_rows(ctx["tables"].get(scene))


def _left_out(t: pd.DataFrame) -> str:
    u = t.attrs.get("unsteady", [])
    return (f" [{len(u)} f left out, drift not steady: {min(u):g}–{max(u):g} Hz]" if u else "")


def _extrema_text(ex) -> str:
    return ", ".join(f"{e.kind} {e.f:g} Hz" for e in ex) or "none"


def _counted(ex, t: pd.DataFrame) -> tuple[list, str]:
    """The extrema at frequencies whose D about the drift is diffusive (the column
    ``diffusive``, NA counts as diffusive: nothing moves to test) and a text naming the
    others."""
    if "diffusive" not in t:
        return list(ex), ""
    bad = set(t["f"][~t["diffusive"].fillna(True).astype(bool)])
    keep = [e for e in ex if e.f not in bad]
    dropped = [e for e in ex if e.f in bad]
    return keep, (f"; not counted: {_extrema_text(dropped)} (D about the drift not diffusive)"
                  if dropped else "")


def _design_false_alarms() -> str:
    fa = MIRROR.get("t1_false_alarm")
    if not fa:
        return ""
    return (f"With independent particles this rule fails by chance on {100 * fa['rate']:.1f} % "
            f"[{100 * fa['lo']:.1f}, {100 * fa['hi']:.1f}] % of current-free curves "
            f"({fa['n_frequencies']} frequencies x {fa['n_particles']} particles; "
            f"{fa['curves']} null curves, benchmarks/calibrations/transport_mirror.py).")


@measure("transport_no_current")
def no_current(claim: Claim, ctx) -> Measured:
    t = _table(ctx, claim.scene)
    if t is None:
        return Measured(missing=f"no transport columns for {claim.scene}")
    if "v_by" in t and len(t) and (t["v_by"] == SYMMETRY).all():
        return Measured([Part(LABELS[claim.scene], Quantity(0.0),
                              f"v = 0 exactly at all {len(t)} frequencies, by construction: "
                              "every particle's mirror image counts (mirror pairs on a "
                              "mirror-symmetric floor), so the claim is a property of the "
                              "ensemble's design, not a measurement")],
                        note=_design_false_alarms(),
                        verdict=BY_CONSTRUCTION if claim.options.get("construction") else None)
    s = significant_signs(t["v"], t["v_lo"], t["v_hi"])
    where = t["f"][s != 0].tolist()  # steady rows only; at φ = 0, ψ = 90° all should be
    vmax = float(np.abs(t["v"]).max())
    return Measured([Part(LABELS[claim.scene], Quantity(float(len(where))),
                          f"{len(where)} of {len(t)} frequencies with a significant v "
                          f"({', '.join(f'{x:g}' for x in where) or 'none'}); max |v| = "
                          f"{vmax:.3g} mm/s")], note=_design_false_alarms())


@measure("transport_v_extrema")
def v_extrema(claim: Claim, ctx) -> Measured:
    parts = []
    for sc in CONVEYORS:
        t = _table(ctx, sc)
        if t is None:
            continue
        ex, dropped = _counted(find_extrema(t["f"], t["v"], t["v_lo"], t["v_hi"],
                                            min_depth=V_MIN), t)
        parts.append(Part(LABELS[sc], Quantity(float(len(ex))),
                          f"{len(ex)} ({_extrema_text(ex)}{dropped}); v from {t['v'].min():.3g} "
                          f"to {t['v'].max():.3g} mm/s{_left_out(t)}"))
    return Measured(parts) if parts else Measured(missing="no conveyor scene reduced")


def _sign(s: int) -> str:
    return "+" if s > 0 else "−"


@measure("transport_reversals")
def v_reversals(claim: Claim, ctx) -> Measured:
    along_f, quiet, total = [], [], 0
    for sc, values in GEOMETRIES.items():
        r = f_reversals(ctx["tables"].get(sc))
        if r is None:
            continue
        found, s, t = r
        total += len(found)
        if not found:
            quiet.append(line_label(values) + _left_out(t))
            continue
        along_f.append(f"{line_label(values)}: " + ", ".join(
            f"{a:g}–{b:g} Hz ({_sign(-k)} → {_sign(k)})" for a, b, k in found)
            + f" (v > 0 at {int((s > 0).sum())}, < 0 at {int((s < 0).sum())} of {len(t)} f"
            f"{_left_out(t).replace(' [', '; ').rstrip(']')})")
    if not along_f and not quiet:
        return Measured(missing="no conveyor scene reduced")
    tilted = {sc: (v, ctx["tables"].get(sc)) for sc, v in GEOMETRIES.items() if v["tilt"] != 0}
    by_floor: dict[tuple, dict] = {}
    for floor, f, change in throw_reversals(throw_cuts(tilted)):
        by_floor.setdefault(floor, {}).setdefault(change, []).append(f)
    along_psi = [f"{floor_label(floor)}: " + "; ".join(
        f"ψ {a:g}°→{b:g}° ({_sign(-k)} → {_sign(k)}) at {f_ranges(fs)}"
        for (a, b, k), fs in changes.items()) for floor, changes in by_floor.items()]
    n_psi = sum(len(fs) for changes in by_floor.values() for fs in changes.values())
    total += n_psi
    text = ("along f: " + ("; ".join(along_f) or "none")
            + (f"; no significant sign change along f on {len(quiet)} lines "
               f"({', '.join(quiet)})" if quiet else "")
            + f". Along ψ at fixed f (tilted floors, ψ from 90° down): {n_psi} ("
            + (". ".join(along_psi) or "none") + ")")
    return Measured([Part("significant sign changes of v along f or ψ at a fixed floor, all "
                          "conveyor floors", Quantity(float(total)), text)])


@measure("transport_reversals.along_f")
def v_reversals_along_f(claim: Claim, ctx) -> Measured:
    """T3 as registered: sign changes of v(f) between significant frequencies (Bonferroni
    over each curve) on the conveyor floors of scene transport."""
    texts, total, seen = [], 0, False
    for sc in CONVEYORS:
        t = _table(ctx, sc)
        if t is None:
            continue
        seen = True
        s = significant_signs(t["v"], t["v_lo"], t["v_hi"])
        r = reversals(t["f"].to_numpy(), s)
        total += len(r)
        texts.append(f"{LABELS[sc]}: {len(r)} ({', '.join(f'~{x:g} Hz' for x in r) or 'none'}; "
                     f"v > 0 at {int((s > 0).sum())}, < 0 at {int((s < 0).sum())} of {len(t)} f)"
                     f"{_left_out(t)}")
    if not seen:
        return Measured(missing="no conveyor scene reduced")
    return Measured([Part("significant sign changes of v(f), all conveyor scenes",
                          Quantity(float(total)), "; ".join(texts))])


@measure("transport_d_extrema")
def d_extrema(claim: Claim, ctx) -> Measured:
    def count(sc):
        t = _table(ctx, sc)
        if t is None:
            return None
        ex, dropped = _counted(find_extrema(t["f"], t["D_drift"], t["D_drift_lo"],
                                            t["D_drift_hi"], min_depth=D_MIN), t)
        return ex, dropped + _left_out(t)

    ref = count(HOPPING[0])
    parts = [Part(LABELS[sc], Quantity(float(len(ex))), f"{len(ex)} ({_extrema_text(ex)}{lo})")
             for sc in CONVEYORS if (r := count(sc)) is not None for ex, lo in [r]]
    if not parts:
        return Measured(missing="no conveyor scene reduced")
    ref_txt = ("not reduced" if ref is None
               else f"{len(ref[0])} ({_extrema_text(ref[0])}{ref[1]})")
    return Measured(parts, text=f"at {LABELS[HOPPING[0]]}: {ref_txt}")


def sliding_liftoff() -> float:
    """The sliding scenes' lift-off frequency (Hz, bbb.analysis.liftoff_onset): below it no particle at rest
    anywhere on their floor can lift off."""
    return liftoff_frequency(Params.preset("klages2004", f=1.0, **SLIDING_GEOMETRY))


@measure("transport_sliding")
def sliding(claim: Claim, ctx) -> Measured:
    f_lift = sliding_liftoff()
    parts = []
    for sc, contact, _ in SLIDING:
        t = _table(ctx, sc)
        if t is None:
            continue
        s = significant_signs(t["v"], t["v_lo"], t["v_hi"])  # Bonferroni over the whole curve
        below = (t["f"] < f_lift).to_numpy()
        hits = t["f"][below & (s != 0)].tolist()
        vmax = float(np.abs(t["v"][below]).max()) if below.any() else math.nan
        band = (Band(0.0, 0.0, "at rest below lift-off, a stuck particle rides with the floor")
                if contact == "stick" else
                Band(1.0, math.inf, "friction that lets go carries particles before any hop"))
        parts.append(Part(SLIDING_LABELS[sc], Quantity(float(len(hits))),
                          f"{len(hits)} of {int(below.sum())} frequencies below {f_lift:.1f} Hz "
                          f"with a significant v ({', '.join(f'{x:g}' for x in hits) or 'none'});"
                          f" max |v| there {vmax:.3g} mm/s{_left_out(t)}", band=band))
    return Measured(parts) if parts else Measured(missing="no sliding scene reduced")


@measure("transport_hopping_boundary")
def hopping_vs_throw_number(claim: Claim, ctx) -> Measured:
    parts = []
    for sc, values in REVERSAL_LINES.items():
        c = ctx.get("contact", {}).get(sc)
        if c is None or not len(c):
            continue
        a = airborne(c)
        b = hopping_boundary(a["f"], a["air_lo"], a["air_hi"], AIRBORNE_MIN)
        f_v = throw_number_frequency(values["tilt"], values["throw"])
        _, q = judge_boundary(b, f_v)
        per = ""
        n = ctx.get("counters", {}).get(sc)
        if b is not None and n is not None and "liftoffs_per_s" in n:
            hop = n[np.isclose(n["f"], b[1])]
            per = (f"; lift-offs per period at {b[1]:g} Hz: "
                   f"{float(hop['liftoffs_per_s'].iloc[0]) / b[1]:.2f}" if len(hop) else "")
        where = ("no boundary in the scene's range (airborne share "
                 f"{a['air'].min():.2g}–{a['air'].max():.2g})" if b is None else
                 f"boundary {b[0]:g}–{b[1]:g} Hz (airborne share {a['air'][a['f'] == b[0]].iloc[0]:.2g}"
                 f" → {a['air'][a['f'] == b[1]].iloc[0]:.2g})")
        parts.append(Part(line_label(values), q if q is not None else Quantity(math.nan),
                          f"{where}, Γ_v = 1 at {f_v:.1f} Hz{per}", found=b is not None))
    return Measured(parts) if parts else Measured(missing="no transport_reversal contact table")


@measure("transport_liftoff_boundary")
def liftoff_vs_throw_number(claim: Claim, ctx) -> Measured:
    """T6b: per line of transport_reversal, the boundary by lift-offs per period against the f
    of Γ_v = 1 (:func:`.reversal.liftoff_boundary`, :func:`.reversal.judge_boundary`)."""
    threshold = float(claim.options.get("threshold", LIFTOFF_MIN))
    counters = ctx.get("counters", {})
    if not counters:
        return Measured(missing="no transport_reversal counters table")
    parts = []
    for sc, values in REVERSAL_LINES.items():
        n = counters.get(sc)
        f_v = throw_number_frequency(values["tilt"], values["throw"])
        if n is None or not len(n) or "liftoffs_per_s" not in n:
            parts.append(Part(line_label(values), Quantity(math.nan), "no counters"))
            continue
        n = n.sort_values("f")
        f = n["f"].to_numpy(float)
        per = n["liftoffs_per_s"].to_numpy(float) / f
        b = liftoff_boundary(f, per, threshold)
        _, q = judge_boundary(b, f_v)
        where = (f"no boundary in the scene's range (lift-offs per period {np.nanmin(per):.2f}–"
                 f"{np.nanmax(per):.2f})" if b is None else
                 f"boundary {b[0]:g}–{b[1]:g} Hz (lift-offs per period "
                 f"{per[f == b[0]][0]:.2f} → {per[f == b[1]][0]:.2f})")
        parts.append(Part(line_label(values), q if q is not None else Quantity(math.nan),
                          f"{where}, Γ_v = 1 at {f_v:.1f} Hz", found=b is not None))
    return Measured(parts)


_REG_T, _REG_T5, _REG_T6 = "2026-11-23 d98ddae", "2026-11-23 328f226", "2026-11-25 1b0f70e"
_REG_NEW = "2026-11-28 e570863"
_SCOPE_MAP = {"scenes": [MAP], "lines": {s: LINES[s] for s in HOPPING}, "families": ["rest"],
              "frequencies": "the scene's"}
_SCOPE_T1 = {**_SCOPE_MAP, "lines": {HOPPING[0]: LINES[HOPPING[0]]}}
_SCOPE_T3 = {**_SCOPE_MAP, "lines": {s: LINES[s] for s in CONVEYORS}, "along": ["f"]}
_SCOPE_T3B = {"scenes": [MAP, REVERSAL_MAP], "lines": {s: dict(v) for s, v in GEOMETRIES.items()},
              "families": ["rest"], "frequencies": "the scenes'", "along": ["f", "throw"]}
_SCOPE_REV = {"scenes": [REVERSAL_MAP], "lines": {s: dict(v) for s, v in REVERSAL_LINES.items()},
              "families": ["rest"], "frequencies": "the scene's"}
_SCOPE_SLIDING = {"scenes": [SLIDING_MAP], "lines": {s: LINES[s] for s, _, _ in SLIDING},
                  "families": ["rest"], "frequencies": "below the lift-off frequency"}
_T1_WHY = ("rule: no frequency with a significant v (Bonferroni, α = 0.05); with mirror pairs "
           "v = 0 by construction")

CLAIMS = [
    Claim("Mirror symmetry: a level floor vibrated vertically carries no current",
          no_current, HOPPING[0],
          Band(0.0, 0.0, "rule: no frequency with a significant v (Bonferroni, α = 0.05); "
               "with mirror pairs v = 0 by construction")),
    Claim("Integer frequency lockings produce extrema of the transport rate (paper's outlook, "
          "after Hongler et al.)", v_extrema, "",
          Band(1.0, math.inf, "rule: at least one significant extremum of v(f) per conveyor "
               "scene (bbb.analysis.extrema, family-wise α = 0.05), none counted where D about the "
               "drift is not diffusive")),
    Claim("Current reversals: the sign of the current changes with the driving (paper's "
          "outlook, after Grochowski et al.)", v_reversals_along_f, "",
          Band(1.0, math.inf, "rule: at least one sign change between frequencies whose v is "
               "significant (Bonferroni over the curve)")),
    Claim("Current reversals: the sign of the current changes with the driving (paper's "
          "outlook, after Grochowski et al.), along f or ψ on every conveyor floor", v_reversals, "",
          Band(1.0, math.inf, "rule: at least one significant sign change of v along f or "
               "along ψ at a fixed floor (between consecutive significant points, Bonferroni "
               "over each curve; steady drifts only), judged on every conveyor floor: the "
               "tilted floors (φ = 2°, 5°, ψ = 90°), the thrown ones (φ = 0°, ψ = 60°, 30°), "
               "the floors tilted against their throw (φ = 2°, 5° with ψ = 60°, 30° of scene "
               "transport; φ = 2° with ψ = 90°, 75°, 60°, 45°, 30° under stick and Coulomb "
               "μ = 0.3 of scene transport_reversal); along ψ on the tilted floors")),
    Claim("Not only the current, but also the diffusion coefficient may be irregular functions "
          "of control parameters", d_extrema, "",
          Band(2.0, math.inf, "rule: at least 2 significant extrema of D about the drift "
               "(a maximum and a minimum) per conveyor scene, none counted where it is not "
               "diffusive")),
    Claim("Below lift-off a vibratory conveyor transports by sliding only: the stick model "
          "carries no current there, Coulomb friction does (conveyor theory's sliding regime)", sliding, "",
          Band(-math.inf, math.inf, "rule: below the lift-off frequency (bbb.analysis.liftoff) the "
               "number of frequencies with a significant v (Bonferroni over the curve) is 0 "
               "under stick and ≥ 1 under Coulomb friction")),
    Claim("Conveyor theory's sliding/hopping boundary lies at the throw number Γ_v = Γ sin ψ / "
          "cos φ = 1 (Sloot & Kruyt 1996)", hopping_vs_throw_number, "",
          Band(-F_STEP, F_STEP, f"rule: per line of scene transport_reversal, the boundary "
               f"(from the last f whose airborne share is significantly below H = "
               f"{AIRBORNE_MIN:g} to the first significantly above, hopping_calibration.py) "
               f"minus the f of Γ_v = 1 lies within ± one frequency step ({F_STEP:g} Hz)",
               "Hz")),
]
_META = [("T1", _REG_T, _SCOPE_T1, no_current_cases, ""),
         ("T2", _REG_T, {**_SCOPE_MAP, "lines": {s: LINES[s] for s in CONVEYORS}},
          v_extrema_cases, ""),
         ("T3", _REG_T, _SCOPE_T3, reversal_f_cases, ""),
         ("T3b", _REG_T6, _SCOPE_T3B, reversal_cases, "T3"),
         ("T4", _REG_T, {**_SCOPE_MAP, "lines": {s: LINES[s] for s in CONVEYORS}},
          d_extrema_cases, ""),
         ("T5", _REG_T5, _SCOPE_SLIDING, sliding_cases, ""),
         ("T6", _REG_T6, _SCOPE_REV, hopping_cases, "")]
CLAIMS = [replace(c, id=i, registered=r, scope=sc, cases=cs, supersedes=sup)
          for c, (i, r, sc, cs, sup) in zip(CLAIMS, _META, strict=True)]
CLAIMS[1:1] = [
    Claim("Mirror symmetry: a level floor vibrated vertically carries no current", no_current,
          HOPPING[0], Band(0.0, 0.0, _T1_WHY), options={"construction": True}, id="T1b",
          registered=_REG_NEW, supersedes="T1", scope=_SCOPE_T1,
          cases=no_current_construction_cases)]
CLAIMS.append(
    Claim("Conveyor theory's sliding/hopping boundary lies at the throw number Γ_v = Γ sin ψ / "
          "cos φ = 1 (Sloot & Kruyt 1996), hopping counted by lift-offs", liftoff_vs_throw_number,
          "", Band(-F_STEP, F_STEP, f"rule: per line of scene transport_reversal, the boundary "
                   f"(from the frequency before the first whose lift-offs per floor period "
                   f"reach L = {LIFTOFF_MIN:g} to that one; {LIFTOFFS['source']}) minus the f "
                   f"of Γ_v = 1 within ± one frequency step ({F_STEP:g} Hz); a line without "
                   "counters: not measured", "Hz"),
          id="T6b", registered=_REG_NEW, supersedes="T6", scope=_SCOPE_REV, all_parts=True,
          cases=liftoff_cases))


def line_tables(tables) -> dict[str, pd.DataFrame]:
    """The maps' tables (keyed ``transport_<table>``, ``transport_sliding_<table>``,
    ``transport_reversal_<table>``) as one table per line, keyed ``<line>_<table>``
    (:data:`LINES`, :data:`~.reversal.REVERSAL_LINES`): the rows of that line without the axis
    columns, exactly what the scene with those values in [params] gives."""
    return {**split_lines(tables, MAP, {s: LINES[s] for s in HOPPING + COMBINED},
                          ("diffusion", "counters")),
            **split_lines(tables, SLIDING_MAP, {s: LINES[s] for s, _, _ in SLIDING},
                          ("diffusion", "contact", "counters")),
            **split_lines(tables, REVERSAL_MAP, REVERSAL_LINES,
                          ("diffusion", "contact", "counters"))}


def context(tables, stores=None) -> dict:
    """The context the claims are judged in: each line's diffusion table, and the contact and
    counters tables of the reversal map's lines."""
    lines = line_tables(tables)
    names = HOPPING + COMBINED + tuple(s for s, _, _ in SLIDING) + tuple(REVERSAL_LINES)
    return {"tables": {sc: lines.get(f"{sc}_diffusion") for sc in names},
            **{k: {sc: lines[f"{sc}_{k}"] for sc in REVERSAL_LINES if f"{sc}_{k}" in lines}
               for k in ("contact", "counters")}}


#: the section's own words ({liftoff}: f of lift-off on the sliding floor, Hz)
WORDS = ("Drift v with its bootstrap CI and D about the drift (bbb.analysis.transport) along f per "
         "(tilt φ, throw ψ), on one floor (φ = 0°, ψ = 30°) per contact model from low Γ "
         "to above lift-off ({liftoff:.1f} Hz, bbb.analysis.liftoff_onset), and over "
         "(throw ψ, f) on a floor tilted 2° against its throw per contact model, with the "
         "share of the run in flight; pipeline/studies/transport/claims.py states the rules.")
