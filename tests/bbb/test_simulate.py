import numpy as np
import pytest

from bbb import Params, simulate


@pytest.fixture(scope="module")
def p():
    return Params.preset("klages2004", f=60.0)


@pytest.mark.parametrize(
    ("kwargs", "names"),
    [
        (dict(n_particles=-1), "n_particles"),
        (dict(n_particles=2.5), "n_particles"),
        (dict(record_collisions=-3), "record_collisions"),
        (dict(t_max=0.0), "t_max"),
        (dict(t_max=float("nan")), "t_max"),
        (dict(record_from=-1.0), "record_from"),
        (dict(sample_times=np.array([0.0, 0.5, 0.2])), "sample_times"),
        (dict(sample_times=np.array([0.0, 5.0])), "sample_times"),
        (dict(initial="floating"), "unknown initial family"),
        (dict(initial="dropped", drop_height=(2.0, 1.0)), "drop_height"),
        (dict(initial="launched", launch_speed=(-5.0, 1.0)), "launch_speed"),
        (dict(seed=-4), "seed"),
    ],
)
def test_bad_arguments_raise_a_clear_value_error(p, kwargs, names):
    args = dict(n_particles=3, t_max=1.0, seed=1)
    args.update(kwargs)
    with pytest.raises(ValueError, match=names):
        simulate(p, **args)


def test_only_requested_observables_are_recorded(p):
    run = simulate(p, 4, 0.2, seed=1)
    assert run.positions is None and run.collisions_dense is None
    assert run.counters["collisions"].sum() > 0


def test_recorded_collisions_start_at_record_from_and_stop_at_the_requested_count(p):
    run = simulate(p, 5, 2.0, seed=1, initial="launched", record_collisions=7, record_from=1.0)
    table = run.collisions
    assert np.all(table["t"] >= 1.0) and np.all(table["t"] < 2.0)
    assert np.all(np.bincount(table["particle"], minlength=5) == run.n_recorded)
    assert np.all(run.n_recorded <= 7)


def test_positions_start_at_the_initial_position_and_stay_finite(p):
    times = np.linspace(0.0, 1.0, 11)
    run = simulate(p, 50, 1.0, seed=3, initial="rest", sample_times=times)
    assert run.positions.shape == (50, 11)
    assert np.all(np.isfinite(run.positions))
    assert np.all(np.abs(run.positions[:, 0]) <= p.S / 2)


def _traced_peak(p, t_max: float) -> tuple[int, int]:
    """Peak bytes allocated through Python/numpy while simulating 20 particles for t_max s,
    and the number of collisions."""
    import tracemalloc

    tracemalloc.start()
    try:
        run = simulate(p, 20, t_max, seed=1, sample_times=np.array([0.0, t_max]),
                       record_collisions=3)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return peak, int(run.counters["collisions"].sum())


def test_memory_does_not_grow_with_the_number_of_collisions(p):
    # 10x the simulated time: ~10x the collisions (~1.5e4), the same peak memory.  A buffer of
    # one float per collision would add ~120 kB to a peak of ~10 kB.  (tracemalloc sees numpy
    # arrays made in Python, not numba's own allocations inside the jitted kernel.)
    _traced_peak(p, 0.1)  # compile / load the cache outside the measurement
    short, n_short = _traced_peak(p, 1.0)
    long, n_long = _traced_peak(p, 10.0)
    assert n_long > 5 * n_short
    assert long < 1.5 * short, (short, long)
