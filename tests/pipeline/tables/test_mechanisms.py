"""The jumps and lyapunov observables: a tiny real scene through a real LocalCluster and Zarr."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb.analysis.greenkubo import expansion
from bbb.simulate import simulate

from ..helpers import QUIET

MECH = """\
[study]
name = "mech"
seed = 11

[params]
preset = "klages2004"

[frequencies]
values = [60.0, 80.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 4
t_max = 4.0
sample_dt = 0.05
n_resamples = 50

[observables.positions]
[observables.jumps]
[observables.lyapunov]
particles = 5

[observables.collisions]
record = 20
x_jumps = 30
"""


@pytest.fixture(scope="module")
def mech(tmp_path_factory):
    """(study, store path, tables) of MECH run on 2 workers and reduced."""
    from pipeline.execute.run import run_study
    from pipeline.tables.reduce import reduce_store
    from pipeline.workflow.load import parse_workflow

    study = parse_workflow(MECH, source="mech.toml")
    path = tmp_path_factory.mktemp("mech") / "mech.zarr"
    run_study(study, path, workers=2, **QUIET)
    return study, path, reduce_store(path, echo=lambda s: None)


def test_d_inf_from_the_store_equals_the_expansion_of_independently_simulated_positions(mech):
    study, _, tables = mech
    row = tables["mechanisms"].set_index("f").loc[80.0]
    f, fam = 80.0, study.families[0]
    n = int(math.floor(study.accuracy.t_max * f + 1e-9))
    x = np.concatenate([simulate(study.params(f), 4, study.accuracy.t_max,
                                 study.seed_sequence(f, fam, ci),
                                 sample_times=np.minimum(np.arange(n + 1) / f, study.accuracy.t_max),
                                 numerics=study.accuracy.numerics()).positions for ci in (0, 1)])
    skip = math.ceil(study.analysis.discard * n - 1e-9)
    dx = np.diff(x, axis=1).astype(np.float32).astype(np.float64)[:, skip:]
    seed = np.random.SeedSequence(study.seed, spawn_key=(80000, __import__("zlib").crc32(
        b"mechanisms")))
    gk = expansion(dx, 1.0 / f, n_resamples=50, ci=0.95, seed=int(seed.generate_state(1)[0]))
    assert row["D_inf"] == pytest.approx(gk.D_inf, rel=1e-12)
    assert row["D_0"] == pytest.approx(gk.D_n[0], rel=1e-12)
    assert row["lag"] == gk.lag and bool(row["converged"]) == gk.converged


def test_stored_jumps_sum_to_the_stored_positions_displacement(mech):
    import zarr

    _, path, _ = mech
    g = zarr.open_group(str(path), mode="r")
    jumps = np.asarray(g["jumps"][1, 0])  # 80 Hz: 320 periods in 4 s, the longest row
    pos = np.asarray(g["positions"][1, 0])
    # t_max = 4 s is a whole number of periods at 80 Hz: the jumps span the whole run
    np.testing.assert_allclose(jumps.astype(np.float64).sum(axis=1), pos[:, -1] - pos[:, 0],
                               atol=1e-3)
    # 60 Hz: 240 periods, the rest NaN
    j60 = np.asarray(g["jumps"][0, 0])
    assert np.isfinite(j60[:, :240]).all() and np.isnan(j60[:, 240:]).all()


def test_lyapunov_only_for_the_declared_first_particles(mech):
    import zarr

    _, path, tables = mech
    lam = np.asarray(zarr.open_group(str(path), mode="r")["lyapunov"][...])
    assert (~np.isnan(lam[:, 0, :5])).all() and np.isnan(lam[:, 0, 5:]).all()
    row = tables["mechanisms"].iloc[0]
    assert row["n_lyapunov"] == 5 and row["lam_lo"] <= row["lam"] <= row["lam_hi"]


def test_lyapunov_in_the_store_equals_bbb_lyapunov_on_the_same_initial_states(mech):
    import zarr

    from bbb.analysis.lyapunov import lyapunov
    from bbb.ensemble import initial_state

    study, path, _ = mech
    f = 60.0
    p = study.params(f)
    st = initial_state(p, 4, study.seed_sequence(f, study.families[0], 1), "rest")
    lam = lyapunov(p, 4, study.accuracy.t_max, 0, st, numerics=study.accuracy.numerics())
    stored = np.asarray(zarr.open_group(str(path), mode="r")["lyapunov"][0, 0, 4:5])
    assert stored[0] == lam.lam_i[0]


def test_stored_collision_jumps_are_the_differences_of_the_stored_collisions(mech):
    import zarr

    _, path, _ = mech
    g = zarr.open_group(str(path), mode="r")
    rows = np.asarray(g["collisions"][1, 0])  # the first 20 rows of the same recording
    dx, dt = (np.asarray(g[name][1, 0]) for name in ("collision_dx", "collision_dt"))
    assert dx.shape == dt.shape == (8, 30)
    np.testing.assert_array_equal(dx[:, :19], np.diff(rows[:, :, 1], axis=1).astype(np.float32))
    np.testing.assert_array_equal(dt[:, :19], np.diff(rows[:, :, 0], axis=1).astype(np.float32))


def test_per_collision_expansion_from_the_store_equals_one_of_independently_simulated_runs(mech):
    from bbb.analysis.greenkubo import collision_jumps

    study, _, tables = mech
    row = tables["mechanisms"].set_index("f").loc[80.0]
    f, fam = 80.0, study.families[0]
    runs = [simulate(study.params(f), 4, study.accuracy.t_max, study.seed_sequence(f, fam, ci),
                     record_collisions=31, numerics=study.accuracy.numerics()) for ci in (0, 1)]
    parts = [collision_jumps(r.collisions_dense, r.n_recorded) for r in runs]
    dx, dt = (np.concatenate([p[k] for p in parts]).astype(np.float32).astype(np.float64)
              for k in (0, 1))
    assert np.isfinite(dx).all()  # 8 particles, each ≥ 31 collisions in 4 s at 80 Hz
    seed = np.random.SeedSequence(study.seed, spawn_key=(80000, __import__("zlib").crc32(
        b"mechanisms")))
    gk = expansion(dx, dt.sum(axis=1) / 30, n_resamples=50, ci=0.95,
                   seed=int(seed.generate_state(3)[2]))
    assert row["n_coll_jumps"] == 30 and row["n_coll_particles"] == 8
    assert row["D_inf_coll"] == pytest.approx(gk.D_inf, rel=1e-12)
    assert row["D_0_coll"] == pytest.approx(gk.D_n[0], rel=1e-12)
    assert row["tau_coll"] == pytest.approx(dt.sum() / 240, rel=1e-12)


def test_contrast_columns_split_the_log_ratio_of_the_neighbours_expansions(mech):
    t = mech[2]["mechanisms"].set_index("f")
    r, nb = t.loc[80.0], t.loc[60.0]
    assert r["f_dn"] == 60.0 and np.isnan(r["f_up"]) and np.isnan(r["ln_D_up"])
    for step in ("", "_coll"):
        if not (r[f"converged{step}"] and nb[f"converged{step}"]):
            assert np.isnan(r[f"ln_D{step}_dn"])
            continue
        assert r[f"ln_D{step}_dn"] == pytest.approx(
            math.log(r[f"D_inf{step}"] / nb[f"D_inf{step}"]), rel=1e-12)
        assert r[f"ln_walk{step}_dn"] == pytest.approx(
            math.log(r[f"D_0{step}"] / nb[f"D_0{step}"]), rel=1e-12)
        assert r[f"ln_mem{step}_dn"] == pytest.approx(
            r[f"ln_D{step}_dn"] - r[f"ln_walk{step}_dn"], rel=1e-9, abs=1e-12)
        # the same contrast seen from the other side has the opposite sign
        assert nb[f"ln_D{step}_up"] == pytest.approx(-r[f"ln_D{step}_dn"], rel=1e-12)


def test_lambda_of_moving_and_confined_particles_splits_the_stored_lambdas_by_x_range(mech):
    import zarr

    study, path, tables = mech
    g = zarr.open_group(str(path), mode="r")
    for fi, f in enumerate(study.frequencies):
        lam = np.asarray(g["lyapunov"][fi, 0, :5])
        moves = np.asarray(g["lyapunov_x_range"][fi, 0, :5]) >= study.params(f).S
        row = tables["mechanisms"].set_index("f").loc[f]
        assert row["n_lam_move"] == moves.sum() and row["n_lam_conf"] == (~moves).sum()
        if moves.any():
            assert row["lam_move"] == pytest.approx(lam[moves].mean(), rel=1e-12)


def test_a_lambda_ci_is_degenerate_when_most_particles_share_one_orbit_or_few_values():
    from pipeline.tables.mechanisms import degenerate

    rng = np.random.default_rng(3)
    chaotic = 37.0 * (1 + 0.02 * rng.standard_normal(16))
    # 13 particles held in one periodic orbit: equal up to ~1e-5 (what their transients left)
    held = np.concatenate([-126.1 * (1 + 1e-5 * rng.standard_normal(13)), chaotic[:3]])
    four = np.repeat([1.0, 2.0, 3.0, 4.0], 4)
    assert degenerate(held, -120.0, -100.0) and degenerate(four, 2.0, 3.0)
    assert not degenerate(chaotic, 36.5, 37.5)
    assert degenerate(chaotic, 37.0, 37.0)  # a zero-width interval


def test_mechanism_columns_only_when_declared(reference):
    from pipeline.tables.reduce import reduce_store

    path, _ = reference
    tables = reduce_store(path, path.parent / "tables_plain", echo=lambda s: None)
    assert "mechanisms" not in tables
    assert not any(c.startswith(("D_inf", "lam")) for c in tables["diffusion"].columns)


def test_columns_present_when_declared(mech):
    cols = set(mech[2]["mechanisms"].columns)
    assert {"D_0", "D_1", "D_5", "D_inf", "D_inf_lo", "D_inf_hi", "lag", "converged", "lam",
            "lam_lo", "lam_hi", "lam_coll", "frac_creep"} <= cols


def test_shipped_scenes_without_the_new_observables_keep_their_fingerprint():
    """The fingerprints of committed scenes (unchanged since), measured before jumps/lyapunov
    existed (figure2 has since become target-driven: its fingerprint changed on purpose)."""
    from pipeline.workflow.scenes import load_scene

    before = {  # at commit 05f7e27, before the observables existed
        "figure3": "2ca6f48b9bea73ce17807d694b11bdf6a7f0654ac8693c435d7972fa39aac377",
        "smoke": "27388bc65e6950507b8067cc506473e2a493d294ff3ad699bf8474b8454a2f86",
        "locking": "d2b86776f65b2503595163072a4233b9cf84d6a51fa161e1cd2a9019994ac524",
    }
    for name, fp in before.items():
        assert load_scene(name, False).fingerprint() == fp, name
