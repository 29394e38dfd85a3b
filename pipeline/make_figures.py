"""``python -m pipeline.make_figures [--fast]``: every figure and figures/REPORT.md.

The entry point over the studies (as ``pipeline.cli`` is over engine and studies); the work is
done by :mod:`pipeline.studies.klages2004.make_figures`, which runs the paper's scenes, reduces
them, draws the figures and writes the report.
"""

from __future__ import annotations

from .studies.klages2004.make_figures import SCENES, main, make_figures, run_log_entry

__all__ = ["SCENES", "main", "make_figures", "run_log_entry"]

if __name__ == "__main__":
    raise SystemExit(main())
