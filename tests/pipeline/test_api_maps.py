"""open_study(reduced=True) and reduced_dataset on every shipped map layout (tests/pipeline/
map_scenes.py: the tiny version of each scene with a [grid], run by run_study on one real
LocalCluster): the same coordinates, the same values, the same presence mask; a point sits at
the values the store and the tables record (mu = 0 under stick); an absent point is NaN in
every variable; a refined map's cells refinement did not add are absent."""

from __future__ import annotations

import shutil

import numpy as np
import pytest
import zarr

from pipeline.api import open_study, reduced, reduced_dataset, run_study

from .map_scenes import MAP_SCENES, shipped_maps, tiny_scene

REFINED = "pipeline/studies/dissipation/scenes/dissipation.toml"
SLIDING = "pipeline/studies/transport/scenes/transport_sliding.toml"


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def stores(client, tmp_path_factory):
    """{scene: store path}, each tiny scene run once, when a test first asks for it."""
    made: dict[str, str] = {}

    def get(scene: str) -> str:
        if scene not in made:
            path = tmp_path_factory.mktemp("maps") / f"{scene.split('/')[-1][:-5]}.zarr"
            run_study(tiny_scene(scene), path, client=client, echo=lambda s: None)
            made[scene] = str(path)
        return made[scene]
    return get


def _table_variables(ds, raw):
    """{name in reduced_dataset: name in open_study(reduced=True)} (a column the store also
    has is attached as <table>_<column>)."""
    return {n: (n if n not in raw.variables else f"{v.attrs['table']}_{n}")
            for n, v in ds.data_vars.items() if n != "present"}


def _cells(ds) -> set[tuple]:
    """The (f, axis values...) of the cells where ``present`` holds for some family."""
    p = ds["present"].any("family")
    return {tuple(float(c) if isinstance(c, float) else str(c) for c in idx)
            for idx, v in p.to_series().items() if v}


def test_the_list_of_map_scenes_is_every_shipped_scene_with_a_grid():
    assert shipped_maps() == sorted(MAP_SCENES)


@pytest.mark.parametrize("scene", MAP_SCENES)
def test_open_study_reduced_and_reduced_dataset_agree_value_for_value(stores, scene):
    path = stores(scene)
    a, b, raw = open_study(path, reduced=True), reduced_dataset(path), open_study(path)
    for d in b.dims:
        assert list(a[d].values) == list(b[d].values), d
    assert a["present"].variable.equals(b["present"].variable)
    names = _table_variables(b, raw)
    assert len(names) >= 5  # the counters at least
    for name, other in names.items():
        assert a[other].dims == b[name].dims, name
        assert a[other].variable.equals(b[name].variable), name


@pytest.mark.parametrize("scene", MAP_SCENES)
def test_each_point_is_present_at_the_values_the_store_and_the_tables_record(stores, scene):
    path = stores(scene)
    g = zarr.open_group(path, mode="r")
    ds = reduced_dataset(path)
    axes = [d for d in ds["present"].dims if d not in ("frequency", "family")]
    stored = {(float(g["frequency"][i]), *(_plain(g[a][i]) for a in axes))
              for i in range(g["point"].shape[0])}
    table = reduced(path, ["counters"])["counters"]
    rows = {(float(r["f"]), *(_plain(r[a]) for a in axes)) for _, r in table.iterrows()}
    assert stored == rows == _cells(ds) == _cells(open_study(path))


def _plain(v):
    v = np.asarray(v).item()
    return v if isinstance(v, str) else float(v)


@pytest.mark.parametrize("scene", [s for s in MAP_SCENES if "mu" in tiny_scene(s)] + [REFINED])
def test_an_absent_cell_is_nan_or_empty_in_every_variable_of_both_views(stores, scene):
    path = stores(scene)
    for ds in (reduced_dataset(path), open_study(path, reduced=True)):
        p = ds["present"]
        assert not p.all()  # this layout has cells no point holds
        names = [n for n, v in ds.data_vars.items() if n != "present"
                 and set(v.dims) <= set(p.dims) and v.dims]
        assert len(names) >= 5
        for name in names:
            v = ds[name]
            gone = ~p.any([d for d in p.dims if d not in v.dims])
            vals = v.where(gone, drop=False).values[gone.transpose(*v.dims).values]
            assert ((vals == "") if v.dtype.kind == "U" else np.isnan(vals)).all(), name


def test_mu_of_a_stick_point_is_zero_in_the_store_the_tables_and_the_datasets(stores):
    """The issue's case: a contact x mu map with mu = [0.3] keeps every v value."""
    path = stores(SLIDING)
    g = zarr.open_group(path, mode="r")
    contact = np.array([str(c) for c in g["contact"][...]])
    mu = np.asarray(g["mu"][...])
    assert set(mu[contact == "stick"]) == {0.0} and set(mu[contact == "coulomb"]) == {0.3}
    d = reduced(path, ["diffusion"])["diffusion"]
    assert set(d.loc[d["contact"] == "stick", "mu"]) == {0.0}
    for ds in (open_study(path, reduced=True), reduced_dataset(path)):
        assert list(ds["mu"].values) == [0.0, 0.3]
        assert int(ds["v"].notnull().sum()) == len(d) == int(d["v"].notna().sum())
        assert ds["present"].sel(contact="stick", mu=0.0).all()
        assert not ds["present"].sel(contact="stick", mu=0.3).any()


def test_a_refined_map_leaves_the_cells_it_did_not_add_absent(stores):
    path = stores(REFINED)
    ds = reduced_dataset(path)
    assert list(ds["frequency"].values) == [54.0, 57.0, 60.0]  # 57 Hz added by refinement
    at57 = ds["present"].sel(frequency=57.0, family="rest")
    assert at57.any() and not at57.all()
    assert np.isnan(ds["D"].sel(frequency=57.0).where(~at57, drop=True)).all()
    assert np.isfinite(ds["D"].sel(frequency=57.0).where(at57, drop=True)).any()


def test_a_family_without_a_done_chunk_at_a_point_is_absent_there_and_only_there(stores,
                                                                               tmp_path):
    path = tmp_path / "undone.zarr"
    shutil.copytree(stores(MAP_SCENES[0]), path)  # contact: families rest and launched
    g = zarr.open_group(str(path), mode="r+")
    g["done"][0, 1, :] = False  # the first point's launched chunks
    at = {"frequency": float(g["frequency"][0]), "contact": str(g["contact"][0]),
          "mu": float(g["mu"][0])}
    for ds in (reduced_dataset(path), open_study(path, reduced=True)):
        p = ds["present"].sel(at)
        assert list(p.values) == [True, False]  # rest, launched
        for name, v in ds.data_vars.items():  # every per-family table variable
            if name != "present" and set(v.dims) == set(p.dims) | set(at) and "table" in v.attrs:
                x = v.sel({**at, "family": "launched"}).item()
                assert x == "" if isinstance(x, str) else np.isnan(x), name
        assert np.isfinite(ds["D_family"].sel({**at, "family": "rest"}))
        assert int((~ds["present"]).sum()) == int((~reduced_dataset(
            stores(MAP_SCENES[0]))["present"]).sum()) + 1


def test_the_presence_mask_round_trips_through_netcdf(stores, tmp_path):
    import xarray as xr

    ds = reduced_dataset(stores(SLIDING))
    ds.to_netcdf(tmp_path / "m.nc")
    back = xr.open_dataset(tmp_path / "m.nc")
    assert back["present"].dtype == bool and not back["present"].all()
    assert np.array_equal(back["present"].values, ds["present"].values)
    assert back["present"].attrs["flag_meanings"] == "absent present"


@pytest.mark.parametrize("unstack", [True, False])
def test_a_maps_dask_chunks_are_whole_chunks_of_its_store(stores, unstack):
    """A map opened (masked, unstacked or not): along particle the store's chunks, along
    point (or each axis) whole store chunks."""
    from pipeline.store.study_store import StudyStore

    path = stores(SLIDING)
    acc = StudyStore.open(path).study.accuracy
    ds = open_study(path, unstack=unstack)
    v = ds["positions"]
    assert v.chunks[v.dims.index("particle")] == (acc.chunk_size,) * acc.n_chunks
    assert ds["particle_done"].chunks[-1] == (acc.chunk_size,) * acc.n_chunks
    raw = zarr.open_group(path, mode="r")["positions"]
    assert v.chunks[v.dims.index("time")] == (raw.chunks[-1],) * (raw.shape[-1] // raw.chunks[-1])


def test_the_reduced_netcdf_keeps_every_axis_and_fixed_parameter_as_a_coordinate(stores, tmp_path):
    """The sliding scene's netCDF: its axes (contact, mu) as dimensions, its fixed [params]
    (tilt, throw, read from the scene file itself) and the preset's restitution as scalar
    coordinates with units, read back from the file."""
    import tomllib

    import xarray as xr

    from bbb.params import PRESETS
    from pipeline.workflow.keys import PARAM_UNITS

    from .map_scenes import ROOT

    scene = tomllib.loads((ROOT / SLIDING).read_text())
    path = tmp_path / "sliding.nc"
    reduced_dataset(stores(SLIDING)).to_netcdf(path)
    with xr.open_dataset(path) as nc:
        assert {"frequency", "contact", "mu"} <= set(nc.dims)
        for key in ("tilt", "throw"):
            assert key in nc.coords and nc[key].dims == ()
            assert float(nc[key]) == scene["params"][key]
            assert nc[key].attrs["units"] == PARAM_UNITS[key] == "degree"
        assert float(nc["alpha"]) == PRESETS[scene["params"]["preset"]]["alpha"]
        assert "alpha" not in nc.dims and "tilt" not in nc.data_vars
