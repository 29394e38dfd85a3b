"""What every benchmark shares: the checkout's root, the CPU's name for a results header, and
another revision's bbb package extracted for side-by-side runs."""

from __future__ import annotations

import platform
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"


def cpu_name() -> str:
    """The CPU's model name (from /proc/cpuinfo), else what platform reports, else "unknown"."""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def baseline_tree(ref: str, tmp: str) -> tuple[str, str]:
    """``git archive REF bbb`` into ``tmp``; returns (directory, 'REF (short hash)')."""
    rev = subprocess.run(["git", "rev-parse", "--short", ref], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout.strip()
    arch = subprocess.run(["git", "archive", ref, "bbb"], cwd=ROOT, check=True,
                          capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", tmp], input=arch, check=True)
    return tmp, f"{ref} ({rev})"
