"""Figures of any reduced Dataset (``open_study(path, reduced=True)``): a layer of the engine
above the tables, knowing no study.

* :func:`plot_curve` (:mod:`.curve`) -- a variable against one dimension with its CI, flags
  marked, one line per value of another dimension
* :func:`plot_map` (:mod:`.heatmap`) -- a variable over two dimensions, flags hatched, the CI
  in a panel beside it, contours of another variable
* :func:`plot_dataset` (:mod:`.figures`) -- every figure a talk needs, written as files
* :mod:`.style`, :mod:`.labels`, :mod:`.flags` -- the house style, axis labels with units,
  the verdicts a point is flagged by
* :mod:`.scales`, :mod:`.titles`, :mod:`.models` -- the rules every figure follows: log axes
  past two decades, a diverging map centred at 0 for a signed quantity; the title (scene,
  what it fixes, the cut); contact x mu drawn as one axis of models

``python -m pipeline.gallery`` (above the engine: it runs scenes) draws docs/gallery.md, one
figure of each kind from shipped scenes.
"""

from .curve import plot_curve
from .figures import plot_dataset
from .heatmap import plot_map

__all__ = ["plot_curve", "plot_map", "plot_dataset"]
