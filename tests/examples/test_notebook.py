"""examples/notebook.py runs, cell after cell as a notebook kernel runs it (Agg backend, in
an empty directory), and draws its two figures from the store it made: the example cannot
rot."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pipeline import open_study
from tests.pipeline.figure_store import assert_png_drawn

NOTEBOOK = Path(__file__).resolve().parents[2] / "examples" / "notebook.py"


def test_the_example_notebook_runs_and_plots_d_of_f_and_the_phase_space(tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    # exec, as a kernel does: __main__ has no file, so Dask's spawned workers do not re-run it
    code = f"exec(compile(open({str(NOTEBOOK)!r}).read(), 'notebook.py', 'exec'))"
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    for png in ("notebook_D.png", "notebook_phase_space.png"):
        assert_png_drawn(tmp_path / png, min_size=(400, 300))
    # what it plotted is the store's: D(f) as `bbb reduce` computes it, and collisions at 72 Hz
    from pipeline.cli import main as cli

    assert cli(["reduce", str(tmp_path / "runs" / "notebook.zarr"), "--out",
                str(tmp_path / "tables")]) == 0
    d = pd.read_parquet(tmp_path / "tables" / "diffusion.parquet")
    ds = open_study(tmp_path / "runs" / "notebook.zarr")
    assert d["f"].tolist() == [58.0, 60.0, 66.0, 72.0, 78.0]
    assert f"D(72 Hz) = {d.set_index('f').loc[72.0, 'D']:.0f} mm²/s" in out.stdout
    n = int(np.isfinite(ds.collisions.sel(frequency=72.0, family="rest", field="vy")).sum())
    assert f"{n} collisions plotted" in out.stdout and n > 100
