"""benchmarks/calibrations: every calibration JSON a rule reads is listed, names its maker (an
existing script and its inputs), and ``make calibrate`` remakes it (slow: hours on 2 cores)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from benchmarks.calibrations import CALIBRATIONS
from benchmarks.calibrations.__main__ import remake
from benchmarks.calibrations.compare import differences

ROOT = Path(__file__).resolve().parents[3]
#: committed JSONs under bbb/ and pipeline/ that are not calibrations: the claims registry's
#: frozen rule hashes (pipeline/studies/<study>/frozen.json, written by the registry itself) and
#: the onset study's no-fit predictions (predictions.json: theory, no threshold; its remake is
#: checked by tests/pipeline/studies/onset/test_predictions.py)
NOT_CALIBRATIONS = ("frozen.json", "predictions.json")


def committed_jsons() -> set[str]:
    out = subprocess.run(["git", "ls-files", "bbb/*.json", "pipeline/*.json", "tests/bbb/data/*.json"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    return {p for p in out if Path(p).name not in NOT_CALIBRATIONS}


@pytest.mark.parametrize("cal", CALIBRATIONS, ids=[c.json for c in CALIBRATIONS])
def test_each_committed_calibration_json_names_its_maker_and_the_maker_exists(cal):
    data = json.loads((ROOT / cal.json).read_text(encoding="utf-8"))
    assert data.get("maker") == cal.maker(), f"{cal.json}: remake it with make calibrate"
    assert (ROOT / data["maker"]["script"]).is_file(), data["maker"]["script"]


def test_every_calibration_json_in_bbb_and_pipeline_is_one_make_calibrate_remakes():
    # tests/bbb/data also holds the paper floor's bit hashes (a record of a kernel, not a calibration)
    listed = {c.json for c in CALIBRATIONS}
    assert committed_jsons() - listed == {"tests/bbb/data/paper_floor_bits.json"}
    assert listed <= committed_jsons()


def test_calibrate_refuses_a_json_it_does_not_make_in_one_line():
    res = subprocess.run([sys.executable, "-m", "benchmarks.calibrations", "--only", "bbb/nothing.json"],
                         cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 2
    assert res.stderr.count("\n") == 1 and "bbb/nothing.json: not a calibration" in res.stderr


@pytest.mark.slow
@pytest.mark.parametrize("cal", CALIBRATIONS, ids=[c.json for c in CALIBRATIONS])
def test_make_calibrate_remakes_the_committed_json(cal, tmp_path):
    # the tolerance is benchmarks/calibrations/compare.py's: provenance aside, numbers within 1e-9
    remake(cal, tmp_path / "made.json")
    made = json.loads((tmp_path / "made.json").read_text(encoding="utf-8"))
    committed = json.loads((ROOT / cal.json).read_text(encoding="utf-8"))
    assert differences(made, committed) == []
