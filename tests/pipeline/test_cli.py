"""The `bbb` command line: end to end through the real entry points, and usage errors."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from importlib import metadata
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pipeline.cli import UsageError, main

from .helpers import TINY, store_arrays

BBB = Path(sys.executable).with_name("bbb")
ROOT = Path(__file__).resolve().parents[2]


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



def test_bbb_run_called_in_process_puts_sigterms_handler_back(tmp_path):
    """`bbb run` turns SIGTERM into an interrupt while it runs (tests/cluster/test_map_on_slurm.py
    shows it cancelling SLURM jobs); main() called from Python leaves the handler as it was."""
    import signal

    before = signal.getsignal(signal.SIGTERM)
    assert main(["run", str(tmp_path / "missing.toml")]) == 2
    assert signal.getsignal(signal.SIGTERM) is before

def _snapshot(path) -> dict[str, bytes]:
    out = {}
    for root, _, files in os.walk(path):
        for f in files:
            p = os.path.join(root, f)
            out[p] = Path(p).read_bytes()
    return out


# -- bbb --version ----------------------------------------------------------------------------
def test_version_is_the_installed_package_version():
    """`bbb --version` says the version pip installed, which is pyproject.toml's."""
    res = run_cli("--version")
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert res.returncode == 0 and res.stdout == f"bbb {metadata.version('bbb')}\n"
    assert metadata.version("bbb") == pyproject


# -- bbb run --frequencies --------------------------------------------------------------------
def test_frequency_subset_reproduces_the_chunks_of_the_whole_sweep(reference, tiny_workflow,
                                                                   tmp_path, monkeypatch):
    """`bbb run WF --frequencies 60` computes the same bytes as the 60 Hz chunks of the full
    run of WF: every stored chunk file of every reproducible array, into its default store."""
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(tiny_workflow), "--frequencies", "60", "--workers", "1",
                 "--no-progress"]) == 0
    sub, full = tmp_path / "runs" / "tiny-60Hz.zarr", Path(reference[0])
    assert store_arrays(sub)["frequency"].tolist() == [60.0]
    fi = store_arrays(full)["frequency"].tolist().index(60.0)
    compared = 0
    for name in ("positions", "collisions", "n_recorded", "n_collisions", "n_sticks", "done"):
        chunks = sorted(p.relative_to(sub / name / "c") for p in (sub / name / "c").rglob("*")
                        if p.is_file())
        assert chunks, name
        for rel in chunks:
            twin = full / name / "c" / str(fi) / Path(*rel.parts[1:])
            assert (sub / name / "c" / rel).read_bytes() == twin.read_bytes(), (name, rel)
            compared += 1
    assert compared >= 6 * 4  # 2 families x 2 chunks of each array (done: one file per chunk)


@pytest.mark.parametrize("value, needle", [
    ("61", "--frequencies: 61 Hz not in {WF}; allowed: its frequencies (54, 60 Hz)"),
    ("60,abc", "argument --frequencies: 'abc' is not a number; allowed: comma-separated"),
    ("", "argument --frequencies: '' is not a number"),
    ("60,60", "argument --frequencies: 60 is repeated"),
    ("-60", "argument --frequencies: -60 is out of range; allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    ("2e5", "argument --frequencies: 2e5 is out of range; allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    ("nan", "argument --frequencies: nan is out of range"),
    ("60.0001", "argument --frequencies: 60.0001 is out of range; allowed: frequencies "
                "0.001 ≤ f ≤ 100000 (Hz), multiples of 0.001 Hz"),
])
def test_bad_frequencies_exit_2_in_one_line(value, needle, tiny_workflow, tmp_path, capsys):
    store = tmp_path / "s.zarr"
    rc = main(["run", str(tiny_workflow), f"--frequencies={value}", "--store", str(store)])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("bbb: error: ") and err.count("\n") == 1, err
    assert needle.format(WF=tiny_workflow) in err
    assert not store.exists()


# -- bbb reduce --workflow --------------------------------------------------------------------
def test_reduce_with_a_workflow_uses_its_analysis_settings_without_touching_the_store(
        reference, tmp_path, capsys):
    """fit_to = 0.5 of T = 0.9 t_max = 9 s: the fit ends at the 4.5 s lag (the default 0.25 T =
    2.25 s ends at the 2.0 s lag, the last sample lag below it on the 0.5 s grid), D changes,
    and the store stays byte for byte as it was."""
    wf = tmp_path / "wf.toml"
    wf.write_text(TINY.replace("n_resamples = 100", "n_resamples = 50") +
                  "[analysis]\nfit_to = 0.5\n")
    before = _snapshot(reference[0])
    assert main(["reduce", str(reference[0]), "--out", str(tmp_path / "new"),
                 "--workflow", str(wf)]) == 0
    assert main(["reduce", str(reference[0]), "--out", str(tmp_path / "old")]) == 0
    new = pd.read_csv(tmp_path / "new" / "diffusion.csv")
    old = pd.read_csv(tmp_path / "old" / "diffusion.csv")
    assert new["fit_to"].tolist() == [4.5, 4.5] and old["fit_to"].tolist() == [2.0, 2.0]
    moving = new["n_moving"] > 0
    assert (new.loc[moving, "D"] != old.loc[moving, "D"]).all()
    assert _snapshot(reference[0]) == before


def test_reduce_of_a_frequency_subset_accepts_the_whole_workflow(reference, tiny_workflow,
                                                                 tmp_path):
    """A --frequencies store (here: made by copying the full one's workflow at 60 Hz only)
    reduces with the workflow it was cut from."""
    from pipeline.commands.store import store_with_analysis_of

    store = store_with_analysis_of(str(reference[0]), str(tiny_workflow))
    assert store.study.frequencies == (54.0, 60.0)
    sub = tmp_path / "sub.toml"
    sub.write_text(TINY.replace("[54.0, 60.0]", "[60.0]"))
    with pytest.raises(UsageError, match=r"frequencies: store has 54 Hz, the workflow does not"):
        store_with_analysis_of(str(reference[0]), str(sub))


@pytest.mark.parametrize("edit, needle", [
    (lambda t: t.replace("t_max = 10.0", "t_max = 20.0"), "(accuracy.t_max: store 10.0, workflow 20.0)"),
    (lambda t: t.replace("seed = 7", "seed = 8"), "(seed: store 7, workflow 8)"),
    (lambda t: t.replace("[54.0, 60.0]", "[55.0, 60.0]"), "(frequencies: store has 54 Hz"),
    (lambda t: t.replace("[0.0, 150.0]", "[0.0, 100.0]"), "(families: store"),
    (lambda t: t.replace("chunk_size = 4", "chunk_size = 3"), "accuracy.chunk_size: 3 does not divide"),
])
def test_reduce_refuses_a_workflow_of_other_simulation_settings(edit, needle, reference, tmp_path,
                                                                capsys):
    wf = tmp_path / "wf.toml"
    wf.write_text(edit(TINY))
    before = _snapshot(reference[0])
    rc = main(["reduce", str(reference[0]), "--out", str(tmp_path / "t"), "--workflow", str(wf)])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("bbb: error: ") and err.count("\n") == 1, err
    assert needle in err and str(wf) in err
    assert not (tmp_path / "t" / "diffusion.csv").exists() and _snapshot(reference[0]) == before


def test_reduce_with_a_missing_workflow_exits_2(reference, tmp_path, capsys):
    assert main(["reduce", str(reference[0]), "--workflow", str(tmp_path / "no.toml")]) == 2
    assert "no such workflow file" in capsys.readouterr().err


def test_bbb_plot_writes_the_d_of_f_figures_of_a_store_beside_it(reference, tmp_path):
    import shutil

    store = Path(shutil.copytree(reference[0], tmp_path / "tiny.zarr"))
    assert main(["plot", str(store), "--format", "png"]) == 0
    files = sorted(p.name for p in (tmp_path / "tiny").glob("*"))
    assert files == ["curve_D_family_vs_frequency.png", "curve_D_vs_frequency.png"]


def test_bbb_plot_of_a_path_that_is_no_store_is_one_usage_line(tmp_path, capsys):
    assert main(["plot", str(tmp_path / "nothing.zarr")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no such store" in err


# -- a closed pipe, an unexpected exception -----------------------------------------------------
@pytest.mark.parametrize("command", ["status", "verify"])
def test_output_into_a_closed_pipe_ends_quietly_with_the_status_of_sigpipe(
        command, reference):
    """`bbb status X | head -1` with the reader gone before bbb writes (its end of the pipe
    closed at once, while bbb still imports): no traceback, nothing on stderr, 141."""
    proc = subprocess.Popen([str(BBB), command, str(reference[0])], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    proc.stdout.close()
    err = proc.stderr.read()
    assert proc.wait(timeout=300) == 141 and err == b""


def test_an_undecodable_chunk_no_check_foresees_is_one_line_naming_the_store(
        reference, tmp_path, capsys):
    """A done-marker chunk overwritten with garbage: one `bbb: error:` line naming the
    store, exit 2, never a traceback."""
    import shutil

    store = Path(shutil.copytree(reference[0], tmp_path / "s.zarr"))
    (store / "done/c/0/1/0").write_bytes(b"garbage")
    assert main(["status", str(store)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"bbb: error: {store}") and err.count("\n") == 1, err


def test_an_internal_error_is_one_line_and_bbb_debug_shows_its_traceback(
        reference, capsys, monkeypatch):
    """A bug (stood in for by a status table that raises): one line naming the store and the
    exception, exit 2; with BBB_DEBUG=1 the exception goes through, for its traceback."""
    import pipeline.store.status as status

    def bug(store):
        raise RuntimeError("a bug")

    monkeypatch.setattr(status, "status_text", bug)
    monkeypatch.delenv("BBB_DEBUG", raising=False)
    assert main(["status", str(reference[0])]) == 2
    assert capsys.readouterr().err == (f"bbb: error: {reference[0]}: RuntimeError: a bug "
                                       "(unexpected; BBB_DEBUG=1 shows the traceback)\n")
    monkeypatch.setenv("BBB_DEBUG", "1")
    with pytest.raises(RuntimeError, match="a bug"):
        main(["status", str(reference[0])])
