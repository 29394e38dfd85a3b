"""Do two D(f) tables agree?  Prints one row per frequency and the share that agree.

    python -m benchmarks.checks.agreement OLD.csv NEW.csv [--workflow NEW.toml | --d-resolved D]
                                   [--min-share 0.95]

Both tables are `bbb reduce` CSVs (columns f, D, D_lo, D_hi, mm²/s; optionally stop).  At each
frequency both hold, one of two rules judges (column "by"):

* **resolution** ("res"), where a table says sampling stopped as "resolved to ±d_resolved" (column stop;
  every family): that scene measured D only to ±d_resolved (its CI's half-width reached
  d_resolved, docs/accuracy.md), so the two agree when both |D| ≤ d_resolved, or else by the
  CI rule below.  d_resolved is read from the target-driven scene's workflow (--workflow) or
  given (--d-resolved, mm²/s).
* **CI** ("ci") everywhere else: the difference D_new − D_old is compared with the combined
  half-width √(h_old² + h_new²), each h the CI's half on the side facing the other value
  (bootstrap CIs are not symmetric).

A D whose CI lies wholly below 0 is an estimator failure (the pipeline's rule,
docs/statistics.md), as is a missing D (NaN).  A row where one table has no D is "n/a" and
counts as not agreeing; a row where neither has one ("none") is not compared and leaves the
share's denominator.  Exit 1 when the share of agreeing frequencies is below --min-share (the
target-driven Fig. 2 must agree with the fixed-ensemble one at ≥ 95 % of frequencies).

The CI rule is a 95 % test of D_new = D_old, so two correct tables miss it at ~5 % of the
frequencies it judges, and a 95 % requirement is met by correct tables only about half the
time.  The last line therefore also gives the chance of at least as many CI misses if both
tables were right (binomial, p = 0.05): a small value, not the share, says they differ.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from typing import NamedTuple

#: the stop text of pipeline.store.layout.STOP_LEGEND for a CI half-width <= d_resolved
RESOLVED = "resolved to ±d_resolved"


class Row(NamedTuple):
    """One compared frequency: f Hz, D mm²/s, z (CI rule), by ("ci"/"res"), agrees, note."""

    f: float
    d_old: float
    d_new: float
    z: float
    by: str
    agrees: bool
    note: str = ""


def _num(v: str | None) -> float:
    try:
        return float(v) if v not in (None, "") else math.nan
    except ValueError:
        return math.nan


def read_table(path: str) -> dict[float, tuple[float, float, float, bool]]:
    """{f: (D, D_lo, D_hi, resolved zero?)} of a reduce CSV."""
    with open(path, newline="") as fh:
        return {round(float(r["f"]), 6): _measured(_num(r["D"]), _num(r["D_lo"]),
                                                   _num(r["D_hi"]), _resolved(r.get("stop") or ""))
                for r in csv.DictReader(fh)}


def _measured(d: float, lo: float, hi: float, resolved: bool) -> tuple[float, float, float, bool]:
    """A D significantly below 0 (hi < 0) is no measurement: NaN, as the pipeline reports it."""
    if hi < 0:
        d = lo = hi = math.nan
    return d, lo, hi, resolved


def _resolved(stop: str) -> bool:
    """Whether every family of a stop text (RESOLVED, or "rest: " RESOLVED "; ...")
    stopped as RESOLVED."""
    parts = [p.strip() for p in stop.split(";") if p.strip()]
    return bool(parts) and all(p.endswith(RESOLVED) for p in parts)


def _facing_half(d: float, lo: float, hi: float, other: float) -> float:
    """The CI's half-width on the side of ``d`` that faces ``other`` (mm²/s)."""
    return (hi - d) if other >= d else (d - lo)


def _z(old: tuple, new: tuple) -> float:
    (d0, lo0, hi0, _), (d1, lo1, hi1, _) = old, new
    h = math.hypot(_facing_half(d0, lo0, hi0, d1), _facing_half(d1, lo1, hi1, d0))
    return (d1 - d0) / h if h > 0 else (0.0 if d1 == d0 else math.inf)


def compare(old: dict, new: dict, d_resolved: float | None = None) -> list[Row]:
    """One :class:`Row` per frequency in both tables (module docstring for the rules)."""
    rows = []
    for f in sorted(set(old) & set(new)):
        d0, d1 = old[f][0], new[f][0]
        if not (math.isfinite(d0) or math.isfinite(d1)):
            rows.append(Row(f, d0, d1, math.nan, "none", False, "no D in either table: not compared"))
            continue
        if not (math.isfinite(d0) and math.isfinite(d1)):
            rows.append(Row(f, d0, d1, math.nan, "n/a", False, "no D in a table"))
            continue
        z = _z(old[f], new[f])
        ci_ok = bool(abs(z) <= 1.0)  # NaN (an unbounded side) does not agree
        if (old[f][3] or new[f][3]) and d_resolved is not None:
            res_ok = abs(d0) <= d_resolved and abs(d1) <= d_resolved
            rows.append(Row(f, d0, d1, z, "res", res_ok or ci_ok,
                            f"both |D| <= {d_resolved:g}" if res_ok else ""))
        else:
            rows.append(Row(f, d0, d1, z, "ci", ci_ok))
    return rows


def _d_resolved(args) -> float | None:
    if args.d_resolved is not None:
        return args.d_resolved
    if args.workflow:
        from pipeline.workflow.load import parse_workflow

        with open(args.workflow) as fh:
            return parse_workflow(fh.read(), args.workflow).accuracy.d_resolved
    return None


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--workflow", help="the target-driven scene's workflow (its d_resolved)")
    ap.add_argument("--d-resolved", type=float, help="d_resolved, mm²/s (instead of --workflow)")
    ap.add_argument("--min-share", type=float, default=0.95)
    a = ap.parse_args(argv)
    d_res = _d_resolved(a)
    rows = compare(read_table(a.old), read_table(a.new), d_res)
    if not rows:
        print("no common frequencies", file=sys.stderr)
        return 2
    print(f"{'f/Hz':>7} {'D_old':>11} {'D_new':>11} {'z':>7} {'by':>4}  agrees")
    for r in rows:
        print(f"{r.f:7.2f} {r.d_old:11.4g} {r.d_new:11.4g} {r.z:7.2f} {r.by:>4}  "
              f"{'-' if r.by == 'none' else 'yes' if r.agrees else 'NO'}{f'  ({r.note})' if r.note else ''}")
    none = sum(r.by == "none" for r in rows)
    rows = [r for r in rows if r.by != "none"]
    if not rows:
        print("no frequency where either table measures D", file=sys.stderr)
        return 2
    n_ok = sum(r.agrees for r in rows)
    share = n_ok / len(rows)
    res = [r for r in rows if r.by == "res"]
    print(f"{n_ok}/{len(rows)} frequencies agree ({100 * share:.1f} %; required "
          f"{100 * a.min_share:.0f} %): within the combined 95 % CIs, or, at the {len(res)} "
          f"frequencies that stopped as {RESOLVED}, at the scene's resolution "
          + (f"(both |D| <= d_resolved = {d_res:g} mm²/s)" if d_res is not None else
             "(not applied: no d_resolved given)")
          + f"; by the CIs alone {sum(r.by != 'n/a' and abs(r.z) <= 1 for r in rows)}"
          f"/{len(rows)}; n/a {sum(r.by == 'n/a' for r in rows)}; not compared (no D in "
          f"either table) {none}")
    judged = [r for r in rows if r.by == "ci" or (r.by == "res" and not r.note)]
    misses = sum(not r.agrees for r in judged)
    print(f"CI misses {misses} of {len(judged)} judged by the CIs; P(>= {misses} | both right, "
          f"5 % each) = {binom_tail(misses, len(judged), 0.05):.2f}")
    return 0 if share >= a.min_share else 1


def binom_tail(k: int, n: int, p: float) -> float:
    """P(X >= k) for X ~ Binomial(n, p)."""
    return sum(math.comb(n, i) * p ** i * (1 - p) ** (n - i) for i in range(k, n + 1))


if __name__ == "__main__":
    sys.exit(main())
