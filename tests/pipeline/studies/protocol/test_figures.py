"""The protocol figures draw from a table, and the draft scene matches the scene."""

from __future__ import annotations

from pipeline.studies.protocol.claims import SCENES
from pipeline.studies.protocol.figures import (
    figure_decomposition,
    figure_protocol_map,
    protocol_dataset,
)
from pipeline.workflow.scenes import load_scene

from .synthetic import F, curves


def test_the_map_has_a_row_per_ensemble_and_window(tmp_path):
    c = curves()
    ds = protocol_dataset(c, "displaced")
    assert ds.sizes == {"protocol": 3 * 2, "frequency": F.size}
    assert ds["D"].attrs["units"] == "mm^2/s"
    fig = figure_protocol_map(c, tmp_path)
    assert (tmp_path / f"{fig.get_label()}.png").is_file()
    fig = figure_decomposition(c, tmp_path)
    assert (tmp_path / f"{fig.get_label()}.pdf").is_file()


def test_the_draft_has_the_scenes_families_and_observables():
    (name,) = SCENES
    full, draft = load_scene(name), load_scene(name, fast=True)
    assert draft.source.startswith("pipeline/studies/protocol/scenes/draft/")
    assert draft.families == full.families and draft.observables == full.observables
    assert set(draft.frequencies) <= set(full.frequencies)
    assert full.accuracy.t_max == 50.0 and full.accuracy.sample_dt == 0.05
