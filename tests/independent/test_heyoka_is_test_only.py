"""heyoka is in the test extra only: the project's runtime (bbb/, pipeline/) never imports it."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RUNTIME = ("bbb", "pipeline")


def test_no_runtime_module_imports_heyoka():
    pattern = re.compile(r"^\s*(import|from)\s+heyoka\b", re.MULTILINE)
    importing = [str(f.relative_to(ROOT)) for d in RUNTIME for f in sorted((ROOT / d).rglob("*.py"))
                 if pattern.search(f.read_text(encoding="utf-8"))]
    assert not importing
