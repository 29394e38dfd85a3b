"""Which scenes the paper's study runs and which further studies its figure run draws: the
lowest module of the study, read by make_figures, committed and run_times alike."""

from __future__ import annotations

__all__ = ["SCENES", "EXTRA_STUDIES"]

#: the scenes this study runs, in order
SCENES = ("figure2", "ergodicity", "figure3", "locking", "figure2_matyas2004",
          "locking_matyas2004", "finescale")
#: further studies drawn in the same run (modules under pipeline.studies exposing SCENES,
#: draw(tables, stores, out_dir) -> paths, and report_lines(tables) -> REPORT.md lines)
EXTRA_STUDIES = ("mechanisms", "transport", "contact", "protocol", "dissipation")
