"""pipeline.workflow.identity gives exactly the seeds the pipeline built by hand before it existed:
the expressions below are copied from the modules they replaced (study.py, pilot.py, waves.py,
reduce.py, mechanisms.py, contact.py, collisions.py at 0e5a803), and every committed store and
table depends on them."""

from __future__ import annotations

import zlib
from types import SimpleNamespace

import numpy as np
import pytest

from pipeline.workflow import identity
from pipeline.workflow.keys import Family

from ..helpers import TINY

SEEDS = (2004, 7, 0, 2**32 + 5)
# the committed grids' kinds of frequency: integers, half and quarter Hz, mHz steps, and
# values whose f * 1000 is not exact in binary (54.3, 0.001, 72.125, 100.1)
FREQS = (0.001, 1.0, 46.0, 54.3, 55.6, 56.4, 57.25, 60.0, 60.5, 72.125, 79.999, 100.1, 120.0)
FAMILIES = ("rest", "launched", "dropped", "rest_slide", "ünïcode")
CHUNKS = (0, 1, 7, 63, 2**31)


def _old_chunk(seed, f, fam, chunk):  # study.py Study.seed_sequence, pilot.py
    return np.random.SeedSequence(seed, spawn_key=(round(f * 1000), Family(fam, "rest").key, chunk))


def _old_stop(seed, f, fam, n):  # waves.py stop_seed
    return np.random.SeedSequence(seed, spawn_key=(round(f * 1000), Family(fam, "rest").key,
                                                   zlib.crc32(b"stop"), n))


def _old_reduce(seed, f):  # reduce.py _reduce_seed
    return np.random.SeedSequence(seed, spawn_key=(round(f * 1000), zlib.crc32(b"reduce")))


def _old_mechanisms(seed, f):  # mechanisms.py mechanisms_table
    return np.random.SeedSequence(seed, spawn_key=(round(f * 1000), zlib.crc32(b"mechanisms")))


def _old_table(seed, f, fam, label):  # contact.py contact_table, collisions.py locking_table
    return np.random.SeedSequence(seed, spawn_key=(
        round(f * 1000), zlib.crc32(fam.encode()), zlib.crc32(label.encode())))


def _old_child(seed, label):  # reduce.py _stationarity_columns, _transport_columns
    return np.random.SeedSequence(seed.entropy, spawn_key=(*seed.spawn_key,
                                                           zlib.crc32(label.encode())))


def same(a: np.random.SeedSequence, b: np.random.SeedSequence) -> bool:
    """Equal entropy, spawn_key and pool, and the same numbers drawn from either."""
    return (a.entropy == b.entropy and a.spawn_key == b.spawn_key
            and all(type(x) is int for x in b.spawn_key)
            and np.array_equal(a.generate_state(4), b.generate_state(4))
            and np.array_equal(np.random.default_rng(a).random(3),
                               np.random.default_rng(b).random(3)))


def test_f_key_is_the_rounded_mhz_also_of_numpy_floats():
    for f in FREQS:
        for x in (f, np.float64(f)):
            assert identity.f_key(x) == round(f * 1000) and type(identity.f_key(x)) is int
    fs = np.array(FREQS)
    assert identity.f_keys(fs).tolist() == [round(f * 1000) for f in FREQS]
    # half-way values round to even, as round() did
    assert identity.f_key(0.0005) == round(0.0005 * 1000) == 0
    assert identity.f_keys([0.0025, 0.0035]).tolist() == [2, 4]


@pytest.mark.parametrize("seed", SEEDS)
def test_every_seed_is_bit_identical_to_its_old_expression(seed):
    study = SimpleNamespace(seed=seed)
    n = 0
    for f in FREQS + tuple(np.float64(x) for x in FREQS[::3]):
        assert same(identity.reduce_seed(study, f), _old_reduce(seed, f))
        assert same(identity.reduce_seed(seed, f), _old_reduce(seed, f))
        assert same(identity.mechanisms_seed(study, f), _old_mechanisms(seed, f))
        for label in ("stationarity", "transport"):
            assert same(identity.child_seed(identity.reduce_seed(study, f), label),
                        _old_child(_old_reduce(seed, f), label))
        for fam in FAMILIES:
            family = Family(fam, "rest")
            for chunk in CHUNKS:
                old = _old_chunk(seed, f, fam, chunk)
                assert same(identity.chunk_seed(study, f, family, chunk), old)
                assert same(identity.chunk_seed(seed, f, fam, chunk), old)
                assert same(identity.stop_seed(study, f, family, chunk + 1),
                            _old_stop(seed, f, fam, chunk + 1))
                n += 3
            assert same(identity.pilot_seed(study, f, family), _old_chunk(seed, f, fam, 2**31))
            for label in ("held_frac", "slide_frac", "flight_frac", "locking"):
                assert same(identity.table_seed(study, f, family, label),
                            _old_table(seed, f, fam, label))
    assert n > 1000


def test_the_study_and_the_pipeline_modules_use_these_seeds():
    from pipeline.execute import pilot, waves
    from pipeline.store import study_store as store
    from pipeline.workflow.load import parse_workflow

    study = parse_workflow(TINY)  # seed 7, 54 and 60 Hz, families rest and launched
    for fam in study.families:
        for f in study.frequencies:
            assert same(study.seed_sequence(f, fam, 1), _old_chunk(7, f, fam.name, 1))
            assert same(waves.stop_seed(study, f, fam, 2), _old_stop(7, f, fam.name, 2))
    assert pilot.PILOT_CHUNK == 2**31
    assert store.SEEDING == ("SeedSequence(workflow seed, spawn_key=(round(f * 1000), "
                             "zlib.crc32(family name), chunk index))")


@pytest.mark.parametrize("f", FREQS)
def test_point_key_without_grid_values_is_the_frequency_key(f):
    assert identity.point_key(f) == identity.point_key(f, ()) == identity.point_key(f, {}) \
        == identity.f_key(f)


def test_point_key_with_grid_values_holds_them_after_the_frequency_key():
    assert identity.point_key(60.0, {"alpha": 0.5, "contact": "slide"}) == (
        60000, ("alpha", 0.5), ("contact", "slide"))
