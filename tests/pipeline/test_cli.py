"""The `bbb` command line: end to end through the real entry points, and usage errors."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline.cli import main

from .helpers import TINY, store_arrays

BBB = Path(sys.executable).with_name("bbb")


def run_cli(*args, cwd=None, module=False):
    cmd = [sys.executable, "-m", "pipeline", *args] if module else [str(BBB), *args]
    return subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=300)


def test_run_then_reduce_end_to_end(tiny_workflow, tmp_path):
    """`bbb run` on a 2-worker LocalCluster, then `bbb reduce`: the table exists, D is finite
    and positive where particles move."""
    run = run_cli("run", str(tiny_workflow), "--workers", "2", "--no-progress", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    summary = run.stdout.strip().splitlines()[-1]
    assert summary.startswith("tiny: 8/8 chunks done") and "collisions/s" in summary
    assert "dashboard" in run.stdout
    assert (tmp_path / "runs" / "tiny.zarr").is_dir()  # the default store path

    red = run_cli("reduce", "runs/tiny.zarr", cwd=tmp_path)
    assert red.returncode == 0, red.stderr
    df = pd.read_csv(tmp_path / "runs" / "tiny" / "diffusion.csv")
    moving = df["n_moving"] > 0
    assert moving.any() and np.isfinite(df["D"]).all() and (df.loc[moving, "D"] > 0).all()


def test_status_shows_done_per_frequency_and_family(reference, capsys):
    assert main(["status", str(reference[0])]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("tiny: 8/8 chunks done")
    assert out[1].split()[-2:] == ["rest", "launched"]
    assert out[2].split() == ["54", "2/2", "2/2"]


def test_python_dash_m_pipeline_is_the_cli(reference):
    res = run_cli("status", str(reference[0]), module=True)
    assert res.returncode == 0 and res.stdout.startswith("tiny: 8/8")


def test_usage_error_through_the_script_is_one_line_without_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TINY.replace("chunk_size = 4", "chunk_size = 3"))
    res = run_cli("run", str(bad), "--store", str(tmp_path / "s.zarr"))
    assert res.returncode == 2
    assert res.stderr.count("\n") == 1 and "Traceback" not in res.stderr
    assert f"{bad}:" in res.stderr and "accuracy.chunk_size" in res.stderr
    assert not (tmp_path / "s.zarr").exists()  # stopped before anything ran


@pytest.mark.parametrize("argv, needle", [
    ([], "required"),
    (["run"], "WORKFLOW"),
    (["frobnicate"], "invalid choice"),
    (["run", "wf.toml", "--workers", "0"], "--workers"),
    (["run", "wf.toml", "--workers", "two"], "--workers"),
    (["run", "/nonexistent/wf.toml"], "no such workflow file"),
    (["run", "wf.toml", "--scheduler", "tcp://127.0.0.1:1", "--workers", "2"], "--workers"),
    (["run", "WF", "--scheduler", "nonsense", "--store", "S"], "cannot reach a Dask scheduler"),
    (["reduce", "/nonexistent/s.zarr"], "no such store"),
    (["status", "/nonexistent/s.zarr"], "no such store"),
])
def test_usage_errors_exit_2_with_one_line(argv, needle, capsys, tiny_workflow, tmp_path):
    store = tmp_path / "s.zarr"
    argv = [str(tiny_workflow) if a == "WF" else str(store) if a == "S" else a for a in argv]
    assert main(argv) == 2
    assert not store.exists()
    err = capsys.readouterr().err
    assert err.startswith("bbb: error: ") and err.count("\n") == 1 and needle in err


def test_store_of_another_workflow_is_refused_and_left_unchanged(reference, tmp_path, capsys):
    other = tmp_path / "other.toml"
    other.write_text(TINY.replace("t_max = 10.0", "t_max = 20.0"))
    before = _snapshot(reference[0])
    assert main(["run", str(other), "--store", str(reference[0])]) == 2
    err = capsys.readouterr().err
    assert "different workflow" in err and "accuracy.t_max" in err and err.count("\n") == 1
    assert _snapshot(reference[0]) == before


def test_failed_task_exits_1_naming_the_chunk(tiny_workflow, tmp_path):
    env = dict(os.environ, BBB_FAIL_CHUNKS="54:rest:0")
    res = subprocess.run([str(BBB), "run", str(tiny_workflow), "--store", str(tmp_path / "f.zarr"),
                          "--workers", "1", "--no-progress"],
                         capture_output=True, text=True, env=env, timeout=300)
    assert res.returncode == 1 and "Traceback" not in res.stderr
    assert "f = 54 Hz, family rest, chunk 0 failed" in res.stderr
    assert not store_arrays(tmp_path / "f.zarr")["done"][0, 0, 0]


def _snapshot(path) -> dict[str, bytes]:
    out = {}
    for root, _, files in os.walk(path):
        for f in files:
            p = os.path.join(root, f)
            out[p] = Path(p).read_bytes()
    return out
