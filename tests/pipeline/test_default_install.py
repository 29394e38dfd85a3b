"""What the default install (no extras) runs: a venv that sees every package of this
environment except bokeh (the ``dashboard`` extra) and pyarrow (the ``parquet`` extra) runs
`bbb run` and `bbb reduce` of a tiny scene -- workers included, which start from the same
python.  Its site-packages is a view of this environment's (one symlink per entry, those two
left out) and this checkout; ~15 s on a loaded 2-core machine."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.execute.cluster import NO_DASHBOARD
from pipeline.tables.reduce import NO_PARQUET

from .helpers import TINY

ROOT = Path(__file__).resolve().parents[2]
#: the top-level packages only an extra installs
EXTRAS_ONLY = ("bokeh", "pyarrow")


@pytest.fixture(scope="module")
def default_python(tmp_path_factory) -> Path:
    """The python of a venv without bokeh and pyarrow (asserted: neither can be found)."""
    base = tmp_path_factory.mktemp("default")
    view = base / "site"
    view.mkdir()
    for sp in (Path(p) for p in sys.path if p.endswith("site-packages")):
        for entry in sp.iterdir():
            if not entry.name.lower().startswith(EXTRAS_ONLY) and not (view / entry.name).exists():
                (view / entry.name).symlink_to(entry)
    venv = base / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    py = venv / "bin" / "python"
    site = Path(subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()"
                                "['purelib'])"], check=True, capture_output=True, text=True
                               ).stdout.strip())
    (site / "zz_view.pth").write_text(f"{view}\n{ROOT}\n")
    found = subprocess.run([str(py), "-c", "import importlib.util as u; print([u.find_spec(m) "
                            f"is not None for m in {EXTRAS_ONLY!r}])"], check=True,
                           capture_output=True, text=True).stdout.strip()
    assert found == "[False, False]"
    return py


@pytest.fixture(scope="module")
def ran(default_python, tmp_path_factory) -> tuple[subprocess.CompletedProcess, ...]:
    """`bbb run` and `bbb reduce` of a tiny scene in that venv: (run, reduce, the folder)."""
    cwd = tmp_path_factory.mktemp("default_run")
    (cwd / "tiny.toml").write_text(TINY)

    def bbb(*argv: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(default_python), "-m", "pipeline", *argv], cwd=cwd,
                              capture_output=True, text=True, timeout=600)

    return (bbb("run", "tiny.toml", "--store", "tiny.zarr", "--no-progress"),
            bbb("reduce", "tiny.zarr", "--out", "tables"), cwd)


def test_the_default_install_runs_and_its_dashboard_line_says_how_to_get_one(ran):
    run = ran[0]
    assert run.returncode == 0, run.stderr[-2000:]
    assert f"dashboard: {NO_DASHBOARD}" in run.stdout
    assert "pip install 'bbb[dashboard]'" in NO_DASHBOARD


def test_the_default_install_reduces_to_csv_and_says_once_that_parquet_needs_pyarrow(ran):
    red, cwd = ran[1], ran[2]
    assert red.returncode == 0, red.stderr[-2000:]
    assert red.stderr.count(NO_PARQUET) == 1 and "pip install 'bbb[parquet]'" in NO_PARQUET
    assert sorted(p.name for p in (cwd / "tables").iterdir()) == [
        "counters.csv", "counters.csv-metadata.json", "diffusion.csv", "diffusion.csv-metadata.json"]
