"""The closest allowed name to a misspelled one (pipeline/workflow/suggest.py)."""

from __future__ import annotations

from pipeline.workflow.suggest import closest, did_you_mean


def test_the_closest_name_is_suggested_and_a_far_one_is_not():
    assert closest("acuracy", ["study", "accuracy", "analysis"]) == ["accuracy"]
    assert did_you_mean("Accuracy", ["accuracy"]) == " (did you mean 'accuracy'?)"
    assert did_you_mean("xyz", ["accuracy", "study"]) == ""
