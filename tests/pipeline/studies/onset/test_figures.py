"""The onset figure from synthetic maps with known onsets: every line's onset read where it
was put, a line without an onset kept as NaN (never a value), and real PNG and PDF files."""

from __future__ import annotations

import math

from pipeline.studies.onset.cases import onset_table
from pipeline.studies.onset.figures import draw, onset_rows


def test_each_lines_onset_is_read_where_the_synthetic_map_puts_it_and_a_missing_one_stays_nan():
    t = onset_table("R", {(0.7, 1.05): 60.0, (0.7, 15.0): 58.0, (0.9, 15.0): math.nan})
    rows = onset_rows(t, "onset_map").set_index(["alpha", "R"])
    assert rows.loc[(0.7, 1.05), "onset"] == 60.0 and rows.loc[(0.7, 15.0), "onset"] == 58.0
    assert rows.loc[(0.7, 15.0), "onset_lo"] == 57.5 and rows.loc[(0.7, 15.0), "onset_hi"] == 58.5
    assert math.isnan(rows.loc[(0.9, 15.0), "onset"])


def test_the_figure_is_drawn_as_png_and_pdf(tmp_path):
    tables = {"onset_map_diffusion": onset_table("R", {(0.7, 1.05): 60.0, (0.9, 15.0): 53.0}),
              "onset_sine_diffusion": onset_table("depth", {(0.7, 0.3): 58.0})}
    paths = draw(tables, {}, tmp_path)
    assert sorted(p.suffix for p in paths) == [".pdf", ".png"]
    assert all(p.is_file() and p.stat().st_size > 1000 for p in paths)
    assert draw({}, {}, tmp_path / "none") == []
