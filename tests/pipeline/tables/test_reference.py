"""docs/tables.md (pipeline.tables.reference): generated from the one units map, and complete --
every column any table of bbb reduce writes has a row with a unit and a meaning."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.catalog import TABLES, table_names, tables
from pipeline.tables.reference import DOC, reference_markdown
from pipeline.tables.units import TABLE_COLUMNS, describe, row_unit
from pipeline.workflow.load import parse_workflow

from .test_units import EVERY

FIGURES = Path(__file__).resolve().parents[3] / "figures"
NAMES = tuple(t.name for t in TABLES)


def without_row(columns_by_table: dict[str, list[str]]) -> dict[str, list[str]]:
    """{table: its columns that have no row in TABLE_COLUMNS}, tables with none left out."""
    out = {}
    for table, columns in columns_by_table.items():
        missing = [c for c in columns if describe(table, c) is None]
        if missing:
            out[table] = missing
    return out


@pytest.fixture(scope="module")
def every_table(tmp_path_factory) -> dict[str, list[str]]:
    """The columns of every table (locking too) of a real store with every observable, on a
    tilted floor (the transport columns) -- simulated chunk by chunk.  (Grid axes: the
    committed tables of the map scenes.)"""
    study = parse_workflow(EVERY.replace("tilt = 0.0", "tilt = 2.0"), source="every.toml")
    store = StudyStore.create_or_open(tmp_path_factory.mktemp("ref") / "every.zarr", study)
    for fi in range(len(study.points)):
        for mi in range(len(study.families)):
            for ci in range(study.accuracy.n_chunks):
                compute_chunk(store, fi, mi, ci)
    made = tables(store, table_names(study, every=True))
    assert set(made) == set(NAMES)
    return {name: list(df.columns) for name, df in made.items()}


def committed_tables() -> dict[str, list[str]]:
    """{table: the columns of every committed figures/*.csv written by bbb reduce}: files
    named ``<study>_<table>.csv`` or ``diffusion_<study>.csv``."""
    out: dict[str, list[str]] = {}
    for path in sorted(FIGURES.glob("*.csv")):
        table = next((t for t in NAMES if path.stem.endswith(f"_{t}")),
                     "diffusion" if path.stem.startswith("diffusion_") else None)
        if table is not None:
            out.setdefault(table, []).extend(pd.read_csv(path, nrows=0).columns)
    return out


def test_docs_tables_md_is_the_generated_reference():
    assert DOC.read_text(encoding="utf-8") == reference_markdown()


def test_every_column_of_every_table_of_a_real_store_has_a_row(every_table):
    assert without_row(every_table) == {}


def test_every_column_of_every_committed_reduce_table_has_a_row():
    found = committed_tables()
    assert {"counters", "diffusion", "contact", "locking", "mechanisms"} <= set(found)
    assert "stop" in found["diffusion"]  # target-driven stores' column, absent from EVERY
    assert without_row(found) == {}


def test_a_column_without_a_row_is_caught(every_table):
    columns = {**every_table, "diffusion": [*every_table["diffusion"], "fake_column"]}
    assert without_row(columns) == {"diffusion": ["fake_column"]}
    assert without_row({"counters": ["f", "collisions_per_s", "D"]}) == {"counters": ["D"]}


def test_every_row_has_a_unit():
    missing = [(t, name) for t, rows in TABLE_COLUMNS.items() for name, _, _ in rows
               if name != "<axis>" and row_unit(name) is None]
    assert missing == []


def test_an_exact_row_wins_over_a_pattern():
    # D_drift is its own row, not the family pattern D_<family>
    assert describe("diffusion", "D_drift_lo").startswith("tilted or thrown floors")
    assert describe("diffusion", "D_rest_hi").startswith("D of one family")
    assert describe("locking", "t_max") != describe("counters", "t_max")
