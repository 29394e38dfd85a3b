"""The claims layer: claims as data, judged against the tables with their CIs.

claim (Claim, Band, Quantity, ...: the generic claim record and the verdict rule), measures
(generic measures on D(f) curves and tables), markdown (the claims table of a report).
Knows no paper; imports nothing of the layers above it (tests/test_layout.py).
"""
