"""The ``bbb`` command of a non-editable install, run from a directory outside the repository:
shipped scenes by name (`bbb run smoke`, `bbb scenes`), then `bbb status --json` and `bbb plot`
of the store it made (runs/smoke.zarr below that directory, the default).

bbb is installed from a wheel into a fresh venv (the session's ``installed`` fixture,
tests/pipeline/conftest.py); the command is the ``bbb`` console-script entry point of the
installed distribution, loaded and called in that venv's python, so the test fails if the
editable checkout shadows the wheel (each run also prints and checks ``pipeline.__file__``).
Cost: the session's wheel (shared with other tests) and `bbb run smoke` in the new install:
the module took 47 s alone on a loaded 2-core machine, ~22 s inside `make test`.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pipeline.workflow.scenes import scene_names

from .helpers import run_outside

ROOT = Path(__file__).resolve().parents[2]

#: runs the installed `bbb` entry point with ARGV in the venv's python; first line: where
#: `pipeline` was imported from
BBB = ("import sys, pipeline\n"
       "from importlib.metadata import entry_points\n"
       "(bbb,) = entry_points(group='console_scripts', name='bbb')\n"
       "print(pipeline.__file__, flush=True)\n"
       "sys.exit(bbb.load()({argv!r}))\n")


def bbb(installed: Path, cwd: Path, *argv: str) -> list[str]:
    """stdout lines of the installed `bbb ARGV` run in ``cwd``, after checking that it ran
    the wheel's pipeline (installed beside ``installed``'s venv), not this checkout's."""
    lines = run_outside(installed, BBB.format(argv=list(argv)), cwd).splitlines()
    assert Path(lines[0]).is_relative_to(installed.parents[1]), lines[0]
    assert not Path(lines[0]).is_relative_to(ROOT)
    return lines[1:]


@pytest.fixture(scope="module")
def outside(installed, tmp_path_factory) -> Path:
    """A directory outside the repository in which the installed `bbb run smoke` has run."""
    cwd = tmp_path_factory.mktemp("outside")
    assert not cwd.resolve().is_relative_to(ROOT)
    bbb(installed, cwd, "run", "smoke", "--no-progress")
    return cwd


def test_the_installed_bbb_runs_a_shipped_scene_by_name_into_runs_below_the_cwd(outside):
    assert (outside / "runs" / "smoke.zarr" / "zarr.json").is_file()


def test_the_installed_bbb_scenes_lists_every_shipped_scene(installed, outside):
    lines = bbb(installed, outside, "scenes")
    assert [ln.split()[0] for ln in lines] == scene_names()
    smoke = next(ln for ln in lines if ln.startswith("smoke "))
    assert "? (bbb plan smoke)" in smoke and smoke.endswith("End-to-end check: run, store, reduce")


def test_the_installed_bbb_status_json_reads_the_store(installed, outside):
    got = json.loads("\n".join(bbb(installed, outside, "status", "runs/smoke.zarr", "--json")))
    assert got["name"] == "smoke" and got["chunks_done"] == got["chunks_total"] == 16


def test_the_installed_bbb_plot_draws_the_store(installed, outside):
    bbb(installed, outside, "plot", "runs/smoke.zarr", "--format", "png")
    assert list((outside / "runs" / "smoke").glob("*.png"))
