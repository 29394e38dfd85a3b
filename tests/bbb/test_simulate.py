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


def test_memory_does_not_grow_with_the_number_of_collisions(p):
    # 10× the simulated time: ~10× the collisions, the same output arrays
    short = simulate(p, 2, 1.0, seed=1, sample_times=np.array([0.0, 1.0]), record_collisions=3)
    long = simulate(p, 2, 10.0, seed=1, sample_times=np.array([0.0, 10.0]), record_collisions=3)
    assert long.counters["collisions"].sum() > 5 * short.counters["collisions"].sum()
    assert long.positions.nbytes == short.positions.nbytes
    assert long.collisions_dense.nbytes == short.collisions_dense.nbytes
