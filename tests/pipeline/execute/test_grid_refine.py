"""Refinement of a map in every direction: the rule on synthetic maps with known answers, and a
refined map run that is the same on 1 and 2 workers and after an interruption."""

from __future__ import annotations

import numpy as np
import pytest
import zarr

from pipeline.execute.grid_refine import refine_grid
from pipeline.execute.run import RunFailed, run_study
from pipeline.workflow.keys import GridRefine
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.point import Point

from ..helpers import QUIET, TINY, assert_same_store


def points(grid_axis: str, values, freqs) -> list[Point]:
    return [Point(f, ((grid_axis, v),), None) for v in values for f in freqs]


def table(rows) -> np.ndarray:
    """(D, lo, hi) rows from (D, half-width) pairs."""
    return np.array([(d, d - h, d + h) for d, h in rows], dtype=np.float64)


def test_a_jump_along_an_axis_is_split_at_its_midpoint():
    pts = points("alpha", (0.5, 0.7, 0.9), (60.0,))
    new = refine_grid(pts, table([(10, 1), (10, 1), (50, 1)]),
                      GridRefine((("alpha", 0.05),), extrema=False, jumps=True))
    assert new == [(60.0, (("alpha", 0.8),))]


def test_neighbours_within_their_cis_are_left_alone():
    pts = points("alpha", (0.5, 0.7, 0.9), (60.0,))
    new = refine_grid(pts, table([(10, 5), (12, 5), (14, 5)]),
                      GridRefine((("alpha", 0.05),), extrema=True, jumps=True))
    assert new == []


def test_a_gap_at_the_resolution_is_not_split():
    pts = points("alpha", (0.5, 0.55), (60.0,))
    new = refine_grid(pts, table([(10, 1), (50, 1)]), GridRefine((("alpha", 0.05),)))
    assert new == []


def test_an_extremum_along_f_splits_both_its_gaps_on_the_millihertz_grid():
    pts = [Point(f, (("alpha", 0.7),), None) for f in (50.0, 55.0, 60.0, 65.0)]
    new = refine_grid(pts, table([(10, 1), (100, 1), (10, 1), (10, 1)]),
                      GridRefine((("f", 0.5),), extrema=True, jumps=False))
    assert sorted(new) == [(52.5, (("alpha", 0.7),)), (57.5, (("alpha", 0.7),))]


def test_only_lines_through_the_workflows_own_values_are_refined():
    """α = 0.6 was added between the listed 0.5 and 0.7 (at 60 and 70 Hz); its jump along f
    is not refined: only the listed lines are curves."""
    pts = points("alpha", (0.5, 0.6, 0.7), (60.0, 70.0))
    rows = table([(10, 1), (11, 1), (10, 1), (90, 1), (10, 1), (11, 1)])
    rule = GridRefine((("f", 1.0),), extrema=False, jumps=True)
    own = {"f": (60.0, 70.0), "alpha": (0.5, 0.7)}
    assert refine_grid(pts, rows, rule, own=own) == []
    assert refine_grid(pts, rows, rule) == [(65.0, (("alpha", 0.6),))]  # without own: filled


def test_along_an_axis_only_the_listed_frequencies_are_refined():
    pts = points("alpha", (0.5, 0.9), (60.0, 60.5))
    rows = table([(10, 1), (10, 1), (90, 1), (90, 1)])  # a jump along α at both frequencies
    rule = GridRefine((("alpha", 0.05),), extrema=False, jumps=True)
    new = refine_grid(pts, rows, rule, own={"f": (60.0,), "alpha": (0.5, 0.9)})
    assert new == [(60.0, (("alpha", 0.7),))]


def test_each_grid_line_is_refined_on_its_own():
    """Along f, the line alpha = 0.5 has a jump and the line alpha = 0.7 none."""
    pts = points("alpha", (0.5, 0.7), (60.0, 70.0))
    new = refine_grid(pts, table([(10, 1), (90, 1), (10, 1), (11, 1)]),
                      GridRefine((("f", 1.0),), extrema=False, jumps=True))
    assert new == [(65.0, (("alpha", 0.5),))]


def test_a_point_without_a_value_is_skipped_and_its_neighbours_compared_across_it():
    pts = points("alpha", (0.5, 0.6, 0.9), (60.0,))
    new = refine_grid(pts, table([(10, 1), (np.nan, np.nan), (50, 1)]),
                      GridRefine((("alpha", 0.05),), extrema=False, jumps=True))
    assert new == [(60.0, (("alpha", 0.7),))]  # the gap 0.5-0.9 split


# -- a refined map run ---------------------------------------------------------------------------
REFINED = TINY.replace('name = "tiny"', 'name = "refined"').replace(
    "[54.0, 60.0]", "[60.0, 72.0]").replace("n_particles = 8", "n_particles = 16") + (
    "\n[grid]\nalpha = [0.5, 0.9]\n\n[grid.refine]\nalpha = 0.1\nf = 6.0\n")


@pytest.fixture(scope="module")
def refined_reference(tmp_path_factory):
    path = tmp_path_factory.mktemp("refined") / "r.zarr"
    run_study(parse_workflow(REFINED, source="refined.toml"), path, workers=2, **QUIET)
    return path


def test_a_refined_map_grows_beyond_its_grid(refined_reference):
    g = zarr.open_group(str(refined_reference), mode="r")
    assert g["point"].shape[0] > 4
    assert set(np.asarray(g["alpha"][...])) - {0.5, 0.9}  # values between the grid's


def test_a_refined_map_on_one_worker_is_the_map_on_two(refined_reference, tmp_path):
    run_study(parse_workflow(REFINED, source="refined.toml"), tmp_path / "one.zarr", workers=1,
              **QUIET)
    assert_same_store(refined_reference, tmp_path / "one.zarr")


def test_an_interrupted_refinement_resumes_to_the_same_map(refined_reference, tmp_path):
    g = zarr.open_group(str(refined_reference), mode="r")
    added = float(np.asarray(g["frequency"][...])[4])  # a frequency of the first added point
    study = parse_workflow(REFINED, source="refined.toml")
    path = tmp_path / "cut.zarr"
    with pytest.raises(RunFailed):
        run_study(study, path, workers=2, fail_chunks=f"{added:g}:rest:1", **QUIET)
    run_study(study, path, workers=2, **QUIET)
    assert_same_store(refined_reference, path)
