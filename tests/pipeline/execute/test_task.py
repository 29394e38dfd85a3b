"""The Dask task (pipeline.execute.task): one chunk simulated from its own seed and written to its own
store chunk, the same bytes however often it runs."""

from __future__ import annotations

import numpy as np

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import load_workflow

from ..helpers import store_arrays


def test_a_task_run_twice_writes_the_same_bytes(reference, tiny_workflow, tmp_path):
    # Dask may run a task twice; here the same chunk is recomputed in this process.
    path = tmp_path / "twice.zarr"
    study = load_workflow(tiny_workflow)
    store = StudyStore.create_or_open(path, study)
    for _ in range(2):
        compute_chunk(store, 1, 0, 1)
    a, b = store_arrays(reference[0]), store_arrays(path)
    sl = store.chunk_particles(1)
    assert np.array_equal(a["positions"][1, 0, sl], b["positions"][1, 0, sl])
    assert np.array_equal(a["collisions"][1, 0, sl], b["collisions"][1, 0, sl], equal_nan=True)


def test_a_stored_chunk_is_what_bbb_simulate_gives_for_its_seed(reference, tiny_workflow):
    # the seeding rule of docs/design.md, checked from the outside: f in mHz, crc32 of the family
    # name, chunk index; every recorded collision field (bbb.record.COLLISION_FIELDS) stored
    import zlib

    import zarr

    from bbb import Params, simulate
    from bbb.record import COLLISION_FIELDS

    g = zarr.open_group(str(reference[0]), mode="r")
    assert tuple(g["field"][...]) == COLLISION_FIELDS
    study = load_workflow(tiny_workflow)
    fi, mi, ci = 1, 1, 1  # f = 60 Hz, family "launched", second chunk
    seed = np.random.SeedSequence(7, spawn_key=(60000, zlib.crc32(b"launched"), ci))
    run = simulate(Params.preset("klages2004", f=60.0), 4, 10.0, seed, "launched",
                   sample_times=np.arange(21) * 0.5, record_collisions=40, record_from=2.0,
                   numerics=study.accuracy.numerics(), launch_speed=(0.0, 150.0))
    sl = slice(4 * ci, 4 * ci + 4)
    assert np.array_equal(g["positions"][fi, mi, sl, :], run.positions)
    assert np.array_equal(g["collisions"][fi, mi, sl], run.collisions_dense, equal_nan=True)


def test_a_chunk_of_a_gamma_scene_is_bbb_simulate_at_the_amplitude_of_that_gamma(tmp_path):
    # [params] Gamma = 2: at 60 Hz the chunk runs with A = 2 g / (2 pi 60)^2
    import math

    from bbb import Params, simulate
    from pipeline.workflow.load import parse_workflow

    from ..helpers import TINY

    study = parse_workflow(TINY.replace('preset = "klages2004"',
                                        'preset = "klages2004"\nGamma = 2.0'))
    store = StudyStore.create_or_open(tmp_path / "gamma.zarr", study)
    compute_chunk(store, 1, 0, 0)  # f = 60 Hz, family "rest", first chunk
    p = Params.preset("klages2004", f=60.0, A=2.0 * 9800.0 / (2 * math.pi * 60.0) ** 2)
    run = simulate(p, 4, 10.0, study.seed_sequence(60.0, study.families[0], 0), "rest",
                   sample_times=np.arange(21) * 0.5, record_collisions=40, record_from=2.0,
                   numerics=study.accuracy.numerics())
    assert np.array_equal(store_arrays(tmp_path / "gamma.zarr")["positions"][1, 0, :4], run.positions)


def test_a_maps_tasks_do_not_carry_every_points_params(tmp_path):
    """Sent with each of a map's tasks: its store with a Study that has not computed its
    points (each task gets its own point), a tenth of the store whose Study has them."""
    import pickle

    from pipeline.execute.task import point_arg, store_argument
    from pipeline.store.study_store import StudyStore
    from pipeline.workflow.load import parse_workflow

    from ..helpers import TINY

    alphas = ", ".join(f"{0.3 + 0.6 * i / 400:.4f}" for i in range(400))
    study = parse_workflow(TINY + f"[grid]\nalpha = [{alphas}]\n", source="m.toml")
    store = StudyStore(str(tmp_path / "m.zarr"), study)
    _ = study.points  # computed on the client
    sent = len(pickle.dumps((store_argument(store), point_arg(study, 1))))
    assert sent < len(pickle.dumps(store)) / 10
