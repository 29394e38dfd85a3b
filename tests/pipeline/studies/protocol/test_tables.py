"""The protocol table: a window of T s is a run of length T (the kernel's prefix property),
and the table read off a small store has one row per (f, ensemble, T, definition), seeded by
values only."""

from __future__ import annotations

import numpy as np
import pytest

from bbb import Params
from bbb.simulate import simulate
from pipeline.execute.run import run_study
from pipeline.studies.protocol.tables import COLUMNS, MIXTURE, protocol_table
from pipeline.workflow.load import load_workflow


@pytest.mark.parametrize("initial", ["rest", "launched"])
def test_the_first_T_seconds_are_a_run_of_length_T(initial):
    """Positions of a 4 s run equal the first 4 s of an 8 s run with the same seed: bit for bit
    before the last sample, and to rounding (1e-12 mm) at t = 4 s, where the short run ends
    (so the windows of one run need no separate runs)."""
    p = Params.preset("klages2004", f=54.0)
    dt = 0.05
    short = simulate(p, 8, 4.0, seed=3, initial=initial, sample_times=np.arange(81) * dt)
    long = simulate(p, 8, 8.0, seed=3, initial=initial, sample_times=np.arange(161) * dt)
    assert np.array_equal(short.positions[:, :80], long.positions[:, :80])
    assert np.allclose(short.positions[:, 80], long.positions[:, 80], rtol=0, atol=1e-12)


SMALL = """
[study]
name = "protocol"
seed = 2004
[params]
preset = "klages2004"
[frequencies]
values = [50.0, 54.0]
[families.rest]
initial = "rest"
[families.dropped]
initial = "dropped"
[families.launched]
initial = "launched"
[accuracy]
preset = "draft"
n_particles = 8
chunk_size = 8
t_max = 10.0
sample_dt = 0.05
n_resamples = 50
[observables.positions]
"""


@pytest.fixture(scope="module")
def small_store(tmp_path_factory):
    """Two frequencies, three families of 8 particles x 10 s."""
    root = tmp_path_factory.mktemp("protocol")
    (root / "protocol.toml").write_text(SMALL)
    path = root / "protocol.zarr"
    run_study(load_workflow(root / "protocol.toml"), str(path), workers=1, progress=False,
              dashboard=False, echo=lambda s: None)
    return str(path)


def test_one_row_per_frequency_ensemble_window_definition(small_store):
    t = protocol_table(small_store)
    assert tuple(t.columns) == COLUMNS
    assert set(t["T"]) == {5.0, 10.0}  # 20 and 50 s do not fit in a 10 s run
    assert MIXTURE in set(t["ensemble"]) and len(set(t["ensemble"])) == 4
    assert len(t) == 2 * 4 * 2 * 3
    mix = t[t["ensemble"] == MIXTURE]
    assert (mix["n"] == 24).all()  # three families of 8 pooled
    moving = t[t["definition"] != "all"]
    assert (moving["share_hi"] > moving["share_lo"]).all()  # no zero-width share interval
    assert t[t["definition"] == "all"][["share_lo", "share_hi"]].isna().all().all()
    assert t.equals(protocol_table(small_store))  # deterministic
