"""Reducing a store to tables: D(f) with CIs, ergodicity columns, counters."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.reduce import default_out_dir, reduce_store
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY

REQUIRED = ["f", "D", "D_lo", "D_hi", "D_last", "n_particles", "t_max", "ergodic", "EB",
            "D_rest", "D_launched"]


@pytest.fixture(scope="module")
def tables(reference, tmp_path_factory):
    out = tmp_path_factory.mktemp("tables")
    reduce_store(reference[0], out, echo=lambda s: None)
    return out


def test_diffusion_table_has_the_required_columns(tables):
    df = pd.read_parquet(tables / "diffusion.parquet")
    assert set(REQUIRED) <= set(df.columns)
    assert list(df["f"]) == [54.0, 60.0] and (df["n_particles"] == 16).all()


def test_d_is_finite_and_positive_where_particles_move(tables):
    df = pd.read_parquet(tables / "diffusion.parquet")
    moving = df["n_moving"] > 0
    assert moving.all()  # Γ > 1 at both frequencies: particles lift off and move
    for col in ("D", "D_lo", "D_hi", "D_last", "EB"):
        assert np.isfinite(df.loc[moving, col]).all(), col
    assert (df.loc[moving, "D"] > 0).all()
    assert (df["D_lo"] <= df["D"]).all() and (df["D"] <= df["D_hi"]).all()


def _plain_msd_D(x: np.ndarray, dt: float, discard: float, fit_from: float, fit_to: float
                 ) -> float:
    """D, mm²/s, written out here without bbb.analysis.stats: drop the first ``discard`` of the run,
    average (x(t + Δ) - x(t))² over particles and time origins, fit a line to it over the
    lags fit_from <= Δ <= fit_to (fractions of the analysed duration) and halve the slope."""
    x = x[:, int(round(discard * (x.shape[1] - 1))):]
    T = (x.shape[1] - 1) * dt
    lags = [k for k in range(1, x.shape[1]) if fit_from * T - 1e-9 <= k * dt <= fit_to * T + 1e-9]
    msd = [np.mean((x[:, k:] - x[:, :-k]) ** 2) for k in lags]
    return np.polyfit(np.asarray(lags) * dt, msd, 1)[0] / 2


def test_d_agrees_with_a_plain_msd_slope_of_the_raw_store_positions(reference, tables):
    import zarr

    g = zarr.open_group(str(reference[0]), mode="r")
    x = np.asarray(g["positions"][...])  # (frequency, family, particle, time), all done
    an = parse_workflow(TINY, source="tiny.toml").analysis
    df = pd.read_parquet(tables / "diffusion.parquet")
    for fi in range(x.shape[0]):
        pooled = x[fi].reshape(-1, x.shape[-1])  # both families
        d = _plain_msd_D(pooled, 0.5, an.discard, an.fit_from, an.fit_to)
        row = df.iloc[fi]
        assert row["D_lo"] <= d <= row["D_hi"]
        assert d == pytest.approx(row["D"], rel=1e-9)  # the same estimator, to rounding


def test_parquet_tables_carry_units_and_the_store_provenance(reference, tables):
    import pyarrow.parquet as pq

    from bbb.provenance import kernel_hash
    from pipeline.store.study_store import StudyStore, package_version
    from pipeline.tables.reduce import table_metadata

    attrs = StudyStore.open(reference[0]).attrs()
    for name in ("diffusion", "counters"):
        meta = table_metadata(tables / f"{name}.parquet")
        assert meta["store_fingerprint"] == attrs["fingerprint"] and meta["table"] == name
        assert meta["kernel_hash"] == kernel_hash() and meta["bbb_version"] == package_version()
        schema = pq.read_schema(tables / f"{name}.parquet")
        assert set(meta["units"]) == set(schema.names)
        assert all(schema.field(c).metadata[b"unit"].decode() == u for c, u in meta["units"].items())
    units = table_metadata(tables / "diffusion.parquet")["units"]
    assert (units["f"], units["D"], units["D_rest_lo"], units["fit_to"], units["EB"]) == (
        "Hz", "mm^2/s", "mm^2/s", "s", "1")
    assert table_metadata(tables / "counters.parquet")["units"]["collisions_per_s"] == "1/s"


def test_every_csv_has_a_units_sidecar_naming_its_columns_in_order_with_the_parquet_units(tables):
    """<table>.csv-metadata.json (CSVW): one entry per column of the CSV as pandas reads it,
    in its order, each unit the one the Parquet field carries; the CSV itself stays a plain
    table (its first line the header)."""
    import json

    import pyarrow.parquet as pq

    from pipeline.tables.reduce import csv_units

    csvs = sorted(tables.glob("*.csv"))
    assert {p.stem for p in csvs} == {p.stem for p in tables.glob("*.parquet")}
    for csv in csvs:
        meta = json.loads((tables / f"{csv.name}-metadata.json").read_text(encoding="utf-8"))
        assert meta["@context"] == "http://www.w3.org/ns/csvw" and meta["url"] == csv.name
        header = list(pd.read_csv(csv).columns)
        assert [c["name"] for c in meta["tableSchema"]["columns"]] == header
        schema = pq.read_schema(tables / f"{csv.stem}.parquet")
        assert csv_units(csv) == {c: schema.field(c).metadata[b"unit"].decode() for c in header}
    units = csv_units(tables / "diffusion.csv")
    assert (units["f"], units["D"], units["D_lo"], units["EB"]) == ("Hz", "mm^2/s", "mm^2/s", "1")


def test_csv_holds_the_same_table_as_parquet(tables):
    pq = pd.read_parquet(tables / "diffusion.parquet")
    csv = pd.read_csv(tables / "diffusion.csv")
    flags = {c: bool for c in ("ergodic", "families_agree", "eb_ok", "level_ok", "decay_ok",
                                  "spread_ok", "stationary")}
    pd.testing.assert_frame_equal(pq.astype(flags), csv, check_exact=False, rtol=1e-12)


def test_half_run_d_is_the_fit_of_each_half_of_the_analysed_run(reference, tables):
    # independent of bbb.analysis.stationarity: bbb.analysis.stats' own fit on each half, cut here by hand
    from bbb.analysis.stats import diffusion_coefficient

    df = pd.read_parquet(tables / "diffusion.parquet")
    store = StudyStore.open(reference[0])
    study, done = store.study, store.done()
    times = study.sample_times()
    start = int(np.flatnonzero(times >= study.analysis.discard * times[-1] - 1e-9)[0])
    half = (times.size - start) // 2
    for fi in range(len(study.frequencies)):
        x = np.concatenate([store.read_done("positions", fi, mi, done[fi, mi])
                            for mi in range(len(study.families))])
        for k, a in enumerate((start, start + half)):
            sl = slice(a, a + half)
            d = diffusion_coefficient(x[:, sl], times[sl], discard=0.0).D  # fit 5-25 % of T/2
            assert df[f"D_half{k + 1}"].iloc[fi] == pytest.approx(d, rel=1e-9)
    assert (df["dD_lo"] <= df["dD"]).all() and (df["dD"] <= df["dD_hi"]).all()
    assert df["dD"].to_numpy() == pytest.approx((df["D_half2"] - df["D_half1"]).to_numpy())
    assert df["stationary"].notna().all()


def test_reduction_is_deterministic(reference, tables, tmp_path):
    reduce_store(reference[0], tmp_path, echo=lambda s: None)
    pd.testing.assert_frame_equal(pd.read_parquet(tables / "diffusion.parquet"),
                                  pd.read_parquet(tmp_path / "diffusion.parquet"))


def test_counters_table_has_a_row_per_frequency_and_family(tables):
    df = pd.read_csv(tables / "counters.csv")
    assert len(df) == 4 and set(df["family"]) == {"rest", "launched"}
    assert (df["collisions_per_s"] > 0).all() and (df["anomalies_per_s"] == 0).all()


def test_default_output_goes_beside_the_store():
    study = parse_workflow(TINY, source="tiny.toml")
    assert default_out_dir("runs/tiny.zarr", study) == "runs/tiny"


def test_partial_store_reduces_only_done_chunks(tmp_path):
    study = parse_workflow(TINY, source="tiny.toml")
    store = StudyStore.create_or_open(tmp_path / "p.zarr", study)
    for fi in range(2):
        for mi in range(2):
            compute_chunk(store, fi, mi, 0)
    df = reduce_store(store.path, tmp_path / "out", echo=lambda s: None)["diffusion"]
    assert (df["n_particles"] == 8).all()  # 2 families x 1 done chunk of 4


def test_collisions_only_store_gets_counters_but_no_diffusion_table(tmp_path):
    text = TINY.replace("[observables.positions]\n", "")
    study = parse_workflow(text, source="coll.toml")
    store = StudyStore.create_or_open(tmp_path / "c.zarr", study)
    compute_chunk(store, 0, 0, 0)
    tables = reduce_store(store.path, tmp_path / "out", echo=lambda s: None)
    assert set(tables) == {"counters"} and not (tmp_path / "out" / "diffusion.csv").exists()
    assert (tmp_path / "out" / "counters.parquet").exists()


def _damaged_copy(reference_store, tmp_path, *, done: bool):
    """A copy of the reference store whose positions chunk (60 Hz, launched, chunk 0) holds
    bytes no codec can decode, marked done or not."""
    import shutil

    import zarr

    store = tmp_path / "damaged.zarr"
    shutil.copytree(reference_store, store)
    chunk = store / "positions" / "c" / "1" / "1" / "0" / "0"
    assert chunk.is_file()
    chunk.write_bytes(b"not a zstd frame")
    zarr.open_group(str(store), mode="r+")["done"][1, 1, 0] = done
    return store


def test_a_damaged_chunk_not_marked_done_is_never_read(reference, tmp_path):
    """An interrupted run may leave a torn chunk behind; reduce reads only done chunks."""
    store = _damaged_copy(reference[0], tmp_path, done=False)
    df = reduce_store(store, tmp_path / "out", echo=lambda s: None)["diffusion"]
    ref = reduce_store(reference[0], tmp_path / "ref", echo=lambda s: None)["diffusion"]
    assert list(df["n_particles"]) == [16, 12]  # 60 Hz lost the 4 particles of that chunk
    assert df.loc[0, "D"] == ref.loc[0, "D"]     # 54 Hz untouched


def test_a_damaged_done_chunk_is_named_in_one_line(reference, tmp_path, capsys):
    from pipeline.cli import main

    store = _damaged_copy(reference[0], tmp_path, done=True)
    assert main(["reduce", str(store), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "positions[f = 60 Hz, family launched, chunk 0] is damaged: unreadable" in err
    assert "run `bbb run`" in err and "Traceback" not in err and "\n" not in err


def test_task_seconds_sum_the_done_chunks_only(tmp_path):
    from pipeline.tables.counters import counters_table

    from ..store.test_study_store import fake_chunk

    study = parse_workflow(TINY.replace("n_particles = 8", "n_particles = 20"), source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "g.zarr", study)
    for ci, s in ((1, 0.5), (3, 2.0), (4, 8.0)):  # chunks 0 and 2 not done, 2 with seconds
        store.write_chunk(0, 0, ci, fake_chunk(study, 1.0), s)
    store.write_chunk(0, 0, 2, fake_chunk(study, 1.0), 100.0, mark_done=False)
    t = counters_table(store, store.done())
    assert t.task_seconds.tolist() == [10.5, 0.0, 0.0, 0.0]


def test_the_ci_columns_say_what_their_interval_means_with_units(tables):
    df = pd.read_parquet(tables / "diffusion.parquet")
    from pipeline.tables.reduce import table_metadata

    units = table_metadata(tables / "diffusion.parquet")["units"]
    assert (units["D_status"], units["D_cover"], units["mover_share_hi"], units["CV2_D"],
            units["CV2_D_lo"], units["CV_D"]) == ("", "1", "1", "1", "1", "1")
    ok = df["D_status"] == "ok"
    assert (df.loc[ok, "D_cover"] == 0.95).all()
    # at 54 Hz two of 16 particles carry D: the rare-mover rule and its calibrated coverage
    rare = df[df["D_status"].str.contains("rare movers")]
    assert list(rare["f"]) == [54.0] and (rare["D_cover"] < 0.95).all()
    assert all(f"coverage {c:.2f}" in t for c, t in zip(rare["D_cover"], rare["D_status"],
                                                         strict=True))
    # CV² is the signed 2 EB - EB(T/2) (EB_decay = EB(T/2)/EB), CV its root only where > 0
    assert np.allclose(df["CV2_D"], df["EB"] * (2 - df["EB_decay"]), rtol=1e-9)
    pos = df["CV2_D"] > 0
    assert np.allclose(df.loc[pos, "CV_D"], np.sqrt(df.loc[pos, "CV2_D"]))
    assert df.loc[~pos, "CV_D"].isna().all()
    assert (df["CV2_D_lo"] <= df["CV2_D"]).all() and (df["CV2_D"] <= df["CV2_D_hi"]).all()


def test_an_estimator_failure_is_not_put_in_the_value_columns():
    # D significantly below 0 (particles settling in the fit window): NaN in D, D_lo, D_hi,
    # the fit's numbers only in D_status, so no figure or claim reads them as a value
    from bbb.analysis.stats.bootstrap import bootstrap_mean_unchecked as _bootstrap_mean
    from bbb.analysis.stats.interval import d_interval
    from pipeline.tables.diffusion import _d_columns, _status_text

    d = -7.4e-6 + 5e-6 * np.random.default_rng(0).standard_normal(128)
    r = d_interval(d, _bootstrap_mean(d, 400, 0.95, np.random.default_rng(1), "percentile"), 0.95)
    cols = _d_columns("D", r)
    assert set(cols) == {"D", "D_lo", "D_hi"} and all(np.isnan(v) for v in cols.values())
    text = _status_text(r, {"rest": r})
    assert text.startswith("estimator failed: fit D = -7") and "mm²/s < 0" in text
    ok = d_interval(-d, _bootstrap_mean(-d, 400, 0.95, np.random.default_rng(1), "percentile"),
                    0.95)
    assert _status_text(ok, {"a": ok, "b": r}) == f"b: {r.note()}"
