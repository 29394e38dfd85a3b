"""benchmarks/ is a package run as modules: no script edits sys.path, every folder of scripts is a
package, and the scripts sit in the suite's folders, not loose at its top."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "benchmarks"
FOLDERS = {"calibrations", "bits", "checks", "perf", "studies"}


def sys_path_edits(path: Path) -> list[int]:
    """Lines of ``path`` that touch ``sys.path`` (insert, append, assignment, ...)."""
    return [node.lineno for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(node, ast.Attribute) and node.attr == "path"
            and isinstance(node.value, ast.Name) and node.value.id == "sys"]


def test_no_benchmark_edits_sys_path():
    found = {str(p.relative_to(ROOT)): lines for p in sorted(BENCH.rglob("*.py"))
             if (lines := sys_path_edits(p))}
    assert found == {}, f"run it as a module (python -m benchmarks....) instead: {found}"


def test_every_folder_of_benchmarks_is_a_package_of_the_suite():
    folders = {p.parent for p in BENCH.rglob("*.py")} - {BENCH}
    assert {p.name for p in folders} == FOLDERS
    assert all((p / "__init__.py").is_file() for p in [BENCH, *folders])


def test_only_the_shared_helpers_sit_at_the_top_of_benchmarks():
    assert {p.name for p in BENCH.glob("*.py")} == {"__init__.py", "common.py"}
