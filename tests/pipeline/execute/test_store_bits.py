"""Stores keep their bits across the observables' move to plug-ins: small stores of scenes
using every observable are what the engine wrote before (digests of every array's values and
metadata, pinned by tests/pipeline/execute/store_bits.py), and a finished store resumes with
nothing to do and re-reduces the same tables."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pipeline.execute.run import run_study
from pipeline.store.study_store import StudyStore
from pipeline.tables.catalog import table_names, tables
from pipeline.workflow.load import parse_workflow

from ..helpers import QUIET
from .store_bits import DATA, SCENES, build_store, store_digests

PINNED = json.loads(DATA.read_text(encoding="utf-8"))


@pytest.mark.parametrize("scene", sorted(SCENES))
def test_every_array_of_a_store_is_the_one_pinned_before_observables_were_plug_ins(scene, tmp_path):
    build_store(scene, tmp_path / "s.zarr")
    now, then = store_digests(tmp_path / "s.zarr"), PINNED[scene]
    assert now["workflow_fingerprint"] == then["workflow_fingerprint"]
    assert sorted(now["arrays"]) == sorted(then["arrays"])
    changed = [a for a in then["arrays"] if now["arrays"][a] != then["arrays"][a]]
    assert changed == []


def test_a_finished_store_resumes_with_all_chunks_done_and_reduces_to_the_same_tables(tmp_path):
    path = tmp_path / "every.zarr"
    build_store("every_observable", path)
    store = StudyStore.open(path)
    names = table_names(store.study, every=True)
    before = tables(store, names)
    said: list[str] = []
    study = parse_workflow(SCENES["every_observable"], "every_observable.toml")
    report = run_study(study, path, workers=1, **{**QUIET, "echo": said.append})
    assert report.skipped == store.done().size == 8
    assert len(said) == 1 and "all 8 chunks already done" in said[0]
    after = tables(StudyStore.open(path), names)
    assert list(after) == list(before) == ["counters", "diffusion", "contact", "mechanisms",
                                           "locking"]
    for name in names:
        pd.testing.assert_frame_equal(after[name], before[name], check_exact=True)
