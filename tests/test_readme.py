"""The README's first screen: its own-study example runs as written (the TOML, the three `bbb`
commands, the Python lines) and fits in the first 60 lines."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
SECTION = README.split("## Your own study", 1)[1].split("\n## ", 1)[0]


def blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", SECTION, flags=re.S)


def test_the_own_study_example_ends_within_the_first_60_lines():
    last = blocks("python")[-1].strip().splitlines()[-1]
    line = next(i for i, text in enumerate(README.splitlines(), 1) if text == last)
    assert line <= 60


def test_the_first_screen_holds_install_the_two_commands_and_no_issue_numbers_or_dates():
    screen = "\n".join(README.splitlines()[:60])
    for needed in ("## Install", "pip install .", "make venv", "make figures", "make test",
                   "## Your own study", "bbb plot"):
        assert needed in screen, needed
    assert not re.search(r"\bissue \d+|#\d+\b|\b20\d\d-\d\d-\d\d\b", screen)


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


def test_the_readme_own_study_example_runs_as_written(tmp_path):
    (toml,), (sh,), (py,) = blocks("toml"), blocks("sh"), blocks("python")
    name = re.search(r'`([\w.]+\.toml)`', SECTION).group(1)
    (tmp_path / name).write_text(toml, encoding="utf-8")
    bbb = str(Path(sys.executable).with_name("bbb"))
    commands = [c.split("#")[0].split() for c in sh.strip().splitlines()]
    assert [c[:2] for c in commands] == [[".venv/bin/bbb", "plan"], [".venv/bin/bbb", "run"],
                                         [".venv/bin/bbb", "reduce"], [".venv/bin/bbb", "plot"]]
    for cmd in commands:
        subprocess.run([bbb, *cmd[1:]], cwd=tmp_path, check=True, capture_output=True, timeout=300)
    table = pd.read_csv(tmp_path / "runs" / "my" / "diffusion.csv")
    assert list(table["f"]) == [60.0, 72.0] * 2 and list(table["alpha"]) == [0.5] * 2 + [0.7] * 2
    assert (table["D"] > 0).all()
    assert (tmp_path / "runs" / "my" / "map_D_frequency-alpha.png").stat().st_size > 1000
    out = subprocess.run([sys.executable, "-c", py], cwd=tmp_path, check=True,
                         capture_output=True, text=True, timeout=300).stdout
    assert "D_lo" in out and "60.0" in out and "72.0" in out and "0.7" in out


def test_the_readmes_map_numbers_are_the_committed_benchmarks():
    """The numbers quoted under "Maps at scale" are read off the results files, not typed."""
    results = ROOT / "benchmarks" / "results"
    scale = (results / "maps-scale-2026-11-25.txt").read_text(encoding="utf-8")
    plan = (results / "maps-plan-2026-11-25.txt").read_text(encoding="utf-8")
    text = README.split("Maps at scale", 1)[1].split("\n\n", 1)[0]

    def cell(table: str, row: str, col: int) -> str:
        line = next(ln for ln in table.splitlines() if ln.startswith(f"| {row}"))
        return line.split("|")[col].strip()

    quoted = [cell(scale, "task graph built", 2), cell(scale, "open_study", 2),
              cell(scale, "compute wall", 4), cell(plan, "CPU in tasks, s (probes)", 4),
              cell(plan, "CPU in tasks, s (all)", 4)]
    assert re.findall(r"\d+\.\d+", text) == quoted


def test_the_readmes_map_costs_are_the_committed_results():
    """The maps' planned and measured costs are copied from their results file, row by row."""
    results = (ROOT / "benchmarks" / "results" / "map-costs-2026-11-25-default.md").read_text(
        encoding="utf-8")
    rows = [ln for ln in results.splitlines() if ln.startswith("|")]
    assert len(rows) >= 4
    shown = README.split("<!-- map costs:", 1)[1].split("\n\n", 1)[0].splitlines()[1:]
    assert shown == rows


def test_every_maps_default_plan_is_within_30_percent_of_what_it_cost():
    """The README says so: every ratio measured / planned of the default plans' rows."""
    results = (ROOT / "benchmarks" / "results" / "map-costs-2026-11-25-default.md").read_text(
        encoding="utf-8")
    rows = [ln for ln in results.splitlines()
            if ln.startswith("| `") and "not the default" not in ln]
    ratios = [float(r) for ln in rows for r in re.findall(r"\((\d+\.\d+)\)", ln)]
    assert len(rows) == 5 and len(ratios) == 15
    assert all(0.7 <= r <= 1.3 for r in ratios), ratios


def _prose(section: str) -> str:
    """The first paragraph under a README heading, its lines joined."""
    return " ".join(README.split(section, 1)[1].strip().split("\n\n", 1)[0].split())


def test_the_readmes_stopping_rule_is_figure2s_scene_and_its_table():
    """The rule's numbers are the scene's; the rows the resolution stopped above D ~ 0 are
    counted from the committed Fig. 2 table."""
    from pipeline.store.layout import STOP_LEGEND, TARGET, ZERO
    from pipeline.workflow.load import load_workflow

    study = load_workflow(ROOT / "workflows" / "figure2.toml")
    acc = study.accuracy
    text = _prose("## What `make figures` computes")
    table = pd.read_csv(ROOT / "figures" / "diffusion_figure2.csv")
    above = table[(table["stop"] == STOP_LEGEND[ZERO]) & (table["D"] > acc.d_resolved)]
    rel = ((above["D_hi"] - above["D_lo"]) / 2 / above["D"]).max()
    for quoted in (f"{len(study.points)} frequencies", f"≤ {100 * acc.target_ci:g} % of D",
                   f'("{STOP_LEGEND[TARGET]}") or ≤ {acc.d_resolved:g} mm²/s ("{STOP_LEGEND[ZERO]}")',
                   f"{acc.max_particles} particles", f"D < {acc.d_resolved / acc.target_ci:.0f} mm²/s",
                   f"{len(above)} frequencies of {above['f'].min():g}–{above['f'].max():g} Hz",
                   f"D of {above['D'].min():.0f}–{above['D'].max():.0f} mm²/s",
                   f"up to {100 * rel:.1f} % of D"):
        assert quoted in text, quoted
