# bbb — everything starts from `make test` on a machine with only Python 3.11+.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed

.PHONY: venv test test-slow lint smoke figures bench calibrate clean clean-numba

venv: $(STAMP)

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,dev]'
	touch $(STAMP)

# --durations=25: every log (CI's included: .ci/run and ci.yml run `make test`) lists the
# 25 slowest tests, so a test that grows shows up where it grew
test: $(STAMP)
	$(PY) -m pytest -q --durations=25

test-slow: $(STAMP)
	$(PY) -m pytest -q -m slow

# ruff pinned by the `dev` extra (pyproject.toml)
lint: $(STAMP)
	$(VENV)/bin/ruff check .

# the smoke study end to end: run on a local Dask cluster, then D(f) tables in runs/smoke/
smoke: $(STAMP)
	$(VENV)/bin/bbb run workflows/smoke.toml --store runs/smoke.zarr
	$(VENV)/bin/bbb reduce runs/smoke.zarr --out runs/smoke

# every figure and figures/REPORT.md; FAST=1 runs the same scenes at draft accuracy
figures: $(STAMP)
	$(PY) -m pipeline.make_figures $(if $(FAST),--fast,)

clean:
	rm -rf $(VENV) runs .pytest_cache

# numba caches a jitted function by its own file only: after editing a kernel module that
# another one calls (search.py from kernel.py, ...), the caller's cached code is stale
clean-numba:
	find bbb -name '*.nbi' -delete -o -name '*.nbc' -delete

# benchmarks print tables (not tests); committed outputs live in benchmarks/results/
# (the benchmarks are modules of the package benchmarks/: python -m benchmarks.perf.kernel ...)
bench: $(STAMP)
	$(PY) -m benchmarks.perf.kernel
	$(PY) -m benchmarks.perf.pipeline

# remake every calibration JSON a rule reads, in place, from the maker and inputs each one names
# (benchmarks/calibrations/__init__.py): ~2 h on 2 cores (benchmarks/results/calibrate-*.txt);
# `git diff` then shows what moved; each maker's table lands in benchmarks/results/.
# CHECK=1 remakes into a scratch folder and compares with the committed JSONs instead
calibrate: $(STAMP)
	$(PY) -m benchmarks.calibrations $(if $(CHECK),--check,)
