"""The tables of a grid store: long format with one column per axis and its unit, one row per
(point[, family]); their Dataset unstacked, ``family`` a dimension, CF attributes, to_netcdf."""

from __future__ import annotations

import math

import numpy as np
import pyarrow.parquet as pq
import pytest

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.catalog import tables
from pipeline.tables.dataset import CONVENTIONS, tables_dataset
from pipeline.tables.reduce import reduce_store
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY

# alpha x R with one invalid combination left out: slide needs R well above S/2 = 1 mm
SKIP = TINY.replace('name = "tiny"', 'name = "skip"').replace(
    'preset = "klages2004"', 'preset = "klages2004"\ncontact = "slide"') + (
    '\n[grid]\nalpha = [0.5, 0.7]\nR = [1.0, 15.0]\ninvalid = "skip"\n')


@pytest.fixture(scope="module")
def grid_store(tmp_path_factory):
    """The SKIP map, every chunk computed in this process: 6 of its 8 points exist."""
    study = parse_workflow(SKIP, source="skip.toml")
    store = StudyStore.create_or_open(tmp_path_factory.mktemp("grid") / "g.zarr", study)
    for fi in range(len(study.points)):
        for mi in range(len(study.families)):
            for ci in range(study.accuracy.n_chunks):
                compute_chunk(store, fi, mi, ci)
    store.consolidate()
    return store


def test_the_skipped_points_are_not_in_the_store(grid_store):
    assert len(grid_store.study.points) == 4  # (alpha, R = 1) is left out at both f
    assert {dict(p.grid)["R"] for p in grid_store.study.points} == {15.0}


def test_the_diffusion_table_has_one_row_per_point_and_a_column_per_axis(grid_store):
    df = tables(grid_store, ["diffusion"])["diffusion"]
    assert list(df.columns[:3]) == ["f", "alpha", "R"]
    assert sorted(zip(df["alpha"], df["f"], strict=True)) == [
        (a, f) for a in (0.5, 0.7) for f in (54.0, 60.0)]
    assert (df["R"] == 15.0).all()


def test_each_row_has_the_gamma_of_its_frequency(grid_store):
    """Gamma = A (2 pi f)^2 / g with the preset's A = 0.1 mm and g = 9800 mm/s^2, whatever
    the row's alpha and R."""
    import math

    df = tables(grid_store, ["diffusion"])["diffusion"]
    want = [0.1 * (2 * math.pi * f) ** 2 / 9800.0 for f in df["f"]]
    np.testing.assert_allclose(df["Gamma"], want, rtol=1e-12)


def test_the_parquet_tables_carry_the_axis_units(grid_store, tmp_path):
    reduce_store(grid_store.path, tmp_path)
    for name in ("diffusion", "counters"):
        schema = pq.read_schema(tmp_path / f"{name}.parquet")
        units = {f.name: f.metadata[b"unit"].decode() for f in schema if f.metadata}
        assert units["alpha"] == "1" and units["R"] == "mm" and units["f"] == "Hz"


def test_the_dataset_unstacks_the_grid_with_nan_where_a_point_is_absent(grid_store):
    study = grid_store.study
    ds = tables_dataset(tables(grid_store), dict(study.grid), [f.name for f in study.families])
    assert ds["D"].dims == ("frequency", "alpha", "R")
    assert ds["D_family"].dims == ("frequency", "alpha", "R", "family")
    assert np.isnan(ds["D"].sel(R=1.0)).all()  # the skipped points
    assert np.isfinite(ds["D"].sel(R=15.0, frequency=60.0)).all()


def test_the_per_family_columns_become_one_variable_along_family(grid_store):
    study = grid_store.study
    t = tables(grid_store)
    ds = tables_dataset(t, ["alpha", "R"], [f.name for f in study.families])
    assert not [v for v in ds.data_vars if v.startswith(("D_rest", "D_launched"))]
    row = t["diffusion"].iloc[0]
    got = ds["D_family_lo"].sel(frequency=row["f"], alpha=row["alpha"], R=row["R"],
                                family="launched")
    assert float(got) == row["D_launched_lo"] or (math.isnan(got) and math.isnan(
        row["D_launched_lo"]))


def test_every_variable_has_cf_units_and_long_name(grid_store):
    ds = tables_dataset(tables(grid_store), ["alpha", "R"], ["rest", "launched"])
    assert ds.attrs["Conventions"] == CONVENTIONS
    for name, var in ds.variables.items():
        assert "units" in var.attrs and var.attrs.get("long_name"), name
        assert var.attrs["units"] != "?", name
    assert ds["D"].attrs["units"] == "mm^2/s" and ds["R"].attrs["units"] == "mm"


def test_the_dataset_round_trips_through_netcdf(grid_store, tmp_path):
    import xarray as xr

    ds = tables_dataset(tables(grid_store), ["alpha", "R"], ["rest", "launched"])
    ds.to_netcdf(tmp_path / "g.nc")
    back = xr.open_dataset(tmp_path / "g.nc")
    np.testing.assert_array_equal(back["D"].values, ds["D"].values)
    assert back["ergodic"].attrs["units"] == "" and back.attrs["Conventions"] == CONVENTIONS


def test_open_study_unstacks_the_store_with_every_grid_value(grid_store):
    from pipeline.api import open_study

    ds = open_study(grid_store.path)
    assert ds["positions"].dims[:3] == ("frequency", "alpha", "R")
    assert list(ds["R"].values) == [1.0, 15.0] and ds["R"].attrs["units"] == "mm"
    assert np.isnan(ds["positions"].sel(R=1.0).values).all()
    assert np.isfinite(ds["positions"].sel(R=15.0, alpha=0.7, frequency=60.0).values).all()


def test_open_study_masks_the_particles_of_a_chunk_not_done_at_its_point(grid_store, tmp_path):
    import shutil

    import zarr

    from pipeline.api import open_study

    path = tmp_path / "partial.zarr"
    shutil.copytree(grid_store.path, path)
    study = grid_store.study
    pi = next(i for i, p in enumerate(study.points) if p.f == 60.0 and dict(p.grid)["alpha"] == 0.7)
    zarr.open_group(str(path), mode="r+")["done"][pi, 1, 0] = False  # launched, chunk 0
    x = open_study(path)["positions"].sel(frequency=60.0, alpha=0.7, R=15.0)
    cs = study.accuracy.chunk_size
    assert np.isnan(x.sel(family="launched").values[:cs]).all()
    assert np.isfinite(x.sel(family="launched").values[cs:]).all()
    assert np.isfinite(x.sel(family="rest").values).all()
