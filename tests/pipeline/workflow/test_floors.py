"""Floors in scenes: `[params] floor` with its shape's keys, checked in one line, as [grid]
axes, and a sawtooth scene through `bbb run`, `reduce` and `plot` whose drift shows."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline.cli import main
from pipeline.workflow.load import WorkflowError, load_workflow, parse_workflow

from ..helpers import TINY

WORKFLOWS = Path(__file__).resolve().parents[3] / "workflows"


def with_params(extra: str) -> str:
    return TINY.replace('preset = "klages2004"\n', f'preset = "klages2004"\n{extra}\n')


def error_of(text: str) -> str:
    with pytest.raises(WorkflowError) as e:
        parse_workflow(text, source="wf.toml")
    assert "\n" not in str(e.value)
    return str(e.value)


@pytest.mark.parametrize("name, floor, axis", [("sine", "sine", "depth"),
                                               ("sawtooth", "sawtooth", "peak")])
def test_the_shipped_floor_scenes_give_their_shape_at_every_point(name, floor, axis):
    study = load_workflow(WORKFLOWS / f"{name}.toml")
    assert {p.params.floor for p in study.points} == {floor}
    assert len({getattr(p.params, axis) for p in study.points}) == 2


def test_an_unknown_floor_is_one_line_naming_the_shapes():
    msg = error_of(with_params('floor = "wavy"'))
    assert "floor" in msg and "sine" in msg and "sawtooth" in msg


def test_a_depth_on_the_arcs_is_refused_in_one_line():
    assert "depth" in error_of(with_params("depth = 0.3"))


def test_a_sine_without_its_depth_is_refused_in_one_line():
    assert "depth" in error_of(with_params('floor = "sine"'))


def test_a_sawtooth_peak_outside_its_period_is_refused_in_one_line():
    assert "peak" in error_of(with_params('floor = "sawtooth"\ndepth = 0.3\npeak = 1.0'))


@pytest.mark.parametrize("extra", ['contact = "slide"', "tilt = 5.0"])
def test_a_sine_under_sliding_or_on_a_conveyor_is_refused_before_the_run(extra):
    msg = error_of(with_params(f'floor = "sine"\ndepth = 0.3\n{extra}'))
    assert "stick" in msg and "level" in msg


def test_an_arc_scene_keeps_its_params_without_the_floor_keys():
    study = parse_workflow(TINY, source="wf.toml")
    assert not {"floor", "depth", "peak"} & set(study.points[0].params.as_dict())


def test_a_sawtooth_scene_runs_reduces_and_plots_with_a_drift_off_centre(tmp_path):
    text = (WORKFLOWS / "sawtooth.toml").read_text().replace("values = [60.0, 70.0]",
                                                             "values = [60.0]")
    wf = tmp_path / "saw.toml"
    wf.write_text(text)
    store = tmp_path / "saw.zarr"
    assert main(["run", str(wf), "--store", str(store), "--workers", "1", "--no-progress"]) == 0
    assert main(["reduce", str(store), "--out", str(tmp_path / "tables")]) == 0
    df = pd.read_csv(tmp_path / "tables" / "diffusion.csv").set_index("peak")
    assert df.loc[0.3, "v_lo"] > 0.0 or df.loc[0.3, "v_hi"] < 0.0
    assert df.loc[0.5, "v"] == 0.0 and np.isfinite(df["D"]).all()
    assert main(["plot", str(store), "--out", str(tmp_path / "figs")]) == 0
    assert any((tmp_path / "figs").glob("*v_vs_frequency*.png"))
