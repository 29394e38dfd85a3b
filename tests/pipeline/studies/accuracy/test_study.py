"""The accuracy study (issue 5): Pareto front, error scaling, and a tiny study through the real
pipeline (tiny workflow, 1 worker, a few seconds of simulation)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pipeline.studies.accuracy.study import (
    ROW_COLUMNS,
    SCALING_COLUMNS,
    SUMMARY_COLUMNS,
    Variant,
    pareto_front,
    run_accuracy_study,
    variant_study,
)
from pipeline.workflow.accuracy import ACCURACY_KNOBS, ACCURACY_PRESETS
from pipeline.workflow.load import parse_workflow

TINY_REF = """\
[study]
name = "tinyacc"
seed = 11

[params]
preset = "klages2004"

[frequencies]
values = [60.0, 72.0]

[families.launched]
initial = "launched"
launch_speed = [0.0, 200.0]

[accuracy]
preset = "reference"
n_particles = 32
chunk_size = 16
t_max = 24.0
sample_dt = 0.5
n_resamples = 100

[observables.positions]
"""


# --- Pareto front ----------------------------------------------------------------------------
def test_pareto_front_is_exactly_the_non_dominated_points():
    rng = np.random.default_rng(0)
    cost, err = rng.lognormal(size=60), rng.lognormal(size=60)
    err[3] = np.nan  # an unmeasured error is never on the front
    front = pareto_front(cost, err)
    assert not front[3]
    ok = np.isfinite(err)
    for i in range(cost.size):
        if not ok[i]:
            continue
        dominated = ok & (cost <= cost[i]) & (err <= err[i]) & ((cost < cost[i]) | (err < err[i]))
        assert front[i] == (not dominated.any())
    # the front, ordered by cost, has strictly falling error
    order = np.argsort(cost[front])
    assert np.all(np.diff(err[front][order]) < 0)
    assert pareto_front(np.array([1.0, 2.0, 3.0]), np.array([3.0, 1.0, 2.0])).tolist() == [
        True, True, False]


# --- statistical error: 1/sqrt(N), not 1/sqrt(t_max), at fractional fit lags ------------------


# --- variants --------------------------------------------------------------------------------
def test_variant_study_replaces_only_the_accuracy():
    ref = parse_workflow(TINY_REF)
    v = variant_study(TINY_REF, Variant("v_stick-0.1", "knob", {"preset": "reference",
                                                                "v_stick": 0.1}, "v_stick", 0.1))
    assert v.accuracy.v_stick == 0.1 and v.accuracy.t_max == ACCURACY_PRESETS["reference"]["t_max"]
    assert (v.frequencies, v.families, v.base_params, v.seed) == (
        ref.frequencies, ref.families, ref.base_params, ref.seed)
    assert v.name == "tinyacc-v_stick-0.1"
    p = variant_study(TINY_REF, Variant("paper", "preset", {"preset": "paper"}))
    assert {k: getattr(p.accuracy, k) for k in ACCURACY_KNOBS} == ACCURACY_PRESETS["paper"]


# --- a tiny study through the real pipeline --------------------------------------------------
@pytest.fixture(scope="module")
def tiny_study(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("acc")
    wf = tmp / "tinyacc.toml"
    wf.write_text(TINY_REF)
    ref = {k: getattr(parse_workflow(TINY_REF).accuracy, k) for k in ACCURACY_KNOBS}
    variants = [
        Variant("reference", "reference", {"preset": "reference", **ref}),
        # a prefix of the reference: same chunks and seeds, shorter run
        Variant("short", "knob", {"preset": "reference", **ref, "t_max": 12.0}, "t_max", 12.0),
        Variant("v_stick-0.1", "knob", {"preset": "reference", **ref, "v_stick": 0.1},
                "v_stick", 0.1),
        Variant("small", "preset", {"preset": "draft", "n_particles": 16, "chunk_size": 16,
                                    "t_max": 12.0, "n_resamples": 50}),
    ]
    res = run_accuracy_study(wf, tmp / "out", variants=variants, workers=1,
                             figure=tmp / "accuracy.png", echo=lambda s: None)
    return tmp, res


def test_tiny_study_tables_have_the_documented_columns(tiny_study):
    tmp, res = tiny_study
    assert list(res["rows"].columns) == list(ROW_COLUMNS)
    assert list(res["summary"].columns) == list(SUMMARY_COLUMNS)
    assert list(res["scaling"].columns) == list(SCALING_COLUMNS)
    for name in ("accuracy", "accuracy_summary", "accuracy_scaling"):
        assert pd.read_parquet(tmp / "out" / f"{name}.parquet").shape == res[
            {"accuracy": "rows", "accuracy_summary": "summary",
             "accuracy_scaling": "scaling"}[name]].shape
    assert (tmp / "accuracy.png").stat().st_size > 10_000
    rows = res["rows"]
    assert len(rows) == 4 * 2  # variants x frequencies (one family)
    # every row is judged against the reference variant's D at its frequency, in the
    # documented units (not the reference against itself)
    ref_D = rows[rows.variant == "reference"].set_index("f")["D"]
    np.testing.assert_allclose(rows.D_ref, ref_D.loc[rows.f].to_numpy(), rtol=1e-12)
    np.testing.assert_allclose(rows.err_rel, (rows.D - rows.D_ref) / rows.D_ref, rtol=1e-9)
    np.testing.assert_allclose(rows.z_ref, (rows.D - rows.D_ref) / rows.hw_ref, rtol=1e-9)
    assert (rows.cpu_s > 0).all() and (rows.collisions_per_cpu_s > 1e4).all()


def test_tiny_study_pareto_front_is_non_dominated(tiny_study):
    s = tiny_study[1]["summary"]
    cand = s[s.variant != "reference"]
    for _, a in cand[cand.pareto].iterrows():
        dominated = ((cand.cpu_s <= a.cpu_s) & (cand.err_rms <= a.err_rms)
                     & ((cand.cpu_s < a.cpu_s) | (cand.err_rms < a.err_rms)))
        assert not dominated.any()
    assert not s[s.variant == "reference"].pareto.any()


def test_a_shorter_run_is_exactly_a_prefix_of_the_reference(tiny_study):
    """The study measures t_max on the reference's own trajectories: that is only the same as
    running with a shorter t_max if the first seconds of a trajectory do not depend on it."""
    import zarr

    tmp = tiny_study[0]
    ref = zarr.open_group(str(tmp / "out" / "stores" / "reference.zarr"), mode="r")
    short = zarr.open_group(str(tmp / "out" / "stores" / "short.zarr"), mode="r")
    xs = np.asarray(short["positions"][...])
    np.testing.assert_array_equal(np.asarray(ref["positions"][..., : xs.shape[-1]]), xs)
    # and so the paired comparison of the prefix variant is exact: z_pair = 0
    rows = tiny_study[1]["rows"]
    short_rows = rows[rows.variant == "short"]
    np.testing.assert_allclose(short_rows.D, short_rows.D_pair, rtol=1e-12)


def test_tiny_study_scaling_rows(tiny_study):
    sc = tiny_study[1]["scaling"]
    n = sc[sc.axis == "N"]
    assert set(n.value) <= {16.0, 32.0} or len(n) == 0  # at most n_all / 4 per subset
    t = sc[sc.axis == "T"]
    assert (t.value < 24.0).all()


def test_cli_accuracy_usage_errors(tmp_path, capsys):
    from pipeline.cli import main

    assert main(["accuracy", str(tmp_path / "nope.toml")]) == 2
    assert "no such workflow file" in capsys.readouterr().err
    assert main(["accuracy", "--workers", "2", "--scheduler", "tcp://x:1"]) == 2
