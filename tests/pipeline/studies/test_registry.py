"""The studies' claim registry: every claim registered once, turned each way by its synthetic
cases, frozen once judged in the committed report, and shown beside the claim it supersedes."""

from __future__ import annotations

from pathlib import Path

import pytest

from pipeline.claims.registry import case_problems, frozen_mismatches, id_problems
from pipeline.studies.registry import all_claims, frozen, judged_ids

REPORT = Path(__file__).resolve().parents[3] / "figures" / "REPORT.md"
CLAIMS = [c for cs in all_claims().values() for c in cs]
#: claims without synthetic cases yet: none (the list may only shrink)
CASES_PENDING: set[str] = set()


def test_every_claim_is_registered_once_with_an_id_and_a_commit():
    assert id_problems(CLAIMS) == []


def test_the_claims_without_synthetic_cases_are_exactly_the_pending_ones():
    assert {c.id for c in CLAIMS if c.cases is None} == CASES_PENDING


@pytest.mark.parametrize("claim", [c for c in CLAIMS if c.id not in CASES_PENDING],
                         ids=lambda c: c.id)
def test_every_claim_turns_each_way_on_its_synthetic_cases_and_a_perturbation_flips_it(claim):
    assert case_problems(claim) == []


@pytest.mark.parametrize("study", list(all_claims()))
def test_every_frozen_claim_keeps_the_rule_and_scope_it_was_judged_under(study):
    assert frozen_mismatches(all_claims()[study], frozen(study)) == []


def test_every_claim_judged_in_the_committed_report_is_frozen():
    frozen_ids = {i for s in all_claims() for i in frozen(s)}
    assert judged_ids(REPORT.read_text(encoding="utf-8")) - frozen_ids == set()


def test_a_superseded_claim_is_judged_in_the_report_beside_the_one_that_replaces_it():
    judged = judged_ids(REPORT.read_text(encoding="utf-8"))
    pairs = {(c.supersedes, c.id) for c in CLAIMS if c.supersedes}
    assert ("T3", "T3b") in pairs
    assert [p for p in pairs if not set(p) <= judged] == []


def test_every_scene_of_a_study_folder_is_run_by_that_study_and_every_run_scene_is_shipped():
    from pipeline.studies.registry import studies
    from pipeline.workflow.scenes import scene_names, scene_study

    declared = {n: s.name for s in studies() for n in s.scenes}
    in_folders = {n: scene_study(n) for n in scene_names() if scene_study(n) != "workflows"}
    assert {n: declared.get(n) for n in in_folders} == in_folders
    assert set(declared) <= set(scene_names())


def test_a_study_is_its_packages_record_under_its_own_name():
    import pytest as _pytest

    from pipeline.studies.registry import STUDIES, study

    assert [study(n).name for n in STUDIES] == list(STUDIES)
    with _pytest.raises(KeyError, match="registered: klages2004"):
        study("impact_phase")
