"""The store layer: one Zarr store per study, above the workflow layer.

study_store (StudyStore: open, resume, grow, read and write chunks), attrs (the root
attributes and the fingerprint), layout (which arrays, units, chunks; the stop codes as
stored), integrity (is a done chunk what its task wrote: checked on every read), metadata
(which zarr.json is damaged; a workflow's layout in memory), lock (one run per store), verify
(``bbb verify``: a store against its own workflow) and chunk_checks (the checks of one done
chunk's data).  Imports only the workflow layer
(tests/test_layout.py).
"""
