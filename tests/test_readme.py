"""The README runs as written: every code block in it is run here (or, for the commands that
take hours or a cluster, dry-run), and a test below fails if a block is added that none runs.
Its own-study examples -- diffusion on the paper's floor and transport on a conveyor -- are
what a new user copies: written to a file, planned, run, reduced, plotted and opened in
xarray, with the commands as the README gives them."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
BBB = str(Path(sys.executable).with_name("bbb"))
FENCE = re.compile(r"^```(\w+)\n(.*?)^```", flags=re.S | re.M)


def all_blocks() -> list[tuple[str, str]]:
    """(language, text) of every fenced code block of the README, in order."""
    return FENCE.findall(README)


def section(heading: str) -> str:
    """The README's text under ``heading`` (a line as written, e.g. ``## Install``), up to the
    next heading of the same or a higher level."""
    level = heading.split(" ", 1)[0]
    text = README.split(f"\n{heading}\n", 1)[1]
    stop = re.search(rf"^#{{1,{len(level)}}} ", text, flags=re.M)
    return text[:stop.start()] if stop else text


def blocks(heading: str) -> list[tuple[str, str]]:
    """The code blocks under ``heading``, each recorded as run by this module."""
    found = FENCE.findall(section(heading))
    RUN.extend(found)
    return found


RUN: list[tuple[str, str]] = []
INSTALL = blocks("## Install")
TWO_COMMANDS = blocks("## Two commands")
DIFFUSION = blocks("### Diffusion on the paper's floor")
CONVEYOR = blocks("### Transport on a conveyor")
SHIPPED = blocks("### From a shipped scene")
PYTHON = blocks("## From Python")
CLUSTER = blocks("## On a cluster")


def commands(sh: str) -> list[list[str]]:
    """The commands of a shell block, comments dropped."""
    return [shlex.split(line.split("#")[0]) for line in sh.strip().splitlines()
            if line.split("#")[0].strip()]


def run_bbb(cmd: list[str], cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess:
    """``bbb ...`` as the README writes it, with this environment's bbb."""
    assert cmd[0] == "bbb", cmd
    return subprocess.run([BBB, *cmd[1:]], cwd=cwd, check=True, capture_output=True,
                          text=True, timeout=timeout)


def run_python(code: str, cwd: Path, timeout: float = 300) -> str:
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, check=True,
                          capture_output=True, text=True, timeout=timeout).stdout


def own_study(found: list[tuple[str, str]], tmp_path: Path) -> tuple[str, list[list[str]], str]:
    """Write the section's TOML under the name its text gives (``my.toml``), and return
    (study name, the shell block's commands, the Python block)."""
    (_, toml), (_, sh), (_, py) = found
    assert [lang for lang, _ in found] == ["toml", "sh", "python"]
    name = tomllib.loads(toml)["study"]["name"]
    (tmp_path / f"{name}.toml").write_text(toml, encoding="utf-8")
    cmds = commands(sh)
    assert [c[:2] for c in cmds] == [["bbb", "plan"], ["bbb", "run"], ["bbb", "reduce"],
                                     ["bbb", "plot"]]
    assert cmds[0][2] == cmds[1][2] == f"{name}.toml"
    assert cmds[2][2] == cmds[3][2] == f"runs/{name}.zarr"
    return name, cmds, py


# -- the README's shape ----------------------------------------------------------------------
def test_every_code_block_of_the_readme_is_run_by_a_test_here():
    assert sorted(RUN) == sorted(all_blocks())


def test_the_first_screen_holds_install_the_two_commands_and_no_issue_numbers_or_dates():
    screen = "\n".join(README.splitlines()[:60])
    for needed in ("## Install", "pip install .", "make venv", "make figures", "make test",
                   "## Your own study", "### Diffusion on the paper's floor", "bbb plot",
                   "[netcdf]"):
        assert needed in screen, needed
    assert not re.search(r"\bissue \d+|#\d+\b|\b20\d\d-\d\d-\d\d\b", README)


def test_the_conveyor_example_states_the_sign_of_v_and_names_d_drift():
    text = " ".join(section("### Transport on a conveyor").split())
    assert "**v < 0 is downhill**" in text and "`D_drift`" in text
    doc = tomllib.loads(CONVEYOR[0][1])
    # the sign as the workflow reference says it: the floor falls towards -x
    from pipeline.workflow.keys import PARAM_LONG_NAMES

    assert "downhill towards -x" in PARAM_LONG_NAMES["tilt"] and doc["params"]["tilt"] > 0


def test_user_facing_text_names_no_issue_of_ours():
    """Docs, scenes, docstrings and the README speak to users: no "issue 12" (an upstream
    project's "numba issue #4807" is a reference, not ours).  The kernel's sources are left
    out: their bytes are every store's kernel_hash, so a comment edited there would orphan
    every store; they are cleaned with the next kernel change."""
    from bbb.provenance import KERNEL_SOURCES

    kernel = {ROOT / "bbb" / name for name in KERNEL_SOURCES}
    files = [ROOT / "README.md", *ROOT.glob("docs/*.md"), *ROOT.glob("workflows/*.toml"),
             *ROOT.glob("pipeline/**/*.toml"), *ROOT.glob("pipeline/**/*.py"),
             *ROOT.glob("pipeline/**/*.md"), ROOT / "figures" / "REPORT.md",
             *(f for f in ROOT.glob("bbb/**/*.py") if f not in kernel)]
    hits = [f"{f.relative_to(ROOT)}:{i}" for f in files
            for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
            if re.search(r"\bissues? \d+", line, flags=re.I)]
    assert not hits, hits


# -- the blocks that take hours, a cluster or an install: dry-run ----------------------------
def test_the_install_and_two_command_blocks_name_make_targets_and_extras_that_exist():
    """`make -n TARGET` of each make line (the targets' real runs: `make test` is this
    suite, `make figures FAST=1` its installed test); each pip line's extras are the
    project's (`pip install` itself: tests/pipeline/test_installed_cli.py)."""
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    lines = commands(INSTALL[0][1]) + commands(TWO_COMMANDS[0][1])
    assert {c[0] for c in lines} == {"make", "pip"}
    for cmd in lines:
        if cmd[0] == "make":
            subprocess.run(["make", "-n", *cmd[1:]], cwd=ROOT, check=True, capture_output=True,
                           timeout=60)
        else:
            assert cmd[:2] == ["pip", "install"] and cmd[2].startswith(".")
            named = re.findall(r"\[([\w,]+)\]", cmd[2])
            assert all(e in extras for group in named for e in group.split(",")), cmd


def test_the_cluster_blocks_commands_parse_with_bbbs_own_parser():
    """A scheduler and SLURM are not here: each line is parsed by the real `bbb` parser (an
    option the README names that bbb lacks fails), and its scene exists where named."""
    from pipeline.cli import _build_parser
    from pipeline.workflow.scenes import scene_names

    cmds = commands(CLUSTER[0][1])
    assert cmds
    for cmd in cmds:
        args = _build_parser().parse_args(cmd[1:])
        assert args.command == cmd[1]
        if not args.workflow.endswith(".toml"):
            assert args.workflow in scene_names()


def test_the_shipped_scene_block_lists_shows_and_copies_a_scene(tmp_path):
    cmds = commands(SHIPPED[0][1])
    assert [c[:2] for c in cmds] == [["bbb", "scenes"]] * 2 + [["bbb", "new"]]
    listing = run_bbb(cmds[0], tmp_path).stdout
    scene = cmds[1][cmds[1].index("--show") + 1]
    assert re.search(rf"^{scene}\s", listing, flags=re.M)
    shown = run_bbb(cmds[1], tmp_path).stdout
    from pipeline.workflow.scenes import scene_path

    assert shown.split("\n", 1)[1] == scene_path(scene).read_text(encoding="utf-8")
    run_bbb(cmds[2], tmp_path)
    name = cmds[2][2]
    from pipeline.workflow.load import load_workflow, parse_workflow

    made, shipped = load_workflow(tmp_path / f"{name}.toml"), parse_workflow(shown)
    assert made.name == name and made.points == shipped.points
    assert made.accuracy == shipped.accuracy and made.families == shipped.families


# -- the own-study examples, as a new user runs them ------------------------------------------
def test_the_diffusion_example_runs_as_written(tmp_path):
    name, cmds, py = own_study(DIFFUSION, tmp_path)
    for cmd in cmds:
        run_bbb(cmd, tmp_path)
    table = pd.read_csv(tmp_path / "runs" / name / "diffusion.csv")
    doc = tomllib.loads(DIFFUSION[0][1])
    fs, alphas = doc["frequencies"]["values"], doc["grid"]["alpha"]
    assert list(table["f"]) == fs * len(alphas)
    assert list(table["alpha"]) == [a for a in alphas for _ in fs]
    assert (table["D"] > 0).all() and (table["D_lo"] < table["D_hi"]).all()
    assert (tmp_path / "runs" / name / "map_D_frequency-alpha.png").stat().st_size > 1000
    out = run_python(py, tmp_path)
    assert "D_lo" in out and all(f"{f:.1f}" in out for f in fs)


def test_the_conveyor_example_gives_v_of_f_with_cis_as_a_new_user_gets_it(tmp_path):
    """Copied from the README and run with its commands (plan, run, reduce, plot, then
    xarray): the drift v at every (f, α) of the scene, a steady drift's CI around v and
    never of zero width, the v(f) curves and v map drawn.  On a draft scene of 10 points:
    about 2.5 min on a loaded 2-core machine, the plan's pilot included."""
    name, cmds, py = own_study(CONVEYOR, tmp_path)
    for cmd in cmds:
        run_bbb(cmd, tmp_path)
    doc = tomllib.loads(CONVEYOR[0][1])
    fr = doc["frequencies"]
    fs = [fr["start"] + i * fr["step"] for i in range(int((fr["stop"] - fr["start"]) / fr["step"]) + 1)]
    table = pd.read_csv(tmp_path / "runs" / name / "diffusion.csv")
    assert sorted(zip(table["f"], table["alpha"], strict=True)) == sorted(
        (f, a) for f in fs for a in doc["grid"]["alpha"])
    steady = table[table["v_status"] == "ok"]
    assert len(steady) > 0 and table["v"].notna().all()
    assert ((steady["v_lo"] <= steady["v"]) & (steady["v"] <= steady["v_hi"])).all()
    assert (steady["v_hi"] > steady["v_lo"]).all()
    blank = table[~table["v_status"].isin(["ok", "by construction"])]
    assert blank["v_lo"].isna().all()  # never "v ± CI" where v is not a steady drift
    out_dir = tmp_path / "runs" / name
    for fig in ("curve_v_vs_frequency_by_alpha.png", "map_v_frequency-alpha.png"):
        assert (out_dir / fig).stat().st_size > 1000, fig
    from pipeline.tables.reduce import csv_units

    assert csv_units(out_dir / "diffusion.csv")["v"] == "mm/s"
    out = run_python(py, tmp_path)
    assert all(c in out for c in ("v_lo", "v_hi", "v_status", "D_drift"))
    assert all(f"{f:.1f}" in out for f in fs)
    code = (f"from pipeline import reduced_dataset\nds = reduced_dataset('runs/{name}.zarr')\n"
            "print(float(ds.tilt), float(ds.throw), ds.v.attrs['units'], dict(ds.v.sizes))")
    tilt, throw, unit, sizes = run_python(code, tmp_path).strip().split(" ", 3)
    assert (float(tilt), float(throw)) == (doc["params"]["tilt"], doc["params"]["throw"])
    assert unit == "mm/s" and sizes == str({"frequency": len(fs), "alpha": 2})
    # the figures a talk needs: titled with the scene and its tilt, v in a diverging map at 0
    from matplotlib.collections import QuadMesh

    from pipeline import reduced_dataset
    from pipeline.plot.figures import talk_figures

    figs = dict(talk_figures(reduced_dataset(tmp_path / "runs" / f"{name}.zarr"),
                             ("curve_v_vs_frequency_by_alpha", "map_v_frequency-alpha")))
    assert len(figs) == 2
    for fig in figs.values():
        assert name in fig.get_suptitle() and "tilt" in fig.get_suptitle(), fig.get_suptitle()
    mesh = next(m for m in figs["map_v_frequency-alpha"].findobj(QuadMesh) if m.get_gid() == "map")
    assert mesh.get_cmap().name == "RdBu_r" and mesh.norm(0.0) == 0.5


def test_the_from_python_block_runs_on_a_dask_client_and_writes_netcdf(tmp_path):
    """The block as written: a 2-worker Client, the smoke scene, its tables, netCDF (80 s on
    a loaded 2-core machine)."""
    (lang, py), = PYTHON
    assert lang == "python" and "client = Client(" in py
    out = run_python(py, tmp_path, timeout=900)
    assert out.splitlines()[0] == "(200, 201)" and "D_lo" in out and "72.0" in out
    import xarray as xr

    with xr.open_dataset(tmp_path / "smoke.nc") as nc:
        assert nc["D"].attrs["units"] == "mm^2/s" and nc.sizes["frequency"] == 4
