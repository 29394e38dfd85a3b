"""Compare, at full precision, each line of a map store's tables with the tables of the store
of the scene without a grid that the line replaces.

    python -m benchmarks.bits.compare_map_stores [--runs runs]

For the transport and contact studies' map scenes (``transport``, ``transport_sliding``,
``contact``, ``contact_proj``): every table ``bbb reduce`` makes of the map store (and the
locking table of a store with collisions), sliced at each line (pipeline.studies.map_lines),
against the same table of ``<runs>/<old scene>.zarr`` (the per-scene stores, when present).
Prints one line per (line, table): identical (bit for bit, every column but the timing ones),
or the columns that differ.  The committed CSVs round to six digits; this compares the
numbers themselves.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pipeline.store.study_store import StudyStore
from pipeline.studies.contact.claims import LINES as CONTACT_LINES
from pipeline.studies.map_lines import line_table
from pipeline.studies.transport.claims import LINES as TRANSPORT_LINES
from pipeline.studies.transport.claims import SLIDING
from pipeline.tables.catalog import tables
from pipeline.tables.collisions import locking_table

#: columns that hold wall times (not reproducible)
TIMING = ("task_seconds",)
#: {map scene: {old scene: its line}}
MAPS = {
    "transport": {s: v for s, v in TRANSPORT_LINES.items()
                  if s not in {x for x, _, _ in SLIDING}},
    "transport_sliding": {s: TRANSPORT_LINES[s] for s, _, _ in SLIDING},
    "contact": {f"contact_{m}": v for m, v in CONTACT_LINES.items()},
    "contact_proj": {f"contact_proj_{m}": v for m, v in CONTACT_LINES.items()},
}


def _tables(path: Path) -> dict[str, pd.DataFrame]:
    st = StudyStore.open(str(path))
    out = tables(st)
    if st.study.observables.collisions:
        out["locking"] = locking_table(st)
    return out


def _differ(a: pd.DataFrame, b: pd.DataFrame) -> str:
    if list(a.columns) != list(b.columns):
        return f"columns {list(a.columns)} -> {list(b.columns)}"
    if len(a) != len(b):
        return f"rows {len(a)} -> {len(b)}"
    diffs, timing = [], []
    for c in a.columns:
        if a[c].dtype != b[c].dtype:
            diffs.append(f"{c} (dtype {a[c].dtype} -> {b[c].dtype})")
            continue
        x, y = a[c].to_numpy(), b[c].to_numpy()
        if np.issubdtype(x.dtype, np.floating):  # bit for bit, NaN where NaN
            same = (x.view(np.uint64) == y.view(np.uint64)) | (np.isnan(x) & np.isnan(y))
        else:  # integers, strings, nullable booleans: equal, or missing in both
            na_a, na_b = a[c].isna().to_numpy(), b[c].isna().to_numpy()
            eq = (a[c].astype(object).where(~na_a, None).to_numpy()
                  == b[c].astype(object).where(~na_b, None).to_numpy())
            same = (na_a & na_b) | (~na_a & ~na_b & eq.astype(bool))
        if not same.all():
            (timing if c in TIMING else diffs).append(f"{c} ({int((~same).sum())} cells)")
    if diffs:
        return "differ: " + ", ".join(diffs) + (f"; timing: {', '.join(timing)}" if timing else "")
    return "identical" + (f" (timing only: {', '.join(timing)})" if timing else "")


def compare(runs: Path) -> list[str]:
    out = []
    for scene, lines in MAPS.items():
        path = runs / f"{scene}.zarr"
        if not path.exists():
            out.append(f"{scene}: no map store in {runs}")
            continue
        maps = _tables(path)
        for old, values in lines.items():
            label = ", ".join(f"{a} = {v}" for a, v in values.items())
            old_path = runs / f"{old}.zarr"
            if not old_path.exists():
                out.append(f"{scene} [{label}]: no store {old_path.name} (a new line)")
                continue
            before = _tables(old_path)
            for name, t in maps.items():
                sliced = line_table(t, values)
                if name not in before:
                    out.append(f"{scene} [{label}] {name}: not made by {old}")
                    continue
                out.append(f"{scene} [{label}] {name} vs {old} ({len(sliced)} rows): "
                           f"{_differ(before[name], sliced)}")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", default="runs", help="folder of the stores (default runs)")
    args = ap.parse_args(argv)
    for line in compare(Path(args.runs)):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
