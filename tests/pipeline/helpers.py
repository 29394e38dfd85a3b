"""Shared test material: a tiny workflow and bit-for-bit store comparison."""

from __future__ import annotations

import numpy as np
import zarr

# Two frequencies on either side of the f = 55 peak, two families, 2 chunks of 4 particles:
# 8 tasks of a few ms each.  Positions and collisions, so every array of the layout exists.
TINY = """\
[study]
name = "tiny"
seed = 7

[params]
preset = "klages2004"

[frequencies]
values = [54.0, 60.0]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"
launch_speed = [0.0, 150.0]

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 4
t_max = 10.0
sample_dt = 0.5
n_resamples = 100

[observables.positions]

[observables.collisions]
record = 40
record_from = 2.0
"""

# TINY made to last seconds, so that a kill lands mid-sweep whatever the machine's load:
# 2 frequencies x 2 families x 4 chunks = 16 tasks of ~0.1-0.2 s each (t_max = 30 s).
FAULT = (TINY.replace('name = "tiny"', 'name = "fault"')
         .replace("[54.0, 60.0]", "[54.0, 56.0]")
         .replace("n_particles = 8", "n_particles = 16")
         .replace("t_max = 10.0", "t_max = 30.0"))

# run_study keyword arguments for tests: no progress bar, no dashboard, no printing.
QUIET = dict(progress=False, dashboard=False, echo=lambda s: None)

# Arrays whose contents are a deterministic function of the workflow (chunk_seconds is not).
NON_REPRODUCIBLE = {"chunk_seconds"}


def store_arrays(path) -> dict[str, np.ndarray]:
    g = zarr.open_group(str(path), mode="r")
    return {name: np.asarray(arr[...]) for name, arr in g.arrays()}


def assert_same_store(a, b) -> None:
    """Bit-identical reproducible arrays (NaN where NaN) and the same data fingerprint."""
    xa, xb = store_arrays(a), store_arrays(b)
    assert sorted(xa) == sorted(xb)
    for name in xa:
        if name in NON_REPRODUCIBLE:
            continue
        assert xa[name].dtype == xb[name].dtype, name
        assert xa[name].shape == xb[name].shape, name
        if xa[name].dtype.kind == "f":
            # bit-identical, NaN padding included
            assert np.array_equal(xa[name].view(np.uint64), xb[name].view(np.uint64)), name
        else:
            assert np.array_equal(xa[name], xb[name]), name
    ga, gb = zarr.open_group(str(a), mode="r"), zarr.open_group(str(b), mode="r")
    assert ga.attrs["fingerprint"] == gb.attrs["fingerprint"]


def run_outside(py, code: str, cwd, timeout: float = 600) -> str:
    """stdout of ``py -c code`` run in ``cwd`` (outside the repository), without the
    PYTHONPATH of this environment, cut after ``timeout`` s; asserts it exits 0."""
    import os
    import subprocess

    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONSAFEPATH")}
    out = subprocess.run([str(py), "-c", code], cwd=cwd, env=env, capture_output=True,
                         text=True, timeout=timeout)
    assert out.returncode == 0, out.stderr[-3000:]
    return out.stdout


def write_as_a_run(path, name: str, index: tuple, value) -> None:
    """``name[index] = value`` in the store at ``path``, with the chunk's digest recorded as
    a run that wrote those values would have: the store stays intact, so only `bbb verify`'s
    physics checks (pipeline/store/chunk_checks.py) can find the fault.  ``index``: (point,
    family, particle or slice of particles of one chunk, ...)."""
    from pipeline.store.layout import chunk_digest

    g = zarr.open_group(str(path), mode="r+")
    arr = g[name]
    arr[index] = value(arr[index]) if callable(value) else value
    fi, mi, p = index[:3]
    cs = arr.chunks[2]
    ci = (p.start if isinstance(p, slice) else p) // cs
    k = [str(v) for v in g["array"][...]].index(name)
    block = np.asarray(arr[fi, mi, ci * cs: (ci + 1) * cs])
    trim = "period" in arr.metadata.dimension_names
    g["digest"][fi, mi, ci, k] = chunk_digest(block, arr.fill_value, trim)
