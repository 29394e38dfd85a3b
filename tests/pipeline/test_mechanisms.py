"""The jumps and lyapunov observables: a tiny real scene through a real LocalCluster and Zarr."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bbb.greenkubo import expansion
from bbb.simulate import simulate

from .helpers import QUIET

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
"""


@pytest.fixture(scope="module")
def mech(tmp_path_factory):
    """(study, store path, tables) of MECH run on 2 workers and reduced."""
    from pipeline.reduce import reduce_store
    from pipeline.run import run_study
    from pipeline.workflow import parse_workflow

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

    from bbb.ensemble import initial_state
    from bbb.lyapunov import lyapunov

    study, path, _ = mech
    f = 60.0
    p = study.params(f)
    st = initial_state(p, 4, study.seed_sequence(f, study.families[0], 1), "rest")
    lam = lyapunov(p, 4, study.accuracy.t_max, 0, st, numerics=study.accuracy.numerics())
    stored = np.asarray(zarr.open_group(str(path), mode="r")["lyapunov"][0, 0, 4:5])
    assert stored[0] == lam.lam_i[0]


def test_mechanism_columns_only_when_declared(reference):
    from pipeline.reduce import reduce_store

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
    from pipeline.scenes import load_scene

    before = {  # at commit 05f7e27, before the observables existed
        "figure3": "2ca6f48b9bea73ce17807d694b11bdf6a7f0654ac8693c435d7972fa39aac377",
        "smoke": "27388bc65e6950507b8067cc506473e2a493d294ff3ad699bf8474b8454a2f86",
        "locking": "d2b86776f65b2503595163072a4233b9cf84d6a51fa161e1cd2a9019994ac524",
    }
    for name, fp in before.items():
        assert load_scene(name, False).fingerprint() == fp, name
