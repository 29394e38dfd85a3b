"""The studies' adapter from a map's long tables to per-line tables
(pipeline/studies/map_lines.py): each slice of a tiny map's tables is, bit for bit, the table of
the tiny scene without a grid at that line's values."""

from __future__ import annotations

import pandas as pd

from pipeline.execute.run import run_study
from pipeline.store.study_store import StudyStore
from pipeline.studies.map_lines import line_table
from pipeline.tables.catalog import tables
from pipeline.tables.collisions import locking_table
from pipeline.workflow.load import parse_workflow

from ..helpers import QUIET, TINY

#: TINY over tilt x contact x mu (mu of the Coulomb line only): 4 lines, contact observed
MAP = (TINY.replace('name = "tiny"', 'name = "map"') + "\n[observables.contact]\n"
       '\n[grid]\ntilt = [0.0, 2.0]\ncontact = ["stick", "coulomb"]\nmu = [0.3]\n')


def _tables(path) -> dict[str, pd.DataFrame]:
    st = StudyStore.open(str(path))
    return {**tables(st), "locking": locking_table(st)}


def test_a_slice_of_a_maps_tables_is_the_table_of_its_scene_without_a_grid(tmp_path):
    from distributed import Client, LocalCluster

    study = parse_workflow(MAP, source="map.toml")
    lines = [{"tilt": 0.0, "contact": "stick", "mu": 0.0},
             {"tilt": 2.0, "contact": "coulomb", "mu": 0.3}]
    with (LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0",
                       env={"NUMBA_NUM_THREADS": "1"}) as cluster, Client(cluster)):
        for name, s in [("map", study)] + [(f"line{i}", study.line(v)) for i, v in enumerate(lines)]:
            run_study(s, tmp_path / f"{name}.zarr", scheduler=cluster.scheduler_address, **QUIET)
    maps = _tables(tmp_path / "map.zarr")
    for i, values in enumerate(lines):
        line = _tables(tmp_path / f"line{i}.zarr")
        assert sorted(maps) == sorted(line) == ["contact", "counters", "diffusion", "locking"]
        assert "v" in line["diffusion"]  # the transport columns: tilt is an override
        for name, want in line.items():
            got = line_table(maps[name], values)
            pd.testing.assert_frame_equal(got.drop(columns="task_seconds", errors="ignore"),
                                          want.drop(columns="task_seconds", errors="ignore"),
                                          check_exact=True, obj=f"{name} at {values}")
