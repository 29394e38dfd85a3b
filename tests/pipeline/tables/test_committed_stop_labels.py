"""The committed tables' ``stop`` columns use only the stop labels the store's legend defines
(pipeline.store.layout.STOP_LEGEND): a label renamed in the code is renamed in the tables."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pipeline.store.layout import STOP_LEGEND

ROOT = Path(__file__).resolve().parents[3]


def labels(cell: str) -> list[str]:
    """The labels of one stop cell: "target met", or "rest: target met; launched: cap"."""
    return [part.split(": ", 1)[-1].strip() for part in cell.split(";") if part.strip()]


def stop_cells() -> dict[str, set[str]]:
    """{committed table: the labels its stop columns hold}."""
    found = {}
    for path in sorted((ROOT / "figures").glob("*.csv")):
        table = pd.read_csv(path, dtype=str, keep_default_na=False)
        cols = [c for c in table if c == "stop" or c.startswith("stop_")]
        if cols:
            found[path.name] = {lab for c in cols for cell in table[c] if cell for lab in labels(cell)}
    return found


def test_the_committed_tables_stop_columns_hold_only_the_legends_labels():
    found = stop_cells()
    assert len(found) >= 5  # Fig. 2, its Mátyás–Klages companion, the maps, the cuts, contact
    stray = {name: sorted(labs - set(STOP_LEGEND.values())) for name, labs in found.items()}
    assert not any(stray.values()), stray
