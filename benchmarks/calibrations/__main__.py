"""Remake every committed calibration JSON (``make calibrate``).

    python -m benchmarks.calibrations [--out DIR] [--only JSON ...] [--check]

Runs each maker of :data:`benchmarks.calibrations.CALIBRATIONS` as ``python -m <module> <args>
--json <file>`` from the checkout's root, adds the ``maker`` record to what it wrote and puts
the JSON where the rule reads it (or under ``--out DIR``, at the same path from there).
``--check`` remakes into a scratch folder and compares with the committed JSONs instead
(:func:`benchmarks.calibrations.compare.differences`: provenance keys aside, equal within the
stated tolerance); it exits 1 when one differs.  Prints each maker's wall time: a full remake
takes hours on 2 cores (the contrast rule and the mirror pairs ~45 min each on a quiet machine).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.calibrations import CALIBRATIONS, Calibration
from benchmarks.calibrations.compare import differences, dump
from benchmarks.common import ROOT


def remake(cal: Calibration, dest: Path) -> float:
    """Run ``cal``'s maker, write its JSON with the maker record to ``dest``; wall seconds.
    Raises RuntimeError naming the maker when it fails or writes nothing."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / Path(cal.json).name
        t0 = time.perf_counter()
        res = subprocess.run([sys.executable, "-m", cal.module, *cal.args, "--json", str(out)], cwd=ROOT)
        seconds = time.perf_counter() - t0
        if res.returncode != 0 or not out.is_file():
            raise RuntimeError(f"{cal.script} {' '.join(cal.args)}: exit {res.returncode}"
                               + ("" if out.is_file() else ", no JSON written"))
        data = json.loads(out.read_text(encoding="utf-8"))
    data["maker"] = cal.maker()
    dest.write_text(dump(data), encoding="utf-8")
    return seconds


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, help="write under this folder instead of in place")
    ap.add_argument("--only", nargs="+", metavar="JSON", help="remake only these (paths as listed)")
    ap.add_argument("--check", action="store_true", help="remake into a scratch folder and compare")
    a = ap.parse_args(argv)
    known = {c.json: c for c in CALIBRATIONS}
    unknown = [j for j in a.only or () if j not in known]
    if unknown:
        print(f"calibrate: {', '.join(unknown)}: not a calibration; one of {', '.join(known)}",
              file=sys.stderr)
        return 2
    todo = [known[j] for j in a.only] if a.only else list(CALIBRATIONS)
    with tempfile.TemporaryDirectory() as scratch:
        base = Path(scratch) if a.check else (a.out or ROOT)
        total, bad = 0.0, 0
        for cal in todo:
            try:
                s = remake(cal, base / cal.json)
            except RuntimeError as exc:
                print(f"calibrate: {exc}", file=sys.stderr)
                return 2
            total += s
            note = ""
            if a.check:
                diff = differences(json.loads((base / cal.json).read_text(encoding="utf-8")),
                                   json.loads((ROOT / cal.json).read_text(encoding="utf-8")))
                bad += bool(diff)
                note = "  identical" if not diff else "  DIFFERS: " + "; ".join(diff[:5])
            print(f"calibrate: {cal.json}  {s:.0f} s{note}", file=sys.stderr, flush=True)
    print(f"calibrate: {len(todo)} calibrations, {total:.0f} s", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
