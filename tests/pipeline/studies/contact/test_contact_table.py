"""The contact observable end to end: held and sliding time into the store, the contact table
of ``bbb reduce`` against bbb.simulate called from outside, bbb verify on it, and the
bootstrap CI of a mean on samples of known mean."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.execute.run import run_study
from pipeline.store.verify import verify_store
from pipeline.tables.contact import bootstrap_mean
from pipeline.tables.reduce import reduce_store
from pipeline.workflow.load import parse_workflow

from ...helpers import QUIET, write_as_a_run

# 54 Hz, Coulomb mu = 0.3: particles from rest creep (held and sliding); 2 chunks of 4.
CONTACT = """\
[study]
name = "tinycontact"
seed = 11

[params]
preset = "klages2004"
contact = "coulomb"
mu = 0.3

[frequencies]
values = [54.0]

[families.rest]
initial = "rest"

[families.launched]
initial = "launched"

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 4
t_max = 4.0
sample_dt = 0.1
n_resamples = 200

[observables.positions]

[observables.contact]
"""


# the same on a conveyor: the paper's arcs thrown at 30 deg, 50 Hz (below lift-off at 66.7 Hz)
CONVEYOR = CONTACT.replace('name = "tinycontact"', 'name = "tinyconveyor"').replace(
    "mu = 0.3\n", "mu = 0.3\nthrow = 30.0\n").replace("values = [54.0]", "values = [50.0]")


def _store(tmp_path_factory, text: str, name: str):
    study = parse_workflow(text, source=f"{name}.toml")
    path = tmp_path_factory.mktemp(name) / f"{name}.zarr"
    run_study(study, path, workers=1, **QUIET)
    return study, path


@pytest.fixture(scope="module")
def contact_store(tmp_path_factory):
    return _store(tmp_path_factory, CONTACT, "tinycontact")


@pytest.fixture(scope="module")
def conveyor_store(tmp_path_factory):
    return _store(tmp_path_factory, CONVEYOR, "tinyconveyor")


def test_contact_fractions_are_the_simulated_times_over_t_max(contact_store):
    assert_fractions_are_the_simulated_times(*contact_store)


def test_contact_fractions_on_a_conveyor_are_the_simulated_times_over_t_max(conveyor_store):
    study, path = conveyor_store
    assert study.params(50.0).throw == 30.0
    assert_fractions_are_the_simulated_times(study, path)


def test_below_liftoff_on_a_conveyor_particles_from_rest_stay_in_contact(conveyor_store):
    # 50 Hz on the floor thrown at 30 deg: the floor never lets go of a particle at rest
    # (bbb.analysis.liftoff_onset); Coulomb particles slide and fly only off the other wall of a cusp
    _, path = conveyor_store
    table = reduce_store(path, path.parent / "tables", echo=lambda s: None)["contact"]
    rest = table[table.family == "rest"].iloc[0]
    assert rest.contact_frac > 0.9 and rest.slide_frac > 0.01


def assert_fractions_are_the_simulated_times(study, path) -> None:
    from bbb.simulate import simulate

    table = reduce_store(path, path.parent / "tables", echo=lambda s: None)["contact"]
    assert len(table) == 2
    acc = study.accuracy
    f = study.frequencies[0]
    for fam in study.families:
        held, sliding = [], []
        for ci in range(acc.n_chunks):
            # on the store's sampling grid: a sliding stretch ends its steps on the sample
            # times (bbb.dynamics.slide), so another grid takes other steps (docs/physics.md)
            run = simulate(study.params(f), acc.chunk_size, acc.t_max,
                           study.seed_sequence(f, fam, ci), numerics=acc.numerics(),
                           sample_times=study.sample_times(), **fam.simulate_kwargs())
            held.append(run.contact_time["held"])
            sliding.append(run.contact_time["sliding"])
        row = table[table.family == fam.name].iloc[0]
        assert row.held_frac == pytest.approx(np.concatenate(held).mean() / acc.t_max, rel=1e-12)
        assert row.slide_frac == pytest.approx(np.concatenate(sliding).mean() / acc.t_max,
                                               rel=1e-12)
        for col in ("held_frac", "slide_frac"):
            assert 0 <= row[f"{col}_lo"] <= row[col] <= row[f"{col}_hi"] <= 1


def test_creeping_particles_from_rest_spend_time_in_contact(contact_store):
    # At 54 Hz (Gamma = 1.17) a particle at rest is carried and slides before it first lifts
    # off: the rest family cannot have zero contact time.
    _, path = contact_store
    table = reduce_store(path, path.parent / "tables", echo=lambda s: None)["contact"]
    rest = table[table.family == "rest"].iloc[0]
    assert rest.contact_frac > 0.01


def test_verify_flags_contact_times_beyond_t_max(contact_store, tmp_path):
    import shutil

    _, path = contact_store
    assert verify_store(path).ok
    bad = tmp_path / "bad.zarr"
    shutil.copytree(path, bad)
    write_as_a_run(bad, "held_time", (0, 0, 2), 5.0)  # > t_max = 4 s
    problems = verify_store(bad).problems
    assert any(p.where.startswith("held_time") and "exceeds t_max" in p.what for p in problems)


def test_stick_scene_without_contact_keeps_its_fingerprint():
    # The observable is opt-in: the same workflow without [observables.contact] and with
    # the key off has the fingerprint of a workflow that never heard of it.
    base = CONTACT.replace("\n[observables.contact]\n", "\n")
    with_off = parse_workflow(base, source="a.toml")
    with_on = parse_workflow(CONTACT, source="a.toml")
    assert "contact" not in with_off.to_dict()["observables"]
    assert with_off.fingerprint() != with_on.fingerprint()


@pytest.mark.parametrize("p_true", [0.02, 0.3])
def test_bootstrap_mean_covers_a_known_mean(p_true):
    # 0/1 samples (a particle creeping or not) of known mean: the 95 % interval covers it in
    # 90-99 % of 300 repetitions.
    rng = np.random.default_rng(5)
    hits = 0
    for k in range(300):
        x = (rng.random(200) < p_true).astype(float)
        _, lo, hi = bootstrap_mean(x, 400, 0.95, np.random.SeedSequence(k))
        hits += lo <= p_true <= hi
    assert 0.90 <= hits / 300 <= 0.99
