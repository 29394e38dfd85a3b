"""The table of run times in docs/reproducing.md: generated from figures/run_log.json, and
matching it."""

from __future__ import annotations

import json
from pathlib import Path

from pipeline.studies.run_times import BEGIN, END, PAGE, table, update_readme

ROOT = Path(__file__).resolve().parents[3]


def test_the_pages_run_times_are_the_committed_run_log():
    text = (ROOT / PAGE).read_text(encoding="utf-8")
    assert text.count(BEGIN) == 1 and text.count(END) == 1
    shown = text.split(BEGIN, 1)[1].split(END, 1)[0].strip().splitlines()
    log = json.loads((ROOT / "figures" / "run_log.json").read_text())
    assert shown == table(log)


def test_a_further_studys_scenes_are_summed_into_its_row_and_earlier_runs_marked():
    """Two transport scenes (60 s + 30.4 s, 10 + 5 of 10 + 8 chunks, one computed by an earlier
    invocation), Fig. 2 alone (100 s and a 7 s reduce), a 2 s cluster, 200 s in all."""
    log = {"scenes": {"figure2": {"wall_s": 100.0, "computed": 40, "chunks": 124, "workers": 2,
                                  "reduce_s": 7.0},
                      "transport": {"wall_s": 60.0, "computed": 10, "chunks": 10, "workers": 2},
                      "transport_sliding": {"wall_s": 30.4, "computed": 5, "chunks": 8,
                                            "workers": 2, "earlier_invocation": True}},
           "cluster_s": 2.0, "wall_s": 200.0, "this_invocation_s": 150.0}
    rows = table(log)
    assert "| `figure2` | 1.7 min (100 s) | 40 of 124 | 2 | 7 s |" in rows
    assert ("| transport (2 scenes) | 1.5 min (90 s) (1 of 2 scenes computed by an earlier "
            "invocation) | 15 of 18 | 2 | – |") in rows
    assert "| **all of the above** | **3.3 min (200 s)** | | | |" in rows
    assert not any(r.startswith("| `ergodicity`") or r.startswith("| contact") for r in rows)


def test_a_store_filled_by_a_separate_run_says_so_instead_of_a_wall_time():
    log = {"scenes": {"dissipation": {"computed": 0, "chunks": 40, "workers": 2,
                                      "separate_run": True},
                      "dissipation_r25": {"wall_s": 12.0, "computed": 3, "chunks": 3, "workers": 2}}}
    rows = table(log)
    assert ("| dissipation (2 scenes) | 12 s (1 of 2 scenes' chunks computed by a separate "
            "`bbb run`: see the maps' costs below) | 3 of 43 | 2 | – |") in rows


def test_update_readme_rewrites_only_between_the_markers(tmp_path):
    log = {"scenes": {"figure3": {"wall_s": 3.0, "computed": 12, "chunks": 12, "workers": 2}}}
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n\n{BEGIN}\n| old |\n{END}\n\nafter\n", encoding="utf-8")
    assert update_readme(readme, log)
    assert readme.read_text(encoding="utf-8") == (
        "intro\n\n" + "\n".join([BEGIN, *table(log), END]) + "\n\nafter\n")
    plain = tmp_path / "PLAIN.md"
    plain.write_text("no markers\n", encoding="utf-8")
    assert not update_readme(plain, log) and plain.read_text(encoding="utf-8") == "no markers\n"
