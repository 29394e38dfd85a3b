"""The make_figures entry: its scenes are valid workflows, and --fast makes draft versions."""

from __future__ import annotations

import importlib.metadata
import json
import os
import tomllib
from pathlib import Path

import pytest

from pipeline.studies.registry import study
from pipeline.workflow.scenes import draft_text, load_scene, scene_label, scene_names, scene_path
from pipeline.workflow.scenes import toml_dump as _toml_dump

from ...helpers import run_outside

SCENES = study("klages2004").scenes  # the paper's scenes


@pytest.mark.parametrize("name", SCENES)
def test_every_scene_is_a_valid_workflow_at_both_accuracies(name):
    paper, draft = load_scene(name), load_scene(name, fast=True)
    assert draft.accuracy.preset == "draft"
    assert draft.frequencies == paper.frequencies and draft.families == paper.families
    assert draft.fingerprint() != paper.fingerprint()  # a separate store


def test_draft_collision_scenes_are_short_and_record_after_a_transient():
    study = load_scene("locking", fast=True)
    assert study.accuracy.t_max == 60.0 and study.accuracy.n_particles == 4
    assert study.observables.collisions_from < study.accuracy.t_max


def test_a_workflow_file_wins_over_the_built_in_scene():
    assert scene_label("figure2") == "workflows/figure2.toml"
    assert scene_label("locking") == "pipeline/studies/klages2004/scenes/locking.toml"


def test_every_scene_and_workflow_is_found_through_the_package():
    assert set(SCENES) | {"smoke", "accuracy"} <= set(scene_names())
    with pytest.raises(FileNotFoundError, match="allowed: .*smoke"):
        scene_path("no_such_scene")


def test_toml_dump_round_trips_a_workflow_document():
    text = scene_path("ergodicity").read_text()
    doc = tomllib.loads(text)
    assert tomllib.loads(_toml_dump(doc)) == doc
    assert tomllib.loads(draft_text(text))["accuracy"]["preset"] == "draft"


def test_the_draft_of_a_target_driven_scene_keeps_a_loose_target():
    """Fig. 2 asks for 3 % with d_resolved = 9 mm²/s: its draft asks for 15 % with small
    chunks and a low cap, and d_resolved loosened by the same factor 5."""
    draft = load_scene("figure2", fast=True).accuracy
    assert (draft.target_ci, draft.chunk_size, draft.max_particles) == (0.15, 64, 256)
    assert draft.d_resolved == 45.0 and draft.t_max == 50.0


def test_the_run_log_records_paths_relative_to_the_repository(tmp_path):

    from pipeline.make_figures import run_log_entry
    from pipeline.workflow.scenes import ROOT

    for store in (ROOT / "runs" / "figure2.zarr", tmp_path / "runs" / "figure2.zarr"):
        entry = run_log_entry("figure2", str(store))
        assert not any(os.path.isabs(v) for v in entry.values()), entry
        assert (ROOT / entry["store"]).resolve() == store.resolve()
        assert (ROOT / entry["workflow"]).resolve() == scene_path("figure2").resolve()
    assert run_log_entry("locking", str(ROOT / "runs" / "locking.zarr")) == {
        "workflow": "pipeline/studies/klages2004/scenes/locking.toml", "store": "runs/locking.zarr"}


def test_the_committed_run_log_holds_no_absolute_path():
    import json

    from pipeline.workflow.scenes import ROOT

    log = json.loads((ROOT / "figures" / "run_log.json").read_text())
    for name, entry in log["scenes"].items():
        for key in ("workflow", "store"):
            assert not entry[key].startswith("/"), (name, key, entry[key])


# -- a non-editable install, used from outside the repository -------------------------------
ROOT = Path(__file__).resolve().parents[4]


def test_a_wheel_ships_every_scene_and_module(installed, tmp_path):
    code = ("import pipeline, bbb, json; from pipeline.make_figures import scenes; SCENES = scenes(); "
            "from pipeline.workflow.scenes import load_scene, scene_names\n"
            "[load_scene(n, fast=f) for n in SCENES for f in (False, True)]\n"
            "print(json.dumps({'file': pipeline.__file__, 'scenes': scene_names(), "
            "'version': bbb.__version__}))")
    got = json.loads(run_outside(installed, code, tmp_path).strip().splitlines()[-1])
    assert not Path(got["file"]).is_relative_to(ROOT)  # the installed copy, not this checkout
    assert set(SCENES) | {"smoke", "accuracy"} <= set(got["scenes"])
    assert set(scene_names()) <= set(got["scenes"])  # every study's scenes/ is package data
    assert got["version"] == importlib.metadata.version("bbb")
    # every module of the source tree is in the wheel (pyproject lists the packages)
    site = Path(got["file"]).parent.parent
    source = {p.relative_to(ROOT) for d in ("bbb", "pipeline") for p in (ROOT / d).rglob("*.py")}
    missing = sorted(str(p) for p in source if not (site / p).exists())
    assert not missing, f"not in the wheel (add the package to pyproject.toml): {missing}"
    # and every scene file, drafts included (a draft missing from the wheel is not an error
    # there: load_scene(fast=True) quietly falls back to the whole scene at draft accuracy)
    scenes = {p.relative_to(ROOT) for p in (ROOT / "pipeline" / "studies").rglob("*.toml")}
    missing = sorted(str(p) for p in scenes if not (site / p).exists())
    assert not missing, f"not in the wheel (add them to package-data in pyproject.toml): {missing}"


@pytest.mark.slow
def test_the_installed_make_figures_fast_runs_from_outside_the_repository(installed, tmp_path):
    # every scene at draft accuracy, every figure and REPORT.md: 7.4 min measured on this
    # shared 2-core machine (2026-11-23, numba compiling cold in the new environment), 8.9 min
    # on 2026-11-28 before the impacts study and the own-seed line were added; cut at 30 min
    run_outside(installed, "import sys; from pipeline.make_figures import main; "
                 "sys.exit(main(['--fast', '--no-progress', '--out', 'figs', '--runs', 'runs']))",
                 tmp_path, timeout=1800)
    assert (tmp_path / "figs" / "REPORT.md").exists()
    assert {p.name for p in (tmp_path / "figs").glob("*.png")} >= {
        "fig1_geometry.png", "fig2_diffusion.png", "fig3_phase_space.png", "fig_locking.png",
        "fig2_matyas2004.png", "fig_impacts_phase.png", "fig_impacts_vx.png"}
