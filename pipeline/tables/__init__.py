"""The tables layer: a store reduced to tables (Parquet + CSV, every column with its unit).

reduce (D(f) with CIs and verdicts, counters; writing and reading the tables), collisions
(collision records, locking tables), contact (held and sliding shares), mechanisms (the
memory expansion of D, λ).  Imports only the execute, store and workflow layers
(tests/test_layout.py).
"""
