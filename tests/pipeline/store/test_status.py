"""`bbb status` of a map: one line a point, with its grid values, and its done chunks."""

from __future__ import annotations

from pipeline.execute.task import compute_chunk
from pipeline.store.status import status_text
from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY


def test_status_lists_every_point_of_a_map_with_its_values_and_done_chunks(tmp_path):
    study = parse_workflow(TINY + '[grid]\ncontact = ["stick", "slide"]\n', source="m.toml")
    store = StudyStore.create_or_open(tmp_path / "m.zarr", study)
    compute_chunk(store, 3, 0, 1)  # slide, 60 Hz, rest, chunk 1
    lines = status_text(store).splitlines()
    assert lines[0].startswith("tiny: 1/16 chunks done") and "4 points (contact x f)" in lines[0]
    assert lines[1].split() == ["f", "(Hz)", "contact", "rest", "launched"]
    assert [ln.split() for ln in lines[2:]] == [
        ["54", "stick", "0/2", "0/2"], ["60", "stick", "0/2", "0/2"],
        ["54", "slide", "0/2", "0/2"], ["60", "slide", "1/2", "0/2"]]
