"""Long studies, marked ``slow``: excluded from `make test`, run by `make test-slow`.

Each runs a real study end to end at a size between the suite's tiny ones and the committed
full runs (the full soak is 1e9 collisions, ~7 min on 2 cores: benchmarks/results/soak-*.txt).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[1]
BBB = Path(sys.executable).with_name("bbb")

pytestmark = pytest.mark.slow


def test_a_soak_sample_of_3e7_collisions_has_no_particle_below_the_surface():
    # the soak's own verdict: the target reached, nothing below the surface or non-finite,
    # no repaired velocity, over every case of the extremes table (~1 min on 2 cores)
    out = subprocess.run([sys.executable, "-m", "benchmarks.checks.soak", "--target", "3e7",
                          "--workers", "2", "--max-particles", "4000", "--sample", "200"],
                         capture_output=True, text=True, timeout=1800, cwd=ROOT)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    lines = out.stdout.splitlines()
    assert "verdict                 PASS" in lines
    assert any(line.startswith("particles below surface 0 ") for line in lines)


def test_the_smoke_study_runs_verifies_and_reduces(tmp_path):
    # the CLI path a user takes (`make smoke` plus `bbb verify`), ~1 min on 2 cores
    store, out = tmp_path / "smoke.zarr", tmp_path / "smoke"
    for args in (["run", str(ROOT / "workflows" / "smoke.toml"), "--store", str(store),
                  "--no-progress"],
                 ["verify", str(store)],
                 ["reduce", str(store), "--out", str(out)]):
        res = subprocess.run([str(BBB), *args], capture_output=True, text=True, timeout=1800)
        assert res.returncode == 0, (args[0], res.stdout[-2000:], res.stderr[-2000:])
    df = pd.read_parquet(out / "diffusion.parquet").set_index("f")
    # above the creeping band (60 and 72 Hz) every particle bounces and D > 0 with its CI
    for f in (60.0, 72.0):
        assert np.isfinite(df.loc[f, "D"]) and df.loc[f, "D_lo"] > 0, df.loc[f]
