"""What bbb reduce says on stderr about D values that must not be read as values
(pipeline.tables.notes), from real stores: synthetic positions written through the store's
own write_chunk and reduced by the real reduce_store, and a real run where nothing moves."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pandas as pd

from pipeline.execute.task import compute_chunk
from pipeline.store.study_store import StudyStore
from pipeline.tables.notes import DRIFT_TEXT, reduce_notes
from pipeline.tables.reduce import reduce_store
from pipeline.workflow.load import parse_workflow
from pipeline.workflow.observables.counters import COUNTERS

# One point, one family of 64 particles, x every 0.1 s for 20 s; the MSD is fitted over lags
# 5.4-8.1 s (fit_from 0.3, fit_to 0.45 of T = 18 s).
SYNTHETIC = """\
[study]
name = "synthetic"

[params]
preset = "klages2004"
{params}

[frequencies]
values = [80.0]

[families.rest]
initial = "rest"

[accuracy]
preset = "draft"
n_particles = 64
chunk_size = 64
t_max = 20.0
sample_dt = 0.1
n_resamples = 200

[observables.positions]

[analysis]
fit_from = 0.3
fit_to = 0.45
"""


def _store(tmp_path, x: np.ndarray, params: str = "") -> str:
    """A store of SYNTHETIC holding positions ``x`` (particle, time), mm, marked done."""
    study = parse_workflow(SYNTHETIC.format(params=params), source="synthetic.toml")
    store = StudyStore.create_or_open(tmp_path / "syn.zarr", study)
    values = {"positions": x, **{f"n_{c}": np.zeros(x.shape[0], np.int64) for c in COUNTERS}}
    store.write_chunk(0, 0, 0, values, seconds=0.0)
    return store.path


def _times() -> np.ndarray:
    return np.arange(201) * 0.1


def _reduce(path, tmp_path) -> tuple[pd.DataFrame, list[str]]:
    lines: list[str] = []
    df = reduce_store(path, tmp_path / "out", echo=lambda s: None, warn=lines.append)["diffusion"]
    return df, lines


def test_a_significantly_negative_d_is_blank_in_the_table_and_said_once_on_stderr(tmp_path):
    # particles rocking with a 9 s period: their MSD falls over lags 5.4-8.1 s, D < 0
    amp = np.random.default_rng(0).uniform(0.5, 1.5, 64)[:, None]
    df, lines = _reduce(_store(tmp_path, amp * np.sin(2 * np.pi * _times() / 9.0)), tmp_path)
    assert math.isnan(df["D"][0]) and df["D_status"][0].startswith("estimator failed: fit D = -")
    (line,) = lines
    assert line.startswith("synthetic: warning: D < 0 significantly") and "1 point (80 Hz)" in line


def test_a_diffusing_ensemble_gives_no_line(tmp_path):
    steps = np.random.default_rng(1).standard_normal((64, 201)) * 0.3
    df, lines = _reduce(_store(tmp_path, np.cumsum(steps, axis=1)), tmp_path)
    assert df["D"][0] > 0 and lines == []


def test_d_with_the_drift_included_points_to_d_drift(tmp_path):
    # a conveyor (tilt 5 deg): every particle drifts at -2 mm/s with a little noise
    steps = np.random.default_rng(2).standard_normal((64, 201)) * 0.3 - 0.2
    df, lines = _reduce(_store(tmp_path, np.cumsum(steps, axis=1), "tilt = 5.0"), tmp_path)
    assert df["v_hi"][0] < 0 and df["D"][0] > 10 * df["D_drift"][0]
    (line,) = lines
    assert "D includes the drift" in line and "about the drift is D_drift" in line
    assert df["D_status"][0].endswith(DRIFT_TEXT)  # the row says so too, without the note


def test_a_conveyor_without_a_significant_drift_keeps_d_status_plain(tmp_path):
    steps = np.random.default_rng(1).standard_normal((64, 201)) * 0.3
    df, lines = _reduce(_store(tmp_path, np.cumsum(steps, axis=1), "tilt = 5.0"), tmp_path)
    assert df["v_lo"][0] < 0 < df["v_hi"][0] and df["D_status"][0] == "ok" and lines == []


def test_reducing_a_store_where_nothing_moves_warns_nothing(tmp_path):
    # the paper's misprinted A = 0.01 mm (Γ = 0.15 at 60 Hz): the particles at rest stay put,
    # the launched ones after a decaying cascade -- simulated for real, chunk by chunk
    text = SYNTHETIC.format(params="A = 0.01").replace("[80.0]", "[60.0]").replace(
        '[families.rest]\ninitial = "rest"', '[families.rest]\ninitial = "rest"\n\n'
        '[families.launched]\ninitial = "launched"').replace("n_particles = 64", "n_particles = 8"
                                                             ).replace("chunk_size = 64",
                                                                       "chunk_size = 8")
    store = StudyStore.create_or_open(tmp_path / "still.zarr",
                                      parse_workflow(text, source="still.toml"))
    for mi in range(2):
        compute_chunk(store, 0, mi, 0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy RuntimeWarning would raise here
        df, lines = _reduce(store.path, tmp_path)
    assert (df["n_particles"] == 16).all() and lines == []


def test_the_notes_name_every_grid_axis_of_a_point():
    df = pd.DataFrame({"f": [80.0, 82.0], "alpha": [0.5, 0.6], "Gamma": [2.6, 2.7],
                       "D": [math.nan, 1.0], "D_status": ["estimator failed: ...", "ok"]})
    (line,) = reduce_notes("map", df)
    assert "1 point (80 Hz, alpha = 0.5)" in line
