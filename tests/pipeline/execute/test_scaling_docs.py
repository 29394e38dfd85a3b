"""The scaling numbers of docs/cluster.md and of pipeline/execute/scale_plan.py's MEASURED are the
committed measurements' (benchmarks/results/scaling-*.txt), read here, not typed twice."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pipeline.execute.scale_plan import MEASURED

ROOT = Path(__file__).resolve().parents[3]
RESULTS = ROOT / "benchmarks" / "results"
DOC = (ROOT / "docs" / "cluster.md").read_text(encoding="utf-8")


def latest(kind: str) -> Path:
    files = sorted(RESULTS.glob(f"scaling-{kind}-*.txt"))
    assert files, f"no benchmarks/results/scaling-{kind}-*.txt"
    return files[-1]


def scaling_rows(text: str) -> list[dict]:
    """The rows of every scaling table (pipeline/execute/scale_plan.py's format), in order."""
    rows = []
    for line in text.splitlines():
        m = re.match(r"^\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)%\s+(\S+)", line)
        if m:
            rows.append({"n": int(m[1]), "wall": m[2], "speed_up": m[3], "eff": m[4],
                         "bound": m[5]})
    return rows


def table_rows(text: str) -> list[list[str]]:
    """The cells of the markdown table rows that start with a number."""
    return [[c.strip() for c in line.strip("|").split("|")] for line in text.splitlines()
            if re.match(r"^\|\s*\d", line)]


def doc_rows(section: str) -> list[list[str]]:
    start = DOC.index(section)
    end = DOC.find("\n#", start + 1)
    return table_rows(DOC[start:end if end > 0 else None])


def test_the_docs_predictions_for_the_dissipation_map_are_the_committed_ones():
    rows = scaling_rows(latest("dissipation").read_text())
    cached, cold = rows[:5], rows[5:10]
    want = [[str(r["n"]), r["wall"], c["wall"], r["speed_up"], f"{r['eff']} %", r["bound"]]
            for r, c in zip(cached, cold, strict=True) if r["n"] in (2, 8, 64, 256)]
    assert doc_rows("### Predicted: the D(f, alpha) map") == want


def test_the_docs_measured_points_are_the_committed_ones():
    for kind, section in (("validation", "### Measured: on this machine"),
                          ("slurm", "### Measured: on the SLURM test cluster")):
        have = table_rows(latest(kind).read_text())
        assert have, kind
        want = [[r[0], r[1], r[2], r[3], r[4], r[5]] for r in have]
        assert doc_rows(section) == want, kind


def test_the_models_overheads_are_the_measured_ones():
    text = latest("overheads").read_text()

    def number(pattern: str) -> float:
        m = re.search(pattern, text)
        assert m, pattern
        return float(m[1])

    imports = number(r"\| fresh process: imports \| ([\d.]+)")  # a new worker's, with its warm-up
    assert MEASURED.warm == pytest.approx(
        imports + number(r"\| fresh process: kernel load \(warm_numba\) \| ([\d.]+)"), abs=0.005)
    assert MEASURED.cold == pytest.approx(imports + number(
        r"\| fresh process: kernel load \(warm_numba\) \| [\d.]+ \| ([\d.]+)"), abs=0.005)
    assert MEASURED.worker_start == pytest.approx(number(r"worker_start = .* = ([\d.]+)"),
                                                  abs=0.005)
    per_task_ms = number(r"= ([\d.]+) ms per task on the serial")
    submit_ms = number(r"submit: ([\d.]+) ms per task")
    assert 1e3 * (MEASURED.sched + MEASURED.submit + MEASURED.result) == pytest.approx(
        per_task_ms, abs=0.01)
    assert 1e3 * MEASURED.submit == pytest.approx(submit_ms, abs=0.01)
    assert MEASURED.decide == pytest.approx(number(r"decide = ([\d.]+) s per chunk"), abs=5e-6)
    assert MEASURED.decide_fixed == pytest.approx(number(r"decide_fixed = ([\d.]+) s"),
                                                  abs=5e-5)
    assert MEASURED.end == pytest.approx(number(r"\| closed \| [\d.]+ \| ([\d.]+)"), abs=0.005)
    fixture = (RESULTS / "slurm-fixture-2026-11-25.txt").read_text()
    first_job = re.search(r"sbatch -> output file, 1st job\s+([\d.]+)", fixture)
    assert MEASURED.job_wait == pytest.approx(float(first_job[1]), abs=0.005)


def test_the_docs_chunk_size_sweep_is_the_committed_one():
    res = latest("dissipation").read_text()
    sweep = res[res.index("chunk sizes at 256 workers:"):]
    sweep = "\n".join(sweep.splitlines()[:sweep.splitlines().index(next(
        ln for ln in sweep.splitlines() if ln.startswith(">= 90 %"))) + 1])
    assert f"```\n{sweep}\n```" in DOC
