"""Bad input through the real CLI (issue 6): every malformed workflow file and command line
below exits with status 2 and one line `bbb: error: ...` naming the file, line and key (or the
argument) and what is allowed, with no traceback, and leaves an existing store byte for byte
as it was (no lock left behind either).

workflow/test_load.py checks what Study parsing says about each mistake; here the claim is the
command line's: the exit status, the single line on stderr, and a store left untouched.
Most cases run `pipeline.cli.main` in this process (fast); a few run the installed `bbb`
script and `python -m pipeline` as subprocesses, where a traceback would show.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import zarr

from pipeline.cli import main

from .helpers import TINY

BBB = Path(sys.executable).with_name("bbb")


def _sub(old: str, new: str):
    return lambda text: text.replace(old, new, 1)


def _param(line: str):
    return _sub('preset = "klages2004"', f'preset = "klages2004"\n{line}')


# id: (edit of TINY, line of the error or None, key, what the message must say is allowed)
WORKFLOWS = {
    "TOML syntax error": (_sub("seed = 7", "seed = = 7"), 3, "", "TOML syntax error"),
    "unknown key": (_sub("t_max = 10.0", "t_max = 10.0\ntmax = 5"), 23, "accuracy.tmax",
                    "allowed: preset, n_particles, chunk_size, t_max"),
    "unknown table": (lambda t: t + "[extras]\nx = 1\n", 31, "extras",
                      "allowed: study, params, frequencies"),
    "misspelled section": (_sub("[accuracy]", "[acuracy]"), 18, "acuracy",
                           "unknown section (did you mean 'accuracy'?); allowed: study, params"),
    "misspelled section of sub-tables only": (
        _sub("[observables.positions]", "[observablse.positions]"), 26, "observablse",
        "(did you mean 'observables'?); allowed: study, params"),
    "misspelled key": (_sub("record = 40", "recrd = 40"), 29, "observables.collisions.recrd",
                       "unknown key (did you mean 'record'?); allowed: record, record_from"),
    "string for an integer": (_sub("n_particles = 8", 'n_particles = "8"'), 20,
                              "accuracy.n_particles", "allowed: an integer > 0"),
    "float seed": (_sub("seed = 7", "seed = 1.5"), 3, "study.seed", "allowed: an integer 0 <= seed"),
    "negative seed": (_sub("seed = 7", "seed = -1"), 3, "study.seed", "allowed: an integer 0 <= seed"),
    "t_max nan": (_sub("t_max = 10.0", "t_max = nan"), 22, "accuracy.t_max", "allowed: s, > 0"),
    "t_max inf": (_sub("t_max = 10.0", "t_max = inf"), 22, "accuracy.t_max", "allowed: s, > 0"),
    "t_max negative": (_sub("t_max = 10.0", "t_max = -1.0"), 22, "accuracy.t_max", "allowed: s, > 0"),
    "alpha nan": (_param("alpha = nan"), 7, "params.alpha", "allowed: 0 < alpha ≤ 1"),
    "alpha 1.5": (_param("alpha = 1.5"), 7, "params.alpha", "allowed: 0 < alpha ≤ 1"),
    "alpha 0": (_param("alpha = 0.0"), 7, "params.alpha", "allowed: 0 < alpha ≤ 1"),
    "beta negative": (_param("beta = -0.1"), 7, "params.beta", "allowed: 0 ≤ beta ≤ 1"),
    "A negative": (_param("A = -0.1"), 7, "params.A", "allowed: 0 ≤ A ≤ 1e+06 (mm)"),
    "g inf": (_param("g = inf"), 7, "params.g", "allowed: 1 ≤ g ≤ 1e+08 (mm/s²)"),
    "S zero": (_param("S = 0.0"), 7, "params.S", "allowed: 1e-06 ≤ S ≤ 1e+06 (mm)"),
    "R < S/2": (_param("R = 0.5"), 7, "params.R", "allowed: S/2 = 1 ≤ R ≤ 1e+15"),
    "empty [frequencies] table": (_sub("values = [54.0, 60.0]", ""), 8, "frequencies",
                                  "empty: neither values nor start, stop, step; allowed: values = "
                                  "[60.0, 72.0] (Hz), or start = 50.0, stop = 90.0, step = 0.5"),
    "grid of frequencies without stop": (_sub("values = [54.0, 60.0]", "start = 50.0\nstep = 1.0"),
                                         9, "frequencies.stop", "allowed: values = [60.0, 72.0] "
                                         "(Hz), or start = 50.0, stop = 90.0, step = 0.5"),
    "empty frequency list": (_sub("[54.0, 60.0]", "[]"), 9, "frequencies.values",
                             "allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    "negative frequency": (_sub("[54.0, 60.0]", "[-54.0, 60.0]"), 9, "frequencies.values",
                           "allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    "nan frequency": (_sub("[54.0, 60.0]", "[54.0, nan]"), 9, "frequencies.values",
                      "allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    "string frequency": (_sub("[54.0, 60.0]", '["54"]'), 9, "frequencies.values",
                         "allowed: frequencies 0.001 ≤ f ≤ 100000 (Hz)"),
    "chunks do not divide the ensemble": (_sub("chunk_size = 4", "chunk_size = 3"), 21,
                                          "accuracy.chunk_size", "allowed: a divisor of n_particles"),
    "chunk_size 0": (_sub("chunk_size = 4", "chunk_size = 0"), 21, "accuracy.chunk_size",
                     "allowed: an integer > 0 dividing n_particles"),
    "sample_dt does not divide t_max": (_sub("sample_dt = 0.5", "sample_dt = 0.3"), 23,
                                        "accuracy.sample_dt", "allowed: a sample_dt that divides"),
    "tol_t too coarse": (_sub("n_resamples = 100", "n_resamples = 100\ntol_t = 1.0"), 25,
                         "accuracy.tol_t", "allowed: s, 1e-18 <= tol_t <= 1e-6"),
    "too few resamples": (_sub("n_resamples = 100", "n_resamples = 5"), 24,
                          "accuracy.n_resamples", "allowed: >= 10"),
    "unknown accuracy preset": (_sub('preset = "draft"', 'preset = "quick"'), 19,
                                "accuracy.preset", "allowed: draft, standard, paper, reference"),
    "unknown initial condition": (_sub('initial = "rest"', 'initial = "thrown"'), 12,
                                  "families.rest.initial", "allowed: rest, dropped, launched"),
    "launch speeds reversed": (_sub("[0.0, 150.0]", "[150.0, 0.0]"), 16,
                               "families.launched.launch_speed", "allowed: [lo, hi] mm/s"),
    "infinite launch speed": (_sub("[0.0, 150.0]", "[0.0, inf]"), 16,
                              "families.launched.launch_speed", "allowed: [lo, hi] mm/s"),
    "record_from beyond t_max": (_sub("record_from = 2.0", "record_from = 20.0"), 30,
                                 "observables.collisions.record_from",
                                 "allowed: s, 0 <= record_from < t_max = 10"),
    "record 0 collisions": (_sub("record = 40", "record = 0"), 29, "observables.collisions.record",
                            "allowed: post-collision states per particle, 1 <= record"),
    "no observables": (lambda t: t[: t.index("[observables.positions]")], None, "observables",
                       "allowed: [observables.positions] and/or [observables.collisions]"),
    "confidence level 1.5": (lambda t: t + "[analysis]\nci = 1.5\n", 32, "analysis.ci",
                             "allowed: confidence level, 0.5 <= ci < 1"),
    "store name with a path": (_sub('name = "tiny"', 'name = "../tiny"'), 2, "study.name",
                               "allowed: letters, digits"),
    "empty file": (lambda t: "", None, "frequencies", "allowed: values = [60.0, 72.0] (Hz), or "
                   "start = 50.0, stop = 90.0, step = 0.5 (Hz, an inclusive grid)"),
    # [grid] (TINY is 30 lines: [grid] is line 31, its first axis line 32)
    "grid key also in params": (lambda t: _param("alpha = 0.5")(t) + "[grid]\nalpha = [0.5, 0.7]\n",
                                33, "grid.alpha", "allowed: alpha in [params] (one value) or in "
                                "[grid] (an axis), not both"),
    "grid unknown axis": (lambda t: t + "[grid]\nomega = [1.0]\n", 32, "grid.omega",
                          "allowed: an axis named by a [params] key"),
    "grid empty axis": (lambda t: t + "[grid]\nalpha = []\n", 32, "grid.alpha",
                        "allowed: a non-empty list of distinct values"),
    "grid axis not a list": (lambda t: t + "[grid]\nalpha = 0.5\n", 32, "grid.alpha",
                             "allowed: a non-empty list of distinct values"),
    "grid mixed types": (lambda t: t + '[grid]\nalpha = [0.5, "a"]\n', 32, "grid.alpha",
                         "allowed: a non-empty list of distinct values"),
    "grid duplicates": (lambda t: t + "[grid]\nalpha = [0.5, 0.5]\n", 32, "grid.alpha",
                        "allowed: a non-empty list of distinct values"),
    "grid invalid point": (lambda t: t + '[grid]\nR = [1.0]\ncontact = ["slide"]\n', 33,
                           "grid.contact", 'or invalid = "skip" in [grid]'),
    "grid point": (lambda t: t + "[grid]\nalpha = [0.5, 2.0]\n", 32, "grid.alpha",
                   "invalid parameters at the point f = 54 Hz, alpha = 2: Params.alpha = 2.0 is "
                   "out of range"),
}


@pytest.fixture(scope="module")
def existing(reference, tmp_path_factory) -> Path:
    """An existing, complete store (a copy of the reference) that no bad input may touch."""
    return Path(shutil.copytree(reference[0], tmp_path_factory.mktemp("existing") / "tiny.zarr"))


@pytest.fixture(scope="module")
def paths(existing, tiny_workflow, tmp_path_factory) -> dict[str, str]:
    """Placeholders of the command lines below: a good workflow, the existing store, a plain
    file, a plain directory, a Zarr group that is not a bbb store, a non-UTF-8 file."""
    d = tmp_path_factory.mktemp("inputs")
    (d / "file.txt").write_text("not a store")
    (d / "dir").mkdir()
    (d / "dir" / "notes.txt").write_text("not a store either")
    zarr.open_group(str(d / "other.zarr"), mode="w", attributes={"made_by": "someone else"})
    (d / "binary.toml").write_bytes(b"\xff\xfe\x00[study]\n")
    return {"GOOD": str(tiny_workflow), "STORE": str(existing), "FILE": str(d / "file.txt"),
            "DIR": str(d / "dir"), "ZARR": str(d / "other.zarr"), "BINARY": str(d / "binary.toml"),
            "MISSING": str(d / "missing" / "s.zarr")}


def snapshot(store: Path) -> dict[str, str]:
    """sha256 of every file under the store (and of its lock file, if any)."""
    out = {}
    for root, _, files in os.walk(store):
        for f in files:
            p = os.path.join(root, f)
            out[os.path.relpath(p, store)] = hashlib.sha256(Path(p).read_bytes()).hexdigest()
    lock = Path(f"{store}.lock")
    if lock.exists():
        out["../lock"] = lock.read_text()
    return out


@pytest.fixture(scope="module")
def pristine(existing) -> dict[str, str]:
    return snapshot(existing)


def run_main(argv: list[str], capsys) -> tuple[int, str, str]:
    rc = main(argv)
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def assert_one_line_usage_error(rc: int, out: str, err: str, *needles: str) -> None:
    assert rc == 2, err
    assert err.startswith("bbb: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and out == "", (out, err)
    for needle in needles:
        assert needle in err, (needle, err)


# -- malformed workflow files ---------------------------------------------------------------------
@pytest.mark.parametrize("case", list(WORKFLOWS))
def test_malformed_workflow_exits_2_naming_file_line_key_and_what_is_allowed(
        case, existing, pristine, tmp_path, capsys):
    """`bbb run BAD.toml --store EXISTING`: status 2, `bbb: error: BAD.toml:LINE: KEY: ...;
    allowed: ...`, and the existing store unchanged."""
    edit, line, key, allowed = WORKFLOWS[case]
    bad = tmp_path / "bad.toml"
    bad.write_text(edit(TINY))
    rc, out, err = run_main(["run", str(bad), "--store", str(existing)], capsys)
    where = f"bbb: error: {bad}:{line}: " if line else f"bbb: error: {bad}: "
    assert_one_line_usage_error(rc, out, err, where + (f"{key}: " if key else ""), allowed)
    assert snapshot(existing) == pristine


def test_a_store_of_another_workflow_exits_2_naming_the_difference(
        existing, pristine, tmp_path, capsys):
    """Different launch speeds: the store is refused naming the family setting that differs."""
    other = tmp_path / "other.toml"
    other.write_text(TINY.replace("[0.0, 150.0]", "[0.0, 100.0]"))
    rc, out, err = run_main(["run", str(other), "--store", str(existing)], capsys)
    assert_one_line_usage_error(rc, out, err, f"{existing}: made by a different workflow (families",
                                "allowed: the same workflow, or another --store")
    assert snapshot(existing) == pristine


# -- malformed command lines ----------------------------------------------------------------------
# id: (argv with placeholders from `paths`, needles with the same placeholders, environment)
COMMAND_LINES = {
    "--workers -1": (["run", "{GOOD}", "--store", "{STORE}", "--workers=-1"],
                     ["argument --workers: -1 is out of range; allowed: an integer >= 1"]),
    "--workers 1.5": (["run", "{GOOD}", "--store", "{STORE}", "--workers", "1.5"],
                      ["argument --workers: '1.5' is not an integer"]),
    "unknown flag": (["run", "{GOOD}", "--store", "{STORE}", "--frobnicate"],
                     ["unrecognized arguments: --frobnicate (see bbb --help)"]),
    "--store without its value": (["run", "{GOOD}", "--store"],
                                  ["argument --store: expected one argument"]),
    "verify without a store": (["verify"], ["the following arguments are required: STORE"]),
    "reduce without a store": (["reduce"], ["the following arguments are required: STORE"]),
    "verify with an unknown flag": (["verify", "{STORE}", "--repair"],
                                    ["unrecognized arguments: --repair"]),
    "workflow that is a directory": (["run", "{DIR}", "--store", "{STORE}"],
                                     ["{DIR}: cannot read", "Is a directory"]),
    "workflow that is not UTF-8": (["run", "{BINARY}", "--store", "{STORE}"],
                                   ["{BINARY}: cannot read", "utf-8"]),
    "store path that is a file": (["run", "{GOOD}", "--store", "{FILE}"],
                                  ["{FILE}: exists and is not a Zarr store; allowed: a new path"]),
    "store path under a file": (["run", "{GOOD}", "--store", "{FILE}/s.zarr"],
                                ["--store {FILE}/s.zarr: cannot create {FILE} (",
                                 "allowed: a path whose parent is or can be made a directory"]),
    "store path that is a plain directory": (["run", "{GOOD}", "--store", "{DIR}"],
                                             ["{DIR}: exists and is not a Zarr store"]),
    "store path that is another Zarr group": (["run", "{GOOD}", "--store", "{ZARR}"],
                                              ["{ZARR}: exists and is not a bbb study store"]),
    "scheduler port not a number": (["run", "{GOOD}", "--store", "{STORE}", "--scheduler",
                                     "tcp://127.0.0.1:notaport"],
                                    ["--scheduler tcp://127.0.0.1:notaport: cannot reach a Dask "
                                     "scheduler", "allowed: the address of a running scheduler"]),
    "scheduler without host and port": (["run", "{GOOD}", "--store", "{STORE}", "--scheduler",
                                         "tcp://"],
                                        ["--scheduler tcp://: cannot reach a Dask scheduler",
                                         "missing port number"]),
    "reduce of a plain directory": (["reduce", "{DIR}"], ["{DIR}: no such store"]),
    "reduce of another Zarr group": (["reduce", "{ZARR}"], ["{ZARR}: not a (complete) bbb study store"]),
    "reduce --out onto a file": (["reduce", "{STORE}", "--out", "{FILE}"],
                                 ["--out {FILE}: cannot create the directory",
                                  "allowed: a directory path"]),
    "status of a file": (["status", "{FILE}"], ["{FILE}: no such store"]),
    "status of a scene": (["status", "{GOOD}"], ["{GOOD}: a scene, not a store; allowed: a store "
                                                 "made by `bbb run` (`bbb run {GOOD}` writes runs/"]),
    "status of a shipped scene's name": (["status", "smoke"], [
        "smoke: a scene, not a store; allowed: a store made by `bbb run` (`bbb run smoke` writes "
        "runs/smoke.zarr)"]),
    "reduce of a scene": (["reduce", "{GOOD}"], ["{GOOD}: a scene, not a store"]),
    "plot of a scene": (["plot", "{GOOD}"], ["{GOOD}: a scene, not a store"]),
    "verify of a scene": (["verify", "{GOOD}"], ["{GOOD}: a scene, not a store"]),
    "scenes --show of an unknown scene": (["scenes", "--show", "smok"], [
        "smok: no such shipped scene (did you mean 'smoke'?); allowed: ", ", smoke, "]),
    "new from an unknown scene": (["new", "mine", "--from", "figure", "--out", "{DIR}/mine.toml"],
                                  ["figure: no such shipped scene (did you mean 'figure",
                                   "allowed: ", ", figure2, "]),
    "new onto an existing file": (["new", "mine", "--from", "smoke", "--out", "{GOOD}"],
                                  ["{GOOD}: exists; allowed: a new file"]),
    "new with a name that is no study name": (["new", "../mine", "--from", "smoke", "--out",
                                               "{DIR}/mine.toml"],
                                              ["'../mine': not a study name; allowed: letters"]),
    "new without --from": (["new", "mine"], ["the following arguments are required: --from"]),
    "verify of a missing path": (["verify", "{MISSING}"],
                                 ["{MISSING}: no such store; allowed: a store made by `bbb run`"]),
    "verify of a file": (["verify", "{FILE}"], ["{FILE}: no such store"]),
    "verify of another Zarr group": (["verify", "{ZARR}"],
                                     ["{ZARR}: not a (complete) bbb study store; allowed:"]),
    "--cluster of an unknown kind": (["run", "{GOOD}", "--store", "{STORE}", "--cluster", "pbs"],
                                     ["argument --cluster: invalid choice: 'pbs'"]),
    "--jobs without --cluster": (["run", "{GOOD}", "--store", "{STORE}", "--jobs", "4"],
                                 ["--jobs counts batch jobs of a --cluster (allowed: --cluster "
                                  "slurm --jobs N)"]),
    "--jobs 0": (["run", "{GOOD}", "--store", "{STORE}", "--cluster", "slurm", "--jobs", "0"],
                 ["argument --jobs: 0 is out of range; allowed: an integer >= 1"]),
    "--cluster with --scheduler": (["run", "{GOOD}", "--store", "{STORE}", "--cluster", "slurm",
                                    "--scheduler", "tcp://127.0.0.1:8786"],
                                   ["--cluster slurm starts its own scheduler and workers "
                                    "(allowed: one of --cluster, --scheduler, --workers)"]),
    "--cluster with --workers": (["run", "{GOOD}", "--store", "{STORE}", "--cluster", "slurm",
                                  "--workers", "2"],
                                 ["--cluster slurm starts its own scheduler and workers"]),
    "unknown scene name to run": (["run", "smok", "--store", "{STORE}"], [
        "smok: no such workflow file or shipped scene (did you mean 'smoke'?); allowed: a TOML "
        "file, or a scene name that `bbb scenes` lists"]),
    "unknown scene name to plan": (["plan", "figure"], ["figure: no such workflow file or "
                                                        "shipped scene (did you mean 'figure"]),
    "unknown scene name to accuracy": (["accuracy", "acuracy", "--out", "{DIR}"],
                                       ["(did you mean 'accuracy'?)", "`bbb scenes`"]),
    "unknown scene name to reduce --workflow": (["reduce", "{STORE}", "--workflow", "smok"],
                                                ["(did you mean 'smoke'?)"]),
    "malformed BBB_FAIL_CHUNKS": (["run", "{GOOD}", "--store", "{STORE}"],
                                  ["BBB_FAIL_CHUNKS: bad item '60-rest-1'; allowed: F:FAMILY:CHUNK"],
                                  {"BBB_FAIL_CHUNKS": "60-rest-1"}),
}


def _fill(items: list[str], paths: dict[str, str]) -> list[str]:
    return [item.format(**paths) for item in items]


@pytest.mark.parametrize("case", list(COMMAND_LINES))
def test_malformed_command_line_exits_2_naming_the_argument(
        case, paths, existing, pristine, capsys, monkeypatch):
    argv, needles, *env = COMMAND_LINES[case]
    for k, v in (env[0] if env else {}).items():
        monkeypatch.setenv(k, v)
    before = _listing(paths)
    rc, out, err = run_main(_fill(argv, paths), capsys)
    assert_one_line_usage_error(rc, out, err, *_fill(needles, paths))
    assert snapshot(existing) == pristine
    assert _listing(paths) == before  # nothing created beside them either (no store, no lock)


def _listing(paths: dict[str, str]) -> dict[str, list[str]]:
    dirs = {os.path.dirname(p) for p in paths.values()} | {paths["DIR"]}
    return {d: sorted(os.listdir(d)) if os.path.isdir(d) else [] for d in dirs}


# -- the same through real processes: no traceback reaches the terminal ---------------------------
@pytest.mark.parametrize("how, argv, needle", [
    pytest.param("script", ["run", "{BAD}", "--store", "{STORE}"], "{BAD}:3: TOML syntax error",
                 id="bbb run with a TOML syntax error"),
    pytest.param("module", ["run", "{GOOD}", "--store", "{STORE}", "--workers", "abc"],
                 "argument --workers: 'abc' is not an integer",
                 id="python -m pipeline run --workers abc"),
    pytest.param("script", ["verify", "{MISSING}"], "{MISSING}: no such store",
                 id="bbb verify of a missing path"),
])
def test_usage_errors_of_real_processes_are_one_line_without_traceback(
        how, argv, needle, paths, existing, pristine, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(TINY.replace("seed = 7", "seed = = 7"))
    places = dict(paths, BAD=str(bad))
    cmd = [str(BBB)] if how == "script" else [sys.executable, "-m", "pipeline"]
    res = subprocess.run(cmd + _fill(argv, places), capture_output=True, text=True, timeout=120)
    assert_one_line_usage_error(res.returncode, res.stdout, res.stderr, *_fill([needle], places))
    assert snapshot(existing) == pristine
