"""The house style of every study's figures: the engine's, :mod:`pipeline.plot.style` (rc
settings for a journal column or the page width, the families' colours, figures made outside
pyplot that save as ``<name>.png`` and ``<name>.pdf``), imported here so the studies keep
reading it from one place.
"""

from __future__ import annotations

from pipeline.plot.style import (
    COLUMN,
    FAMILY_COLORS,
    PAGE,
    STYLE,
    family_color,
    figure_files,
    new_figure,
    save_figure,
)

__all__ = ["COLUMN", "PAGE", "STYLE", "FAMILY_COLORS", "family_color", "figure_files",
           "new_figure", "save_figure"]
