"""The claims layer: claims as data, judged against the tables with their CIs.

record (Claim, Band, Quantity, ...: the generic claim record and the verdict rule), measures
(generic measures on D(f) curves and tables), markdown (the claims table of a report).
Knows no paper; imports nothing of the layers above it (tests/test_layout.py).

Moved: the module ``pipeline.claims`` is now :mod:`pipeline.claims.record` (its
``markdown_table`` and ``md_cell``: :mod:`pipeline.claims.markdown`); its names are
re-exported here, kept for one release.  Code in pipeline/ imports the modules.
"""

from .markdown import *  # noqa: F403
from .record import *  # noqa: F403
from .record import evaluate_claim  # noqa: F401  (imported from pipeline.claims before the move)
