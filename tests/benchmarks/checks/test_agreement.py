"""benchmarks/checks/agreement.py: two D(f) tables agree within their combined CIs, or, where a
target-driven scene stopped as "resolved to ±d_resolved", at that scene's resolution d_resolved."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from benchmarks.checks import agreement

ROOT = Path(__file__).resolve().parents[3]

NAN = float("nan")
RES = agreement.RESOLVED
OLD = pd.DataFrame({"f": [50.0, 54.0, 58.0, 60.0, 62.0],
                    "D": [1e-3, 2e-3, 100.0, 300.0, 200.0],
                    "D_lo": [9e-4, 1.8e-3, 95.0, 291.0, 194.0],
                    "D_hi": [1.1e-3, 2.2e-3, 105.0, 309.0, 206.0]})
NEW = pd.DataFrame({"f": [50.0, 54.0, 58.0, 60.0, 62.0],
                    "D": [3e-6, 4e-6, 120.0, 301.0, NAN],
                    "D_lo": [1e-6, 2e-6, 116.0, 292.0, NAN],
                    "D_hi": [5e-6, 6e-6, 124.0, 310.0, NAN],
                    "stop": [RES, f"rest: {RES}; launched: cap", RES, "target met", RES]})


def _files(tmp_path):
    old, new = tmp_path / "old.csv", tmp_path / "new.csv"
    OLD.to_csv(old, index=False)
    NEW.to_csv(new, index=False)
    return str(old), str(new)


def test_a_point_resolved_to_d_resolved_agrees_at_the_scenes_resolution_and_nowhere_else(tmp_path):
    old, new = _files(tmp_path)
    rows = {r.f: r for r in agreement.compare(agreement.read_table(old),
                                              agreement.read_table(new), d_resolved=9.0)}
    # 50 Hz: CIs far apart (z << -1), both |D| <= 9 mm²/s where the scene stopped resolved
    assert rows[50.0].z < -1 and rows[50.0].by == "res" and rows[50.0].agrees
    # 54 Hz: one family stopped at the cap: the CI rule judges, and they differ
    assert rows[54.0].by == "ci" and not rows[54.0].agrees
    # 58 Hz: stopped "resolved" with D = 120 > 9: resolution does not cover it, CIs differ
    assert rows[58.0].by == "res" and not rows[58.0].agrees
    assert rows[60.0].by == "ci" and rows[60.0].agrees
    assert rows[62.0].by == "n/a" and not rows[62.0].agrees  # no D (estimator failed)
    # without d_resolved every frequency is judged by the CIs
    plain = agreement.compare(agreement.read_table(old), agreement.read_table(new))
    assert [r.agrees for r in plain] == [False, False, False, True, False]


def test_d_resolved_is_read_from_the_scenes_workflow(tmp_path, capsys):
    old, new = _files(tmp_path)
    rc = agreement.main([old, new, "--workflow", str(ROOT / "workflows" / "figure2.toml")])
    summary, misses = capsys.readouterr().out.strip().splitlines()[-2:]
    assert rc == 1 and summary.startswith("2/5 frequencies agree (40.0 %")
    assert "d_resolved = 9 mm²/s" in summary and "by the CIs alone 1/5; n/a 1" in summary
    # judged by the CIs: 54 (miss), 58 (res, D = 120 > 9: miss), 60 (agrees)
    assert misses.startswith("CI misses 2 of 3 judged by the CIs")


def test_a_frequency_where_neither_table_measures_d_is_not_compared(tmp_path, capsys):
    old, new = _files(tmp_path)
    OLD.assign(D=[1e-3, 2e-3, 100.0, 300.0, -2e-7], D_lo=[9e-4, 1.8e-3, 95.0, 291.0, -3e-7],
               D_hi=[1.1e-3, 2.2e-3, 105.0, 309.0, -1e-7]).to_csv(old, index=False)
    rows = agreement.compare(agreement.read_table(old), agreement.read_table(new), 9.0)
    assert rows[-1].by == "none"  # old D significantly < 0 is an estimator failure, like NaN
    agreement.main([old, new, "--d-resolved", "9"])
    summary = capsys.readouterr().out.strip().splitlines()[-2]
    assert summary.startswith("2/4 frequencies agree (50.0 %")
    assert summary.endswith("n/a 0; not compared (no D in either table) 1")


def test_the_binomial_tail_of_ci_misses():
    assert abs(agreement.binom_tail(0, 7, 0.05) - 1.0) < 1e-15
    assert abs(agreement.binom_tail(1, 2, 0.5) - 0.75) < 1e-15
    assert abs(agreement.binom_tail(2, 2, 0.05) - 0.0025) < 1e-15


def _latest_figure2_agreement():
    """(agree, total, percent, by CIs alone) of the newest committed Fig. 2 agreement run."""
    import re
    runs = sorted((ROOT / "benchmarks" / "results").glob("agreement-figure2-*-resolution.txt"))
    assert runs, "no committed agreement-figure2-*-resolution.txt"
    text = runs[-1].read_text()
    m = re.search(r"^(\d+)/(\d+) frequencies agree \(([\d.]+) %.*by the CIs alone (\d+)/\2",
                  text, re.M)
    assert m, f"{runs[-1].name}: no summary line"
    return m.groups()


def test_the_reproducing_and_accuracy_docs_quote_the_latest_figure2_agreement():
    agree, total, percent, by_ci = _latest_figure2_agreement()
    readme = " ".join((ROOT / "docs" / "reproducing.md").read_text().split())
    accuracy = " ".join((ROOT / "docs" / "accuracy.md").read_text().split())
    assert f"at {agree} of {total} frequencies ({percent} %)" in readme
    assert f"({by_ci} of {total})" in readme
    assert f"{agree} of {total} frequencies agree ({percent} %; within the CIs alone {by_ci})" \
        in accuracy


def test_the_benchmarks_resolved_label_is_the_stores():
    """agreement.py stands alone (no pipeline import): its label must be the legend's."""
    from pipeline.store.layout import STOP_LEGEND, ZERO

    assert agreement.RESOLVED == STOP_LEGEND[ZERO]
