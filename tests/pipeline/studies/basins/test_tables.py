"""The basins study's tables as files: a run shorter than every time of PEAK_TIMES (a draft)
gives an empty peak table that keeps its columns, so its CSV reads back."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.studies.basins.tables import PEAK_COLUMNS, PEAK_TIMES, peak_table


def test_a_peak_table_without_a_run_long_enough_keeps_its_columns_and_reads_back(tmp_path):
    short = min(PEAK_TIMES) / 2
    dmix = pd.DataFrame({"family": ["dropped"] * 2, "f": [50.0, 52.0], "T": [short] * 2,
                         "D_mix": [1.0, 2.0]})
    table = peak_table(dmix, {}, np.array([0.0, short]), 0.95)
    assert table.empty and list(table.columns) == PEAK_COLUMNS
    table.to_csv(tmp_path / "basins_peak.csv", index=False)
    assert list(pd.read_csv(tmp_path / "basins_peak.csv").columns) == PEAK_COLUMNS
