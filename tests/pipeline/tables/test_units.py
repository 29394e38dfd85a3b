"""One units map (pipeline.tables.units) for every table: every column of every committed
table has a unit, and the API's xarray attributes carry the very units of the Parquet
metadata; one catalog (pipeline.tables.catalog) gives `bbb reduce` and the API the same tables."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline.api import open_study, reduced
from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.studies.accuracy.study import COLUMN_UNITS as ACCURACY_UNITS
from pipeline.studies.basins.tables import COLUMN_UNITS as BASINS_UNITS
from pipeline.studies.dissipation.cuts import CUT_UNITS
from pipeline.studies.klages2004.finescale import EXTREMA_UNITS
from pipeline.studies.protocol.tables import COLUMN_UNITS as PROTOCOL_UNITS
from pipeline.studies.ratchet.mechanism import REVERSAL_UNITS
from pipeline.studies.ratchet.reversal_states import STATE_UNITS
from pipeline.tables.catalog import TABLES, table_names, tables
from pipeline.tables.reduce import reduce_store, table_metadata
from pipeline.tables.units import D_UNIT, DIMENSIONLESS, UNITS, column_unit, unit
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.observables.registry import own_tables, scene_tables

from ..helpers import TINY

FIGURES = Path(__file__).resolve().parents[3] / "figures"
#: the studies' own columns (accuracy study, the fine-scale extrema, the protocol study, the
#: dissipation study's cuts, the basins study, the ratchet's reversals and states)
STUDY_UNITS = {**ACCURACY_UNITS, **EXTREMA_UNITS, **PROTOCOL_UNITS, **CUT_UNITS, **BASINS_UNITS,
               **REVERSAL_UNITS, **STATE_UNITS}
#: TINY with every observable, so the store has every table (and locking by name); tilt = 0
#: (a conveyor at no tilt: the level floor's motion) adds the transport columns v, D_drift, ...
EVERY = (TINY.replace('name = "tiny"', 'name = "every"')
         .replace('preset = "klages2004"\n', 'preset = "klages2004"\ntilt = 0.0\n', 1)
         .replace("record_from = 2.0\n", "record_from = 2.0\nx_jumps = 20\n")
         + "\n[observables.contact]\n\n[observables.jumps]\n\n[observables.lyapunov]\nparticles = 4\n"
         # and every observable that brings its own table, at its defaults
         + "".join(f"\n[observables.{o.name}]\n" for o in scene_tables()))


def columns_without_unit(paths, extra=STUDY_UNITS) -> dict[str, list[str]]:
    """{file name: its columns the map has no unit for} of the CSV files ``paths``."""
    out = {}
    for path in paths:
        missing = [c for c in pd.read_csv(path, nrows=0).columns if unit(c, extra) is None]
        if missing:
            out[Path(path).name] = missing
    return out


def test_every_column_of_every_committed_table_has_a_unit():
    paths = sorted(FIGURES.glob("*.csv"))
    assert len(paths) >= 20  # the transport and contact studies commit one table per map table
    assert columns_without_unit(paths) == {}


def test_a_column_without_a_unit_is_caught(tmp_path):
    src = FIGURES / "diffusion_figure2.csv"
    df = pd.read_csv(src).assign(fake_column=1.0)
    df.to_csv(tmp_path / "diffusion_figure2.csv", index=False)
    assert columns_without_unit([src, tmp_path / "diffusion_figure2.csv"]) == {
        "diffusion_figure2.csv": ["fake_column"]}
    assert column_unit("fake_column") == "?"  # what the Parquet metadata would say


@pytest.mark.parametrize(("column", "expected"), [
    ("v", "mm/s"), ("v_lo", "mm/s"), ("v_hi", "mm/s"), ("dv_tol", "mm/s"),
    ("D", D_UNIT), ("D_launched_hi", D_UNIT), ("D_inf_coll_lo", D_UNIT), ("D_drift", D_UNIT),
    ("dD", D_UNIT), ("dD_lo", D_UNIT), ("dD_tol", D_UNIT),
    ("Gamma", "1"), ("EB_decay_rest", "1"), ("CV2_D_lo", "1"), ("cv_max", "1"), ("n_moving", "1"),
    ("ln_mem_coll_up_hi", "1"), ("lam_move_tie", "1"), ("lam", "1/s"), ("lam_coll", "1"),
    ("collisions_per_s", "1/s"), ("f_dn", "Hz"), ("tau_coll", "s"), ("v_peak_lo", "mm/s"),
    ("a_lo", "mm/s^2"), ("v_status", ""),
    ("D_status", ""), ("verdict", ""), ("ergodic", ""), ("lam_degenerate", ""), ("family", ""),
])
def test_units_of_columns_and_column_families(column, expected):
    assert column_unit(column) == expected


def test_dimensionless_is_1_and_nothing_reads_as_dimensionless_by_a_blank():
    assert DIMENSIONLESS == "1"
    # "" is only for what is not a quantity: labels, flags, texts
    blank = sorted(c for c, u in UNITS.items() if u == "")
    assert blank == sorted(["family", "initial", "D_status", "ergodic", "families_agree",
                            "eb_ok", "rule", "level_ok", "decay_ok", "spread_ok", "verdict",
                            "stop", "stationary", "v_by", "D_drift_status", "steady",
                            "diffusive", "v_status", "converged", "converged_coll", "still",
                            "contact", "floor"]
                           # the observables' own texts, as each declares them
                           + [c for o in own_tables() for c, _, u, _ in o.columns if u == ""])


@pytest.fixture(scope="module")
def every(tmp_path_factory):
    """A tiny store with every observable, its chunks computed in this process, reduced."""
    study = parse_workflow(EVERY, source="every.toml")
    path = tmp_path_factory.mktemp("every") / "every.zarr"
    store = StudyStore.create_or_open(path, study)
    for fi in range(len(study.frequencies)):
        for mi in range(len(study.families)):
            for ci in range(study.accuracy.n_particles // study.accuracy.chunk_size):
                compute_chunk(store, fi, mi, ci)
    store.consolidate()
    out = tmp_path_factory.mktemp("every_tables")
    names = table_names(study, every=True)
    written = reduce_store(path, out, names=names, echo=lambda s: None)
    return path, out, written


def test_the_catalog_lists_every_table_and_reduce_writes_its_default_ones(every):
    path, _, written = every
    study = StudyStore.open(path).study
    assert table_names(study) == ["counters", "diffusion", "contact", "mechanisms",
                                  *(o.name for o in own_tables())]
    assert table_names(study, every=True) == [t.name for t in TABLES]
    assert list(written) == [t.name for t in TABLES]
    tiny = parse_workflow(TINY, source="tiny.toml")  # positions and collisions only
    assert table_names(tiny) == ["counters", "diffusion"]
    assert table_names(tiny, every=True) == ["counters", "diffusion", "locking"]
    with pytest.raises(ValueError, match="no table 'contact'.*allowed: counters, diffusion, locking"):
        tables(StudyStore.create_or_open(path.parent / "tiny.zarr", tiny), ["contact"])


def test_the_api_gives_the_tables_bbb_reduce_writes(every):
    path, out, written = every
    got = reduced(path, list(written))
    assert list(got) == list(written)
    for name, df in got.items():
        pd.testing.assert_frame_equal(df, pd.read_parquet(out / f"{name}.parquet"), check_exact=True)
    assert list(reduced(path)) == ["counters", "diffusion", "contact", "mechanisms",
                                   *(o.name for o in own_tables())]


def test_the_api_attaches_every_table_with_the_units_of_the_parquet_metadata(every):
    path, out, _ = every
    ds = open_study(path, reduced=True)
    attached = {}
    for name in table_names(StudyStore.open(path).study):
        parquet = table_metadata(out / f"{name}.parquet")["units"]
        assert "?" not in parquet.values(), name
        families = [str(f) for f in ds["family"].values]
        for var in ds.data_vars.values():
            if var.attrs.get("source") == f"bbb reduce: {name} table":
                # a per-family variable (D_family: column D_<family>) stands for each family's
                columns = [var.attrs["column"].replace("<family>", f) for f in families]
                for column in dict.fromkeys(columns):
                    attached[(name, column)] = var.attrs["units"]
                    assert var.attrs["units"] == parquet[column], (name, var.name, column)
        # every column is attached, or left out where an earlier table holds the same values
        index = {"f", "family", "initial"}
        left_out = {c for c in parquet if c not in index and (name, c) not in attached}
        assert left_out <= {"Gamma", "t_max"}, (name, left_out)
    assert {"contact", "mechanisms"} <= {n for n, _ in attached}
    assert ds.held_frac.dims == ("frequency", "family") and ds.D_inf.dims == ("frequency",)
    assert ds.counters_n_particles.dims == ("frequency", "family")  # per family, not pooled
    assert np.array_equal(ds.counters_n_particles.sum("family").values, ds.n_particles.values)
    assert ds.D.attrs["units"] == "mm^2/s" and ds.dD.attrs["units"] == "mm^2/s"
    assert ds.v.attrs["units"] == ds.v_lo.attrs["units"] == "mm/s"  # was "" in xarray
