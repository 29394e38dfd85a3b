"""Do two D(f) tables agree within their combined 95 % CIs?  Prints one row per frequency.

    python benchmarks/agreement.py OLD.csv NEW.csv [--min-share 0.95]

Both tables are `bbb reduce` CSVs (columns f, D, D_lo, D_hi; mm²/s).  At each frequency both
hold, the difference D_new − D_old is compared with the combined half-width
√(h_old² + h_new²), each h the CI's half on the side facing the other value (bootstrap CIs are
not symmetric).  Exit 1 when the share of agreeing frequencies is below --min-share (issue 12:
the target-driven Fig. 2 must agree with the fixed-ensemble one at ≥ 95 % of frequencies).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys


def _read(path: str) -> dict[float, tuple[float, float, float]]:
    with open(path, newline="") as fh:
        return {round(float(r["f"]), 6): (float(r["D"]), float(r["D_lo"]), float(r["D_hi"]))
                for r in csv.DictReader(fh)}


def _facing_half(d: float, lo: float, hi: float, other: float) -> float:
    """The CI's half-width on the side of ``d`` that faces ``other`` (mm²/s)."""
    return (hi - d) if other >= d else (d - lo)


def compare(old: dict, new: dict) -> list[tuple[float, float, float, float, bool]]:
    """Rows (f, D_old, D_new, z, agrees) with z = (D_new − D_old) / combined half-width."""
    rows = []
    for f in sorted(set(old) & set(new)):
        (d0, lo0, hi0), (d1, lo1, hi1) = old[f], new[f]
        h = math.hypot(_facing_half(d0, lo0, hi0, d1), _facing_half(d1, lo1, hi1, d0))
        z = (d1 - d0) / h if h > 0 else (0.0 if d1 == d0 else math.inf)
        rows.append((f, d0, d1, z, abs(z) <= 1.0))
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--min-share", type=float, default=0.95)
    a = ap.parse_args(argv)
    rows = compare(_read(a.old), _read(a.new))
    if not rows:
        print("no common frequencies", file=sys.stderr)
        return 2
    print(f"{'f/Hz':>7} {'D_old':>11} {'D_new':>11} {'z':>7}  agrees")
    for f, d0, d1, z, ok in rows:
        print(f"{f:7.2f} {d0:11.4g} {d1:11.4g} {z:7.2f}  {'yes' if ok else 'NO'}")
    share = sum(r[4] for r in rows) / len(rows)
    print(f"{sum(r[4] for r in rows)}/{len(rows)} frequencies agree within the combined 95 % CIs "
          f"({100 * share:.1f} %; required {100 * a.min_share:.0f} %)")
    return 0 if share >= a.min_share else 1


if __name__ == "__main__":
    sys.exit(main())
