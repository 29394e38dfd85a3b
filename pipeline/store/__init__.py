"""The store layer: one Zarr store per study, above the workflow layer.

study_store (StudyStore: open, resume, grow, read and write chunks), attrs (the root
attributes and the fingerprint), layout (which arrays, units, chunks; the stop codes as
stored), integrity (is a done chunk what its task wrote: checked on every read), metadata
(which zarr.json is damaged; a workflow's layout in memory), lock (one run per store), verify
(``bbb verify``: a store against its own workflow) and chunk_checks (the checks of one done
chunk's data).  Imports only the workflow layer
(tests/test_layout.py).

Moved: the module ``pipeline.store`` is now :mod:`pipeline.store.study_store`; its names are
re-exported here, kept for one release.  Code in pipeline/ imports ``pipeline.store.study_store``.
"""

from .study_store import *  # noqa: F403
from .study_store import (  # noqa: F401  (imported from pipeline.store before the move)
    SEEDING,
    fingerprint_difference,
    is_local,
)
