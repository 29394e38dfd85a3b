"""What a lost root zarr.json held beside the workflow, read back from the arrays when
`bbb run` rebuilds it (pipeline/execute/repair.py): the frequencies refinement added, a map's
points in store order -- or a refusal saying which damaged file alone recorded them.  The
commands' side, on the tiny store: tests/pipeline/test_metadata_faults.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from pipeline.execute.repair import repair_metadata
from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StoreError, StudyStore
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY

REFINE = TINY.replace("values = [54.0, 60.0]", "values = [54.0, 60.0, 66.0]\nrefine = { to = 10.0 }")
MAP = TINY.replace('name = "tiny"', 'name = "map"') + "\n[grid]\nalpha = [0.5, 0.7]\n"


def test_a_lost_root_of_a_refined_store_gets_its_refined_frequencies_back(tmp_path):
    study = parse_workflow(REFINE, "refine.toml")
    grown = StudyStore.create_or_open(tmp_path / "r.zarr", study).add_frequencies((57.125,))
    compute_chunk(grown, 3, 1, 1)  # a chunk of the refined frequency: the one checked
    (Path(grown.path) / "zarr.json").unlink()
    said = []
    assert repair_metadata(study, grown.path, said.append)
    again = StudyStore.open(grown.path)
    assert again.study.frequencies == (54.0, 60.0, 66.0, 57.125)
    assert again.study.refined == (57.125,)
    assert again.done().sum() == 1 and again.done()[3, 1, 1]
    assert "chunk 1 of f = 57.125 Hz, family launched recomputed bit-identical" in said[0]


def test_a_lost_root_and_a_lost_refined_array_metadata_are_refused_naming_why(tmp_path):
    study = parse_workflow(REFINE, "refine.toml")
    grown = StudyStore.create_or_open(tmp_path / "r.zarr", study).add_frequencies((57.125,))
    (Path(grown.path) / "zarr.json").unlink()
    (Path(grown.path) / "refined" / "zarr.json").write_text("{")
    with pytest.raises(StoreError, match=r"and so is refined/zarr.json .* which alone records "
                                         r"the frequencies refinement added"):
        repair_metadata(study, grown.path)
    assert not (Path(grown.path) / "zarr.json").exists()


def test_a_lost_root_of_a_map_gets_its_points_back_in_store_order(tmp_path):
    """A map laid out for alpha = 0.7 then widened to 0.5: its points are not in the grid's
    order, and only the coordinates say so once the root is lost."""
    narrow = parse_workflow(MAP.replace("alpha = [0.5, 0.7]", "alpha = [0.7]"), "narrow.toml")
    wide = parse_workflow(MAP, "map.toml")
    StudyStore.create_or_open(tmp_path / "m.zarr", narrow)
    store = StudyStore.create_or_open(tmp_path / "m.zarr", wide)  # grows: 0.7 first, then 0.5
    before = [p.key for p in store.study.points]
    assert before != [p.key for p in wide.points]  # else this test shows nothing
    compute_chunk(store, 3, 0, 0, point=store.study.points[3])
    (Path(store.path) / "zarr.json").unlink()
    assert repair_metadata(wide, store.path, lambda _: None)
    again = StudyStore.open(store.path)
    assert [p.key for p in again.study.points] == before and again.done()[3, 0, 0]
