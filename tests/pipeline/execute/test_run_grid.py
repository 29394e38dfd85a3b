"""Running a map: a scene with two grid axes runs, resumes and reproduces bit for bit, and
each of its grid lines is, chunk for chunk, the scene without a grid at that line's values."""

from __future__ import annotations

import numpy as np
import pytest
import zarr

from pipeline.execute.run import RunFailed, run_study
from pipeline.workflow.load import parse_workflow

from ..helpers import NON_REPRODUCIBLE, QUIET, TINY, assert_same_store, store_arrays

#: TINY over alpha x contact: 2 x 2 grid lines of 2 frequencies, 32 tasks
MAP = TINY.replace('name = "tiny"', 'name = "map"') + (
    '\n[grid]\nalpha = [0.5, 0.7]\ncontact = ["stick", "slide"]\n')


@pytest.fixture(scope="module")
def map_reference(tmp_path_factory):
    """The map run on a 2-worker LocalCluster."""
    path = tmp_path_factory.mktemp("map") / "map.zarr"
    run_study(parse_workflow(MAP, source="map.toml"), path, workers=2, **QUIET)
    return path


def line_rows(path, values: dict) -> list[int]:
    """The store indices of the points of one grid line, in store order."""
    g = zarr.open_group(str(path), mode="r")
    keep = np.ones(g["point"].shape[0], dtype=bool)
    for a, v in values.items():
        keep &= np.asarray(g[a][...]) == v
    return list(np.flatnonzero(keep))


@pytest.mark.parametrize("values", [{"alpha": 0.5, "contact": "slide"},
                                    {"alpha": 0.7, "contact": "stick"}])
def test_a_grid_line_is_bit_identical_to_the_scene_without_a_grid(map_reference, tmp_path,
                                                                  values):
    study = parse_workflow(MAP, source="map.toml").line(values)
    run_study(study, tmp_path / "line.zarr", workers=1, **QUIET)
    rows = line_rows(map_reference, values)
    grid, line = store_arrays(map_reference), store_arrays(tmp_path / "line.zarr")
    assert np.array_equal(grid["frequency"][rows], line["frequency"])
    g = zarr.open_group(str(map_reference), mode="r")
    compared = 0
    for name, arr in line.items():
        if name in NON_REPRODUCIBLE or g[name].metadata.dimension_names[0] != "point" \
                or name == "point":
            continue
        assert np.array_equal(grid[name][rows], arr, equal_nan=arr.dtype.kind == "f"), name
        compared += 1
    assert compared >= 5  # positions, collisions, counters, done ...


def test_the_lines_differ_where_their_values_do(map_reference):
    """The slice test above could pass on a map that ignores its axes: it does not."""
    g = zarr.open_group(str(map_reference), mode="r")
    a = line_rows(map_reference, {"alpha": 0.5, "contact": "stick"})
    b = line_rows(map_reference, {"alpha": 0.7, "contact": "stick"})
    assert not np.array_equal(g["positions"][a], g["positions"][b], equal_nan=True)


def test_a_map_on_one_worker_is_the_map_on_two(map_reference, tmp_path):
    run_study(parse_workflow(MAP, source="map.toml"), tmp_path / "one.zarr", workers=1,
              **QUIET)
    assert_same_store(map_reference, tmp_path / "one.zarr")


def test_an_interrupted_map_resumes_to_the_same_store(map_reference, tmp_path):
    study = parse_workflow(MAP, source="map.toml")
    path = tmp_path / "cut.zarr"
    # 60 Hz fails at chunk 1 of rest: its data written, never marked done, at all 4 points
    with pytest.raises(RunFailed, match=r"chunk f = 60 Hz, alpha = .*, family rest, chunk 1"):
        run_study(study, path, workers=2, fail_chunks="60:rest:1", **QUIET)
    done = np.asarray(zarr.open_group(str(path), mode="r")["done"][...])
    assert not done.all()
    report = run_study(study, path, workers=2, **QUIET)
    assert report.skipped == int(done.sum()) and report.computed
    assert_same_store(map_reference, path)


def test_a_widened_grid_grows_the_store_without_rewriting_a_done_chunk(map_reference,
                                                                      tmp_path):
    import shutil

    path = tmp_path / "grown.zarr"
    shutil.copytree(map_reference, path)
    before = store_arrays(path)
    wider = MAP.replace("alpha = [0.5, 0.7]", "alpha = [0.5, 0.6, 0.7]")
    report = run_study(parse_workflow(wider, source="map.toml"), path, workers=2, **QUIET)
    after = store_arrays(path)
    n_old = len(before["point"])
    assert len(after["point"]) == n_old + 4  # alpha = 0.6: 2 contacts x 2 frequencies
    assert report.skipped == int(before["done"].sum())
    assert np.all(after["alpha"][n_old:] == 0.6)
    g = zarr.open_group(str(path), mode="r")
    for name, arr in before.items():
        if name not in NON_REPRODUCIBLE and g[name].metadata.dimension_names[0] == "point":
            assert np.array_equal(after[name][:n_old], arr, equal_nan=arr.dtype.kind == "f"), name


def test_open_study_gives_each_point_of_a_whole_map_at_its_axis_values(map_reference):
    from pipeline.api import open_study

    ds = open_study(map_reference)
    assert ds["positions"].dims[:4] == ("frequency", "alpha", "contact", "family")
    g = zarr.open_group(str(map_reference), mode="r")
    for pi in range(g["point"].shape[0]):
        at = dict(frequency=float(g["frequency"][pi]), alpha=float(g["alpha"][pi]),
                  contact=str(g["contact"][pi]))
        assert np.array_equal(ds["positions"].sel(**at).values, g["positions"][pi],
                              equal_nan=True), at


def test_verify_passes_a_map_and_names_the_point_of_a_corrupted_chunk(map_reference, tmp_path):
    import shutil

    from pipeline.store.verify import verify_store

    assert verify_store(str(map_reference)).ok
    path = tmp_path / "bad.zarr"
    shutil.copytree(map_reference, path)
    g = zarr.open_group(str(path), mode="r+")
    pi = line_rows(path, {"alpha": 0.7, "contact": "slide"})[1]  # 60 Hz
    g["n_collisions"][pi, 0, 0:4] = -1
    report = verify_store(str(path))
    assert not report.ok
    assert any("f = 60 Hz, alpha = 0.7, contact = \"slide\", family rest, chunk 0" in str(p)
               for p in report.problems), report.problems
