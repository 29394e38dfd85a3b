"""The workflow layer, the bottom of the pipeline: what a study is before anything runs.

schema (declared keys, the TOML reader), keys (the workflow's tables and keys), load (the
validator: TOML -> Study), accuracy (presets), study (Study: params per f, seeds,
fingerprint), identity (a point's key and every seed), scenes (where shipped scenes live).
Imports nothing of the layers above it (tests/test_layout.py).
"""
