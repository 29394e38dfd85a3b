"""Compare the committed tables (figures/*.csv) of the working tree with those of a git revision.

    python benchmarks/compare_tables.py --base REV [--dir figures]

Prints one line per table: identical, or which columns were added / removed and, for the
columns both hold, how many cells differ and the largest relative difference.  Timing columns
(wall time of the tasks) are never reproducible and are listed apart.  A regeneration of the
figures after a change that must not alter results (a refactor, a new kernel layout) should
print "identical" for every table; after a change of results it says exactly where.
"""

from __future__ import annotations

import argparse
import io
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

#: columns that hold wall times (not reproducible)
TIMING = ("task_seconds",)


def _at_rev(rev: str, path: str) -> str | None:
    try:
        return subprocess.run(["git", "show", f"{rev}:{path}"], check=True, capture_output=True,
                              text=True).stdout
    except subprocess.CalledProcessError:
        return None


def _tracked(rev: str, folder: str) -> list[str]:
    out = subprocess.run(["git", "ls-tree", "--name-only", f"{rev}:{folder}"], check=True,
                         capture_output=True, text=True).stdout.split()
    return sorted(f"{folder}/{n}" for n in out if n.endswith(".csv"))


def _cells_differ(a: pd.Series, b: pd.Series) -> tuple[int, float]:
    """(cells that differ, largest relative difference of the numeric ones)."""
    if pd.api.types.is_numeric_dtype(a) and pd.api.types.is_numeric_dtype(b):
        x, y = a.to_numpy(np.float64), b.to_numpy(np.float64)
        same = (x == y) | (np.isnan(x) & np.isnan(y))
        both = ~same & np.isfinite(x) & np.isfinite(y)
        rel = np.abs(x[both] - y[both]) / np.maximum(np.abs(x[both]), np.abs(y[both]))
        return int((~same).sum()), float(rel.max()) if rel.size else (np.nan if (~same).any() else 0.0)
    def text(s: pd.Series) -> pd.Series:
        return s.astype(object).fillna("<NA>").astype(str)

    same = (text(a) == text(b)).to_numpy()
    return int((~same).sum()), np.nan


def compare(base: str, folder: str) -> list[str]:
    lines = []
    new = sorted(str(p) for p in Path(folder).glob("*.csv"))
    old = _tracked(base, folder)
    for path in sorted(set(new) | set(old)):
        if path not in old:
            lines.append(f"{path}: new table")
            continue
        if path not in new:
            lines.append(f"{path}: removed")
            continue
        a = pd.read_csv(io.StringIO(_at_rev(base, path)))
        b = pd.read_csv(path)
        notes = []
        added = [c for c in b.columns if c not in a.columns]
        gone = [c for c in a.columns if c not in b.columns]
        if added:
            notes.append(f"columns added {added}")
        if gone:
            notes.append(f"columns removed {gone}")
        if len(a) != len(b):
            notes.append(f"rows {len(a)} -> {len(b)}")
        else:
            diffs, timing = [], []
            for c in a.columns:
                if c not in b.columns:
                    continue
                n, rel = _cells_differ(a[c], b[c])
                if n:
                    (timing if c in TIMING else diffs).append(f"{c} ({n} cells, max rel {rel:.2g})")
            if diffs:
                notes.append("differ: " + ", ".join(diffs))
            if timing:
                notes.append("timing only: " + ", ".join(timing))
        identical = not notes or all(n.startswith("timing only") for n in notes)
        lines.append(f"{path}: {'identical' if identical else ''}{'; '.join(notes) if not identical else ''}"
                     + (f" ({notes[0]})" if identical and notes else ""))
    return lines


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", required=True, help="git revision to compare with")
    ap.add_argument("--dir", default="figures", help="folder of the tables (default figures)")
    args = ap.parse_args(argv)
    for line in compare(args.base, args.dir):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
