"""Checks before a run (pipeline.workflow.sanity): a scene in which nothing can move is
refused before anything runs; a scene probably not meant as written is warned about."""

from __future__ import annotations

from pathlib import Path

import pytest

from pipeline.cli import main
from pipeline.execute.cluster import work_left
from pipeline.execute.run import run_study
from pipeline.workflow.load import load_workflow, parse_workflow
from pipeline.workflow.sanity import (
    NothingMoves,
    check_scene,
    looks_like_radians,
    nothing_moves,
    scene_warnings,
)

from ..helpers import QUIET

ROOT = Path(__file__).resolve().parents[3]

# The paper's misprinted amplitude: Γ = 0.403 at 100 Hz, lift-off from 157.6 Hz.
STILL = """\
[study]
name = "still"

[params]
preset = "klages2004"
A = 0.01

[frequencies]
values = [60.0, 100.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 4
chunk_size = 4
t_max = 2.0

[observables.positions]
"""


def edit(old: str, new: str, text: str = STILL):
    assert old in text
    return parse_workflow(text.replace(old, new), source="s.toml")


def test_a_scene_below_lift_off_everywhere_at_rest_and_sticking_is_refused_in_one_line():
    refusal = nothing_moves(edit("", ""))
    assert isinstance(refusal, NothingMoves)
    text = str(refusal)
    assert text.startswith("s.toml:6: A: no particle can lift off: Γ_max = 0.403 at 100 Hz")
    assert "\n" not in text and "allowed:" in text


def test_the_refusal_suggests_the_a_ten_times_larger():
    assert "did you mean A = 0.1?" in str(nothing_moves(edit("", "")))


def test_the_refusal_suggests_a_hundred_times_when_ten_does_not_lift_off():
    # 10 x A = 0.001 at 100 Hz: f_lift = 157.6 Hz; 100 x: 49.8 Hz
    assert "did you mean A = 0.1?" in str(nothing_moves(edit("A = 0.01", "A = 0.001")))


def test_a_preset_amplitude_below_lift_off_names_the_lift_off_frequency():
    refusal = nothing_moves(edit("A = 0.01\n", "", STILL.replace("[60.0, 100.0]", "[30.0, 40.0]")))
    assert "s.toml:7: frequencies:" in str(refusal) and "lift-off needs f >= 49.82 Hz" in str(refusal)


def test_a_gamma_scene_below_lift_off_names_the_lift_off_gamma():
    refusal = nothing_moves(edit("A = 0.01", "Gamma = 0.5"))
    assert "Gamma: " in str(refusal) and "lift-off needs Gamma >= 1 " in str(refusal)


def test_one_point_at_lift_off_is_enough_to_run():
    assert nothing_moves(edit("[60.0, 100.0]", "[60.0, 158.0]")) is None


def test_a_thrown_floor_under_stick_below_its_lift_off_is_refused():
    # throw 30 deg: lift-off at 66.7 Hz (bbb.analysis.liftoff_onset) although Γ = 1.45 at 60 Hz
    study = edit("A = 0.01\n", "throw = 30.0\n", STILL.replace("[60.0, 100.0]", "[40.0, 60.0]"))
    assert study.points[-1].params.gamma > 1 and nothing_moves(study) is not None


def test_coulomb_sliding_below_lift_off_is_not_refused_but_warned():
    study = edit("A = 0.01\n", 'throw = 30.0\ncontact = "coulomb"\nmu = 0.3\n',
                 STILL.replace("[60.0, 100.0]", "[40.0, 60.0]"))
    assert nothing_moves(study) is None
    (line,) = scene_warnings(study)
    assert "no particle at rest can lift off" in line and "only sliding can move" in line


def test_a_family_started_in_flight_below_lift_off_is_not_refused_but_warned():
    study = edit("[families.rest]\ninitial = \"rest\"", "[families.launched]\ninitial = \"launched\"")
    assert nothing_moves(study) is None
    (line,) = scene_warnings(study)
    assert "families started in flight (launched)" in line


def test_gamma_above_50_somewhere_is_warned():
    (line,) = scene_warnings(edit("A = 0.01", "A = 1.0", STILL.replace("100.0]", "120.0]")))
    assert line.startswith("s.toml:6: A: warning: Γ = 58 at 120 Hz is above 50")


def test_gamma_up_to_50_is_not_warned():
    assert scene_warnings(edit("A = 0.01", "A = 1.0")) == []  # Γ = 40 at 100 Hz


def test_a_tilt_that_reads_like_radians_is_warned_with_its_degrees():
    (line,) = scene_warnings(edit("A = 0.01", "A = 0.1\ntilt = 0.1"))
    assert line == ("s.toml:7: tilt = 0.1: warning: angles are in degrees (0.1 rad = 5.7°); "
                    "the run continues")


def test_an_angle_on_a_grid_axis_that_reads_like_radians_is_warned():
    study = edit("A = 0.01\n", "A = 0.1\n\n[grid]\ntilt = [0.0, 0.2618]\n")
    assert scene_warnings(study) == [
        "s.toml:9: tilt = 0.2618: warning: angles are in degrees (0.2618 rad = 15.0°); "
        "the run continues"]


def test_whole_and_half_degrees_and_zero_do_not_read_like_radians():
    assert not any(looks_like_radians(v) for v in (0.0, 0.5, -1.0, 1.5, 2.0, 30.0))
    assert all(looks_like_radians(v) for v in (0.1, -0.2618, 0.5236, 1.2))


@pytest.mark.parametrize("path", sorted(
    str(p.relative_to(ROOT)) for d in ("workflows", "pipeline/studies", "examples")
    for p in (ROOT / d).rglob("*.toml")))
def test_every_shipped_scene_is_silent(path):
    study = load_workflow(ROOT / path)
    assert scene_warnings(study) == [] and nothing_moves(study) is None


def test_check_scene_prints_each_warning_then_refuses(capsys):
    study = edit("A = 0.01", "A = 0.01\ntilt = 0.1")
    with pytest.raises(NothingMoves):
        check_scene(study)
    assert capsys.readouterr().err.startswith("s.toml:7: tilt = 0.1: warning:")


def test_run_study_refuses_before_a_store_exists(tmp_path):
    with pytest.raises(NothingMoves):
        run_study(edit("", ""), tmp_path / "still.zarr", workers=1, **QUIET)
    assert not (tmp_path / "still.zarr").exists()


def test_no_batch_job_is_planned_for_a_scene_that_cannot_move(tmp_path):
    with pytest.raises(NothingMoves):
        work_left(edit("", ""), tmp_path / "still.zarr")
    assert not (tmp_path / "still.zarr").exists()


@pytest.mark.parametrize("command", ["run", "plan"])
def test_bbb_run_and_plan_exit_2_on_a_scene_that_cannot_move(command, tmp_path, capsys):
    wf = tmp_path / "still.toml"
    wf.write_text(STILL)
    extra = ["--store", str(tmp_path / "still.zarr")] if command == "run" else []
    assert main([command, str(wf), *extra]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no particle can lift off" in err[0]
    assert not (tmp_path / "still.zarr").exists()
