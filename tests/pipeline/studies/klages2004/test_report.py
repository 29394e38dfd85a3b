"""REPORT.md: one row per claim, every measured number computed from the tables and stores."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pipeline.claims.claim import evaluate as judge_claims
from pipeline.claims.measures import onset
from pipeline.studies.klages2004 import STUDY
from pipeline.studies.klages2004.claims import CLAIMS, context
from pipeline.studies.report import write_report as write_whole_report

from ...figure_store import tiny_store


def evaluate(tables, claims=CLAIMS):
    """(rows, extrema) of the paper's claims judged on ``tables`` (no store, no parameters)."""
    ctx = context(tables)
    return judge_claims(claims, ctx), ctx["extrema"]


def write_report(out, *, stores, tables, run_log=None, study=STUDY):
    """REPORT.md of the paper's study alone, from ``tables``."""
    return write_whole_report(out, stores=stores, tables={study.name: tables}, run_log=run_log,
                              studies=[study])

F = np.round(np.arange(50.0, 99.2001, 0.4), 3)


def _diffusion(D, rel=0.05):
    D = np.asarray(D, float)
    s = 1.0 + rel * np.abs(D)
    return pd.DataFrame({"f": F, "D": D, "D_lo": D - 1.96 * s, "D_hi": D + 1.96 * s})


def _paper_like():
    """A D(f) with the paper's shape: onset at 50, max 54, min 58, max 60, min 62, rise, max 80."""
    bumps = [(54, 300, 1.0), (58, -250, 1.0), (60, 300, 0.8), (62, -200, 0.8), (80, 2500, 4.0)]
    D = 400 * (F > 50) + 25 * np.clip(F - 64, 0, None)
    for f0, a, w in bumps:
        D = D + a * np.exp(-((F - f0) ** 2) / (2 * w * w))
    return _diffusion(np.clip(D, 0, None))


def _locking(k_at):
    rows = []
    for f in F:
        k = k_at(f)
        v = k * 9800 / (2 * f)
        rows.append({"f": f, "family": "rest", "initial": "rest", "n_states": 1000,
                     "frac_creep": 0.2, "v_creep": 1.1 * 0.1 * 2 * math.pi * f, "v_max": v,
                     "k_max": k, "v_peak": 0.7 * v, "k_peak": 0.7 * k, "t_max": k / f,
                     "n_flights": 900, "loops": k})
    return pd.DataFrame(rows)


def _row(rows, text):
    return next(r for r in rows if text in r.claim)


def test_every_claim_gets_one_row():
    rows, _ = evaluate({"figure2": _paper_like()})
    assert len(rows) == len(CLAIMS) == 19


def test_the_extrema_rows_follow_the_data_not_the_paper():
    rows, extrema = evaluate({"figure2": _paper_like()})
    kinds = [(e.kind, round(e.f)) for e in extrema["rest (Fig. 2 scene)"]]
    assert kinds == [("max", 54), ("min", 58), ("max", 60), ("min", 62), ("max", 80)]
    for text in ("maximum of D(f) around f = 54", "minimum around f = 58", "maximum at f = 60",
                 "minimum around f = 62", "maximum around f = 80"):
        assert _row(rows, text).verdict == "agrees", text


def test_a_missing_extremum_is_reported_as_a_disagreement():
    flat = _diffusion(np.where(F > 57, 100.0 + 30 * (F - 57), 0.0))  # no bumps at all
    rows, _ = evaluate({"figure2": flat})
    row = _row(rows, "maximum at f = 60")
    assert row.verdict == "disagrees" and "D(60)" in row.note


def test_onset_is_the_first_frequency_with_d_significantly_above_zero():
    t = _diffusion(np.where(F >= 57.6, 200.0, 0.0))
    assert onset(t, ("D", "D_lo", "D_hi")) == pytest.approx(57.6)


def test_the_k_rows_compare_the_locking_table_with_the_papers_values():
    good = _locking(lambda f: 1.47 if f < 66 else 2.5 if f < 76 else 3.43 if f < 86 else 4.5)
    rows, _ = evaluate({"locking": good})
    assert all(_row(rows, f"k ≈ {k:g}").verdict == "agrees" for k in (1.47, 2.5, 3.43, 4.5))
    bad = _locking(lambda f: 1.0)
    rows, _ = evaluate({"locking": bad})
    assert _row(rows, "k ≈ 4.5").verdict == "disagrees"


def test_the_loop_row_finds_where_k_max_steps_up():
    lock = _locking(lambda f: 1.5 + np.floor((f - 56) / 10))  # steps at 66, 76, 86, 96
    rows, _ = evaluate({"locking": lock})
    row = _row(rows, "two-loop spiral")
    assert row.verdict == "agrees" and "spacing Δf = 10.0 Hz" in row.measured


def test_claims_without_their_table_are_not_measured():
    rows, _ = evaluate({})
    assert {r.verdict for r in rows} == {"not measured"}


def test_the_report_states_parameters_amplitude_accuracy_and_run_time(tmp_path_factory, tmp_path):
    store, t = tiny_store(tmp_path_factory)
    stores = {"figure2": store, "locking": store, "figure3": store}
    path = write_report(tmp_path, stores=stores,
                        tables={"figure2": t["diffusion"], "ergodicity": t["diffusion"],
                                "locking": t["locking"]},
                        run_log={"fast": True, "wall_s": 12.0, "scenes": {}})
    text = path.read_text()
    assert text.count("\n| ") >= len(CLAIMS) + 1  # header + one row per claim
    assert "| A | 0.1 mm |" in text and "prints A = 0.01" in text
    assert "| figure2 | " in text and "| draft |" in text
    assert "task time" in text and "runs and reductions behind it: 12 s" in text


# --- the generic verdict rule (pipeline.claims.claim) on synthetic numbers --------------------------
from pipeline.claims.claim import Band, Claim, Quantity, combine, judge  # noqa: E402
from pipeline.claims.measures import extremum  # noqa: E402

BAND = Band.around(60.0, 2.0, "test")


@pytest.mark.parametrize(("q", "verdict"), [
    (Quantity(60.0, 59.0, 61.0), "agrees"),                 # whole CI inside
    (Quantity(61.5, 61.0, 62.5), "agrees within the CI"),   # value inside, CI over the edge
    (Quantity(62.3, 61.8, 63.0), "inconclusive"),           # value outside, CI reaches in
    (Quantity(63.0, 62.5, 63.5), "disagrees"),              # whole CI outside
    (Quantity(57.0, 56.0, 57.9), "disagrees"),
    (Quantity(61.9), "agrees"),                             # no CI: the value alone
    (Quantity(math.nan), "not measured"),
])
def test_each_verdict_class_is_reached_by_its_rule(q, verdict):
    assert judge(q, BAND) == verdict


def test_a_value_just_inside_the_band_but_within_its_ci_of_the_edge_is_not_a_plain_agree():
    # 0.1 inside the edge, CI +-0.3: the margin is smaller than the CI
    assert judge(Quantity(61.9, 61.6, 62.2), BAND) == "agrees within the CI"
    assert judge(Quantity(61.9, 61.6, 61.95), BAND) == "agrees"  # perturbed CI: now it is


def test_parts_combine_into_one_verdict():
    assert combine(["agrees", "agrees"]) == "agrees"
    assert combine(["agrees", "agrees within the CI"]) == "agrees within the CI"
    assert combine(["agrees", "inconclusive"]) == "inconclusive"
    assert combine(["agrees", "disagrees"]) == "partly"
    assert combine(["disagrees", "disagrees"]) == "disagrees"


def _k_table(k, half):
    t = _locking(lambda f: k)
    t["k_max_lo"], t["k_max_hi"] = k - half, k + half
    return t


def test_a_k_claim_inside_its_ci_of_the_band_edge_says_so():
    # paper: k = 2.5 +- 0.15 at 72 Hz; measured 2.63 [2.60, 2.70] straddles 2.65
    rows, _ = evaluate({"locking": _k_table(2.63, 0.03).assign(k_max_hi=2.70)})
    row = _row(rows, "k ≈ 2.5")
    assert row.verdict == "agrees within the CI" and "flips inside the CI" in row.note
    assert "2.5 ± 0.15" in row.judged_by and "[2.6, 2.7]" in row.measured
    rows, _ = evaluate({"locking": _k_table(2.60, 0.03)})  # whole CI inside
    assert _row(rows, "k ≈ 2.5").verdict == "agrees"
    rows, _ = evaluate({"locking": _k_table(2.68, 0.04)})  # CI reaches back into the band
    assert _row(rows, "k ≈ 2.5").verdict == "inconclusive"
    rows, _ = evaluate({"locking": _k_table(2.75, 0.03)})
    assert _row(rows, "k ≈ 2.5").verdict == "disagrees"


def test_an_extremum_location_carries_a_ci_of_half_the_grid_spacing():
    rows, _ = evaluate({"figure2": _paper_like()})
    row = _row(rows, "maximum at f = 60")
    assert "± 0.2 Hz" in row.measured and "60 ± 2 Hz" in row.judged_by


def test_adding_a_claim_is_one_record_and_it_appears_in_the_report(tmp_path):
    from pipeline.studies.klages2004.claims import CLAIMS as PAPER

    extra = Claim("Local maximum near f = 80 (a claim added by a test)", extremum, "figure2",
                  Band.around(80.0, 1.0, "added for the test", "Hz"), f0=80.0, window=1.0,
                  options={"kind": "max"})
    rows, _ = evaluate({"figure2": _paper_like()}, claims=[*PAPER, extra])
    assert rows[-1].claim == extra.text and rows[-1].verdict in ("agrees", "agrees within the CI")
    from dataclasses import replace

    study = replace(STUDY, claims=(*PAPER, extra))  # what appending to CLAIMS makes
    text = write_report(tmp_path, stores={}, tables={"figure2": _paper_like()},
                        study=study).read_text()
    line = next(ln for ln in text.splitlines() if extra.text in ln)
    assert line.startswith(f"| {len(PAPER) + 1} |") and "80 ± 1 Hz: added for the test" in line


def test_the_ergodicity_verdicts_name_the_rule_its_error_rates_and_the_excluded_spread(
        tmp_path_factory, tmp_path):
    store, t = tiny_store(tmp_path_factory)
    ergo = t["diffusion"].copy()
    ergo["CV_D_upper"] = 0.37  # a distinctive spread bound: it must reach the report as is
    path = write_report(tmp_path, stores={"figure2": store}, tables={"ergodicity": ergo})
    text = path.read_text()
    section = text.split("## Ergodicity verdicts, frequency by frequency", 1)[1]
    r = ergo.iloc[0]
    assert f"Rule `{r['rule']}`" in section
    fp, fn = 100 * r["rule_fp"], 100 * r["rule_fn"]
    assert f"false positive {fp:.0f} %, false negative {fn:.0f} %" in section
    rows = [ln for ln in section.splitlines() if ln.startswith(f"| {r['f']:g} |")]
    assert len(rows) == 1 and "| 37 % |" in rows[0]


def test_the_ergodicity_table_shows_cv2_signed_with_its_ci_and_no_clipped_zero(
        tmp_path_factory, tmp_path):
    # a spread estimate below 0 (noise about CV = 0) is shown as it is, not as "0 %", and a
    # bound that cannot be stated (its CV² bound ≤ 0) says so
    store, t = tiny_store(tmp_path_factory)
    ergo = t["diffusion"].copy()
    ergo["CV2_D"], ergo["CV2_D_lo"], ergo["CV2_D_hi"] = -0.0126, -0.0581, 0.0342
    ergo["CV_D"], ergo["CV_D_upper"] = float("nan"), float("nan")
    text = write_report(tmp_path, stores={"figure2": store}, tables={"ergodicity": ergo})
    section = text.read_text().split("## Ergodicity verdicts, frequency by frequency", 1)[1]
    row = next(ln for ln in section.splitlines() if ln.startswith(f"| {ergo['f'].iloc[0]:g} |"))
    assert "| -0.0126 [-0.0581, 0.0342] |" in row and "| none (CV² bound ≤ 0) |" in row
    assert "0 %" not in row


def test_the_ergodicity_rule_line_quotes_the_cv2_ci_coverage_from_its_calibration(
        tmp_path_factory, tmp_path):
    import json
    from pathlib import Path

    import bbb.analysis.stats

    cal = json.loads((Path(bbb.analysis.stats.__file__).parent / "ergodicity_calibration.json")
                     .read_text())["cv2_ci_coverage"]
    values = [c for pops in cal.values() for c in pops.values()]
    store, t = tiny_store(tmp_path_factory)
    text = write_report(tmp_path, stores={"figure2": store},
                        tables={"ergodicity": t["diffusion"]}).read_text()
    want = f"covered the true CV² in {100 * min(values):.0f} %–{100 * max(values):.0f} %"
    assert want in text
