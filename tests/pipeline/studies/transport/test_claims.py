"""Calibration of the transport claim rules (pipeline/studies/transport/claims.py) on synthetic
v(f) curves with known answers, fixed before any transport store was reduced."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.claims.claim import evaluate
from pipeline.claims.signs import significant_signs
from pipeline.studies.transport.claims import (
    CLAIMS,
    COMBINED,
    CONVEYORS,
    HOPPING,
    LINES,
    SLIDING,
    SLIDING_GEOMETRY,
    sliding_liftoff,
)
from pipeline.workflow.scenes import load_scene

#: the rules these tests turn, in the order they were written for: T1, T2, T3b (the reversal
#: rule along f and ψ), T4, T5, T6
RULES = [next(c for c in CLAIMS if c.id == i) for i in ("T1", "T2", "T3b", "T4", "T5", "T6")]
F = np.arange(50.0, 100.1, 2.0)  # the scenes' 26 frequencies


def _table(v, lo, hi, d=None) -> pd.DataFrame:
    d = np.full(F.size, 10.0) if d is None else d
    return pd.DataFrame({"f": F, "v": v, "v_lo": lo, "v_hi": hi, "D_drift": d,
                         "D_drift_lo": d - 0.2, "D_drift_hi": d + 0.2})


def test_the_claim_rows_turn_on_synthetic_tables_with_known_answers():
    bumpy = -5.0 - 4.0 * np.sin(2 * np.pi * (F - 50.0) / 25.0)  # 2 extrema of v, no reversal
    flat = np.zeros(F.size)
    tables = {HOPPING[0]: _table(flat, flat - 1, flat + 1),
              **{s: _table(bumpy, bumpy - 0.3, bumpy + 0.3, d=20 + 5 * np.sin(F / 4.0))
                 for s in CONVEYORS}}
    rows = evaluate(RULES, {"tables": tables})
    assert [r.verdict for r in rows] == ["agrees", "agrees", "disagrees", "agrees",
                                         "not measured", "not measured"], rows
    tables[HOPPING[0]] = _table(bumpy, bumpy - 0.3, bumpy + 0.3)  # a current where none may be
    for s in CONVEYORS:
        tables[s] = _table(-bumpy, -bumpy - 0.3, -bumpy + 0.3)  # reversed sign: still none
    assert [r.verdict for r in evaluate(RULES, {"tables": tables})][:3] == [
        "disagrees", "agrees", "disagrees"]
    wave = 6.0 * np.sin(2 * np.pi * (F - 50.0) / 40.0)  # changes sign at 70 Hz
    tables[CONVEYORS[0]] = _table(wave, wave - 0.3, wave + 0.3)
    assert evaluate(RULES, {"tables": tables})[2].verdict == "agrees"


def test_unsteady_frequencies_are_left_out_of_every_rule():
    up = np.linspace(-20.0, 20.0, F.size)  # a significant reversal, but only where unsteady
    t = _table(up, up - 0.3, up + 0.3)
    t["steady"] = F < 70.0
    tables = {s: t for s in HOPPING}
    row = evaluate(RULES, {"tables": tables})[2]
    assert row.verdict == "disagrees" and "left out" in row.measured
    t["steady"] = True
    assert evaluate(RULES, {"tables": tables})[2].verdict == "agrees"


F_SLIDE = np.arange(20.0, 80.1, 2.0)  # the sliding scenes' 31 frequencies


def _sliding_tables(v_stick, v_coulomb, se=0.3):
    def tab(v):
        return pd.DataFrame({"f": F_SLIDE, "v": v, "v_lo": v - 1.96 * se, "v_hi": v + 1.96 * se})
    return {SLIDING[0][0]: tab(v_stick), SLIDING[1][0]: tab(v_coulomb)}


def _sliding_verdict(tables) -> str:
    return evaluate(RULES, {"tables": tables})[4].verdict


def test_the_sliding_claim_agrees_when_only_coulomb_moves_below_lift_off():
    f_lift = sliding_liftoff()
    rest = np.where(F_SLIDE < f_lift, 0.0, 4.0)  # stick: at rest until it hops
    slides = np.where((F_SLIDE > 44) & (F_SLIDE < 60), 5.0, 0.0)  # Coulomb: a sliding window
    assert _sliding_verdict(_sliding_tables(rest, slides)) == "agrees"


def test_the_sliding_claim_fails_when_stick_moves_below_lift_off_or_coulomb_does_not():
    f_lift = sliding_liftoff()
    creep = np.where(F_SLIDE == 50.0, 5.0, 0.0)  # one significant v below lift-off
    assert _sliding_verdict(_sliding_tables(creep, creep)) != "agrees"
    hop_only = np.where(F_SLIDE > f_lift, 4.0, 0.0)
    assert _sliding_verdict(_sliding_tables(hop_only, hop_only)) != "agrees"


def test_noise_alone_below_lift_off_is_not_a_sliding_current():
    # the stick part on current-free curves: Bonferroni keeps false 'moves' to ≤ 5 % of curves
    rng = np.random.default_rng(4)
    moved = 0
    for _ in range(500):
        v = 0.3 * rng.standard_normal(F_SLIDE.size)
        moved += significant_signs(v, v - 1.96 * 0.3, v + 1.96 * 0.3).any()
    assert moved / 500 <= 0.07


def test_the_sliding_lines_are_the_floor_and_contact_models_the_claim_assumes():
    study = load_scene("transport_sliding")
    assert {tuple(p.grid) for p in study.points} == {
        (("contact", c), ("mu", mu)) for _, c, mu in SLIDING}
    for line, contact, mu in SLIDING:
        p = study.line(LINES[line]).params(50.0)
        assert (p.tilt, p.throw) == (SLIDING_GEOMETRY["tilt"], SLIDING_GEOMETRY["throw"])
        assert (p.contact, p.mu) == (contact, mu)


def test_the_transport_map_holds_the_judged_floors_and_the_combined_ones():
    study = load_scene("transport")
    lines = {tuple(p.grid) for p in study.points}
    assert lines == {(("tilt", LINES[s]["tilt"]), ("throw", LINES[s]["throw"]))
                     for s in HOPPING + COMBINED}
    assert len(lines) == 9 and not set(HOPPING) & set(COMBINED)
    for s in HOPPING + COMBINED:
        p = study.line(LINES[s]).params(50.0)
        assert (p.tilt, p.throw) == (LINES[s]["tilt"], LINES[s]["throw"])
        assert list(study.line(LINES[s]).frequencies) == list(F)


def test_the_no_current_claim_holds_by_construction_with_mirror_images_and_says_so():
    zero = np.zeros(F.size)
    t = _table(zero, zero, zero)
    t["v_by"] = "mirror symmetry"
    row = evaluate(RULES, {"tables": {HOPPING[0]: t}})[0]
    assert row.verdict == "agrees" and "by construction" in row.measured
    assert "not a measurement" in row.measured
    t["v_by"] = "independent"  # the same zeros estimated from independent particles
    row = evaluate(RULES, {"tables": {HOPPING[0]: t}})[0]
    assert row.verdict == "agrees" and "by construction" not in row.measured


def test_extrema_where_D_about_the_drift_is_not_diffusive_are_not_counted():
    d = 20 + 5 * np.sin(F / 4.0)  # a maximum and a minimum per scene: T4 agrees
    v = -5.0 - 4.0 * np.sin(2 * np.pi * (F - 50.0) / 25.0)
    tables = {s: _table(v, v - 0.3, v + 0.3, d=d) for s in CONVEYORS}
    rows = evaluate(RULES, {"tables": tables})
    assert rows[1].verdict == "agrees" and rows[3].verdict == "agrees"
    for s in CONVEYORS:  # ballistic spread everywhere but the ends
        tables[s]["diffusive"] = (F < 52) | (F > 98)
    rows = evaluate(RULES, {"tables": tables})
    assert rows[1].verdict == "disagrees" and rows[3].verdict == "disagrees"
    assert "not counted" in rows[3].measured and "not diffusive" in rows[3].measured


def test_the_docs_quote_the_committed_calibration_and_benchmark():
    from pathlib import Path

    from bbb.analysis.transport import CURVATURE_TOL, STEADY_SE
    from pipeline.studies.transport.claims import MIRROR

    doc = (Path(__file__).resolve().parents[4] / "docs" / "statistics.md").read_text("utf-8")
    fa = MIRROR["t1_false_alarm"]
    assert f"k = {STEADY_SE:g} is the smallest" in doc
    assert f"the CI lies above {1 + CURVATURE_TOL:g}" in doc
    assert f"fails by chance on {100 * fa['rate']:.1f} % [{100 * fa['lo']:.1f}, " \
           f"{100 * fa['hi']:.1f}] %" in doc
    t5 = MIRROR["variance"]["transport_t5"]["v"]
    assert f"| tilt 5° | {t5['ratio']:.3g} [{t5['lo']:.2f}, {t5['hi']:.2f}] |" in doc


F_MAP = np.arange(30.0, 100.1, 2.0)  # the transport_reversal scene's 36 frequencies


def _map_line(v, se=0.5) -> pd.DataFrame:
    v = np.asarray(v, float)
    return pd.DataFrame({"f": F_MAP, "v": v, "v_lo": v - 1.96 * se, "v_hi": v + 1.96 * se})


def test_current_reversals_count_a_sign_change_along_the_throw_at_a_fixed_floor():
    from pipeline.studies.transport.reversal import REVERSAL_LINES

    # each line keeps one sign along f, but the throw flips it: downhill at ψ = 90°, uphill
    # below -- a change along ψ only
    tables = {n: _map_line(np.full(F_MAP.size, -4.0 if v["throw"] == 90.0 else 4.0))
              for n, v in REVERSAL_LINES.items()}
    row = evaluate(RULES, {"tables": tables})[2]
    assert row.verdict == "agrees" and "along f: none" in row.measured
    assert "ψ 90°→75° (− → +) at 30–100 Hz" in row.measured
    for n in tables:  # one sign everywhere: nothing to count
        tables[n] = _map_line(np.full(F_MAP.size, -4.0))
    assert evaluate(RULES, {"tables": tables})[2].verdict == "disagrees"


def test_current_reversals_along_f_on_a_floor_tilted_against_its_throw_are_intervals():
    from pipeline.studies.transport.reversal import REVERSAL_LINES, reversal_line

    uphill_then_down = np.where(F_MAP <= 60.0, 6.0, -300.0)  # as φ = 2°, ψ = 60° might
    uphill_then_down[(F_MAP > 60.0) & (F_MAP < 66.0)] = 0.0  # not significant in between
    tables = {reversal_line(60.0, "stick"): _map_line(uphill_then_down)}
    row = evaluate(RULES, {"tables": tables})[2]
    assert row.verdict == "agrees"
    assert "φ = 2°, ψ = 60°, stick: 60–66 Hz (+ → −)" in row.measured
    assert set(REVERSAL_LINES) >= set(tables)


def _contact_tables(boundary: dict[str, float]) -> dict[str, pd.DataFrame]:
    """Contact tables whose airborne share jumps from 0 to 0.4 at ``boundary[line]`` Hz."""
    out = {}
    for n, f0 in boundary.items():
        air = np.where(F_MAP >= f0, 0.4, 0.0)
        held = 1.0 - air
        out[n] = pd.DataFrame({"f": F_MAP, "held_frac": held, "slide_frac": 0.0,
                               "held_frac_lo": held - 0.01, "held_frac_hi": held + 0.01,
                               "slide_frac_lo": 0.0, "slide_frac_hi": 0.0})
    return out


def test_the_hopping_boundary_claim_agrees_at_the_throw_number_and_not_beyond_a_step():
    from pipeline.studies.transport.reversal import REVERSAL_LINES, throw_number_frequency

    f_v = {n: throw_number_frequency(v["tilt"], v["throw"]) for n, v in REVERSAL_LINES.items()}
    # the first frequency of the scene above Γ_v = 1 hops: the boundary brackets f_v
    at = {n: F_MAP[F_MAP > f][0] for n, f in f_v.items()}
    row = evaluate(RULES, {"tables": {}, "contact": _contact_tables(at)})[5]
    assert row.verdict in ("agrees", "agrees within the CI"), row
    late = {n: f + 6.0 for n, f in at.items()}  # hopping 6 Hz late everywhere
    assert evaluate(RULES, {"tables": {}, "contact": _contact_tables(late)})[5].verdict == \
        "disagrees"
    half = {n: (late if i % 2 else at)[n] for i, n in enumerate(at)}
    assert evaluate(RULES, {"tables": {}, "contact": _contact_tables(half)})[5].verdict == \
        "partly"
    assert evaluate(RULES, {"tables": {}})[5].verdict == "not measured"
