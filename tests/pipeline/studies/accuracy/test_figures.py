"""The accuracy study's figure (pipeline.studies.accuracy.figures): the committed summary
draws with no text over text."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pipeline.studies.accuracy.figures import accuracy_figure

from ...text_overlap import overlaps

ROOT = Path(__file__).resolve().parents[4]


def test_accuracy_plot_of_the_committed_summary_has_no_text_over_text():
    summary = pd.read_csv(ROOT / "figures" / "accuracy_summary.csv")
    assert overlaps(accuracy_figure(summary)) == []
