"""``bbb reduce``: a study store's tables (:mod:`pipeline.tables.catalog`) written beside it
as Parquet and CSV, and read back.

``counters.parquet`` / ``.csv`` (every store), ``diffusion`` (stores with positions: D(f)
with CIs, ergodicity, stationarity, transport on a conveyor), ``contact`` (stores with
``[observables.contact]``), ``mechanisms`` (stores with jumps or lyapunov); the columns of
each in its module (:mod:`pipeline.tables.counters`, :mod:`~pipeline.tables.diffusion`,
:mod:`~pipeline.tables.contact`, :mod:`~pipeline.tables.mechanisms`).

Every Parquet table carries its provenance in the schema metadata under the key ``bbb``
(a JSON object: ``units`` per column, ``store_fingerprint``, ``kernel_hash``,
``bbb_version`` of the reducing package and of the store, ``study``, ``table``), and each
column its unit as field metadata ``unit``, from the one map :mod:`pipeline.tables.units`
("1": dimensionless, "": not a quantity, such as a label or flag).  :func:`table_metadata`
reads them back.  The Parquet copies need pyarrow (``pip install 'bbb[parquet]'``, not in
the default install: 176 MB); without it the CSV tables are written alone and one line says
what is missing.

Every CSV has its units in a sidecar beside it, ``<table>.csv-metadata.json``: W3C CSV on the
Web metadata (the file name CSVW tools look for by default), one entry per column in the
CSV's order with its ``name``, ``datatype`` and unit as ``schema:unitText`` (the same strings
as the Parquet metadata), the study and store in ``dc:title`` and ``dc:source``;
:func:`csv_units` reads it back.  A sidecar rather than a header line: every reader of
these CSVs (``pd.read_csv`` in users' scripts, in the studies and the claims, spreadsheets)
reads the first line as the column names, and a unit line there would break each of them.
"""

from __future__ import annotations

import json
import os
import sys
from collections.abc import Callable, Iterable
from pathlib import Path

import pandas as pd

from ..store.layout import OPEN
from ..store.study_store import StudyStore, package_version
from ..workflow.study import Study
from .catalog import tables
from .notes import reduce_notes
from .units import column_unit, units

__all__ = ["reduce_store", "default_out_dir", "column_unit", "table_metadata", "write_table",
           "write_csv_table", "csv_units", "CSVW_SUFFIX", "has_parquet", "NO_PARQUET"]

#: the sidecar of ``<table>.csv``: ``<table>.csv-metadata.json`` (CSVW's default location)
CSVW_SUFFIX = "-metadata.json"

#: the one line a reduce without pyarrow prints (stderr)
NO_PARQUET = ("Parquet tables not written (they carry each column's unit and the store's "
              "provenance): pyarrow is not installed -- pip install 'bbb[parquet]'; the CSV "
              "tables are written")


def has_parquet() -> bool:
    """Whether pyarrow, which writes the Parquet tables, is installed (not imported here)."""
    import importlib.util

    return importlib.util.find_spec("pyarrow") is not None


def default_out_dir(store_path: str, study: Study) -> str:
    """Beside the store: ``runs/smoke.zarr`` -> ``runs/smoke``."""
    if "://" in store_path:
        return study.name
    p = Path(store_path.rstrip("/"))
    return str(p.with_suffix("") if p.suffix == ".zarr" else p.parent / f"{p.name}.tables")


def reduce_store(store_path: str | os.PathLike | StudyStore,
                 out_dir: str | os.PathLike | None = None,
                 *, names: Iterable[str] | None = None,
                 echo: Callable[[str], None] = print,
                 warn: Callable[[str], None] | None = None) -> dict[str, pd.DataFrame]:
    """Write the tables of one store (``names``, default: those of
    :func:`pipeline.tables.catalog.table_names`) to ``out_dir`` (default: beside the store);
    returns them.  A StudyStore may carry other reduce settings than the stored ones
    (`bbb reduce --workflow`).  ``warn`` (default: stderr) gets one line per kind of D that
    must not be read as a value (:mod:`pipeline.tables.notes`: failed estimators, D with the
    drift included)."""
    store = store_path if isinstance(store_path, StudyStore) else StudyStore.open(store_path)
    study = store.study
    out = Path(out_dir if out_dir is not None else default_out_dir(store.path, study))
    out.mkdir(parents=True, exist_ok=True)
    done = store.done()
    stops = store.stops()
    if not done.all() and not (stops is not None and (stops[1] != OPEN).all()):
        echo(f"{study.name}: {int((~done).sum())} of {done.size} chunks not done; "
             "reducing the done ones (re-run `bbb run` to finish)")
    made = tables(store, names, done)
    provenance = _provenance(store)
    parquet = has_parquet()
    for name, df in made.items():
        if parquet:
            write_table(df, out / f"{name}.parquet", {**provenance, "table": name})
        write_csv_table(df, out / f"{name}.csv", {**provenance, "table": name})
    kinds = ".parquet/.csv" if parquet else ".csv"
    echo(f"{study.name}: wrote {', '.join(f'{n}{kinds}' for n in made)} to {out} "
         "(units: " + ("the Parquet metadata, " if parquet else "") + "<table>.csv-metadata.json)")
    if not parquet and made:
        (warn or _stderr)(NO_PARQUET)
    if "diffusion" in made:
        for line in reduce_notes(study.name, made["diffusion"]):
            (warn or _stderr)(line)
    return made


def _stderr(line: str) -> None:
    print(line, file=sys.stderr)


def write_table(df: pd.DataFrame, path: str | os.PathLike, provenance: dict) -> None:
    """``df`` as Parquet with per-column units (:mod:`pipeline.tables.units`) and
    ``provenance`` (plus the units) as the schema metadata ``bbb`` (JSON); needs pyarrow
    (:func:`has_parquet`)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pandas(df, preserve_index=False)
    col_units = units(df.columns)
    schema = pa.schema([f.with_metadata({"unit": col_units[f.name]}) for f in table.schema],
                       metadata={**(table.schema.metadata or {}),
                                 b"bbb": json.dumps({**provenance, "units": col_units}).encode()})
    pq.write_table(table.cast(schema), path)


def write_csv_table(df: pd.DataFrame, path: str | os.PathLike, provenance: dict) -> None:
    """``df`` as CSV at ``path`` and its CSVW sidecar ``path`` + :data:`CSVW_SUFFIX`: every
    column's name, datatype and unit (:mod:`pipeline.tables.units`) in the CSV's order."""
    path = Path(path)
    df.to_csv(path, index=False)
    col_units = units(df.columns)
    meta = {
        "@context": "http://www.w3.org/ns/csvw",
        "url": path.name,
        "dc:title": f"bbb reduce: {provenance.get('table', path.stem)} table of study "
                    f"{provenance.get('study')}",
        "dc:source": f"store fingerprint {provenance.get('store_fingerprint')}, kernel "
                     f"{provenance.get('kernel_hash')}, bbb {provenance.get('bbb_version')}",
        "tableSchema": {"columns": [
            {"name": str(c), "titles": str(c), "datatype": _csvw_datatype(df[c]),
             "schema:unitText": col_units[c]} for c in df.columns]},
    }
    Path(f"{path}{CSVW_SUFFIX}").write_text(json.dumps(meta, indent=1, ensure_ascii=False) + "\n",
                                            encoding="utf-8")


def _csvw_datatype(col: pd.Series) -> str | dict:
    """The CSVW datatype of a column as pandas writes it: numbers, True/False, text."""
    values = col.dropna()
    if pd.api.types.is_bool_dtype(col) or (len(values) and values.map(type).eq(bool).all()):
        return {"base": "boolean", "format": "True|False"}  # flags: True, False, or blank
    if pd.api.types.is_integer_dtype(col):
        return "integer"
    if pd.api.types.is_float_dtype(col):
        return "double"
    return "string"


def csv_units(path: str | os.PathLike) -> dict[str, str]:
    """{column: unit} of a CSV ``bbb reduce`` wrote, from its sidecar
    ``<table>.csv-metadata.json`` (FileNotFoundError naming the sidecar if it has none)."""
    sidecar = Path(f"{path}{CSVW_SUFFIX}")
    meta = json.loads(sidecar.read_text(encoding="utf-8"))
    return {c["name"]: c["schema:unitText"] for c in meta["tableSchema"]["columns"]}


def table_metadata(path: str | os.PathLike) -> dict:
    """The ``bbb`` metadata of a reduced Parquet table (units, fingerprint, versions); needs
    pyarrow."""
    import pyarrow.parquet as pq

    meta = pq.read_schema(path).metadata or {}
    return json.loads(meta[b"bbb"]) if b"bbb" in meta else {}


def _provenance(store: StudyStore) -> dict:
    attrs = store.attrs()
    return {"study": store.study.name, "store_fingerprint": attrs.get("fingerprint"),
            "kernel_hash": attrs.get("kernel_hash"), "store_bbb_version": attrs.get("bbb_version"),
            "bbb_version": package_version()}
