"""The execute layer: running a study's chunks as Dask tasks and writing them to its store.

run (the client: cluster, which chunks, resume, failures), task (the Dask task: one chunk),
waves and adaptive (waves of chunks; the pure stopping and refinement rules), cluster (SLURM),
plan and pilot (``bbb plan``: the cost model and the pilot that measures it), interrupt
(SIGTERM handled as Ctrl-C during ``bbb run``).  Imports only
the store and workflow layers (tests/test_layout.py).
"""
