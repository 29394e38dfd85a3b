"""Remake every committed calibration JSON (``make calibrate``).

    python -m benchmarks.calibrations [--out DIR] [--only JSON ...] [--check]

Runs each maker of :data:`benchmarks.calibrations.CALIBRATIONS` as ``python -m <module> <args>
--json <file>`` from the checkout's root, adds the ``maker`` record to what it wrote and puts
the JSON where the rule reads it (or under ``--out DIR``, at the same path from there); what
the maker prints (its table) goes to the terminal and to benchmarks/results/<maker>-<date>.txt
(under ``--out DIR``: to DIR), the name the makers' tables are committed under.
``--check`` remakes into a scratch folder and compares with the committed JSONs instead
(:func:`benchmarks.calibrations.compare.differences`: provenance keys aside, equal within the
stated tolerance); it exits 1 when one differs.  Prints each maker's wall time: a full remake
takes about 2 h on 2 quiet cores (benchmarks/results/calibrate-2026-11-28.txt).
"""

from __future__ import annotations

import argparse
import datetime
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.calibrations import CALIBRATIONS, Calibration
from benchmarks.calibrations.compare import differences, dump
from benchmarks.common import RESULTS, ROOT


def log_name(cal: Calibration) -> str:
    """benchmarks/results/ name of the maker's printed table: contrast-calibration-<date>.txt."""
    return f"{cal.module.rsplit('.', 1)[1].replace('_', '-')}-{datetime.date.today()}.txt"


def remake(cal: Calibration, dest: Path, log: Path | None = None) -> float:
    """Run ``cal``'s maker, write its JSON with the maker record to ``dest`` (and what it
    prints to ``log`` as well as to stdout); wall seconds.  Raises RuntimeError naming the
    maker when it fails or writes nothing."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / Path(cal.json).name
        t0 = time.perf_counter()
        argv = [sys.executable, "-m", cal.module, *cal.args, "--json", str(out)]
        with subprocess.Popen(argv, cwd=ROOT, stdout=subprocess.PIPE, text=True) as proc:
            lines = []
            for line in proc.stdout:
                sys.stdout.write(line)
                lines.append(line)
        seconds = time.perf_counter() - t0
        if proc.returncode != 0 or not out.is_file():
            raise RuntimeError(f"{cal.script} {' '.join(cal.args)}: exit {proc.returncode}"
                               + ("" if out.is_file() else ", no JSON written"))
        if log is not None:
            log.parent.mkdir(parents=True, exist_ok=True)
            log.write_text("".join(lines), encoding="utf-8")
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
                log = None if a.check else (a.out or RESULTS) / log_name(cal)
                s = remake(cal, base / cal.json, log)
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
