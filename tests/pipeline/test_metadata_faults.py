"""A store whose metadata files are damaged, on real stores: the root zarr.json truncated,
overwritten or deleted while the array folders remain, an array's own zarr.json damaged.
Every store command names the damaged file in one line and exits 2; `bbb run` rebuilds the
metadata from the workflow, computes no chunk that was done, and the store is then the
undamaged one bit for bit -- or it refuses, saying why, and changes nothing.
(pipeline/store/metadata.py, pipeline/execute/repair.py)"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import zarr

from pipeline.cli import main
from pipeline.execute.run import run_study
from pipeline.store.study_store import StoreError
from pipeline.workflow.load import load_workflow, parse_workflow

from .helpers import QUIET, TINY, assert_same_store

BBB = Path(sys.executable).with_name("bbb")


def _truncate(rel):
    def damage(store: Path):
        f = store / rel
        f.write_bytes(f.read_bytes()[:300])
    return damage


def _overwrite(rel, data: bytes):
    def damage(store: Path):
        (store / rel).write_bytes(data)
    return damage


def _delete(rel):
    def damage(store: Path):
        (store / rel).unlink()
    return damage


# how the metadata are damaged: (damage, the damaged file, the start of what is wrong)
DAMAGE = {
    "root truncated": (_truncate("zarr.json"), "zarr.json", "not JSON"),
    "root overwritten": (_overwrite("zarr.json", b'{"zarr_format": 3}'), "zarr.json",
                         "not the metadata of a Zarr v3 group"),
    "root deleted": (_delete("zarr.json"), "zarr.json", "missing"),
    "done's zarr.json truncated": (_truncate("done/zarr.json"), "done/zarr.json", "not JSON"),
    "positions' zarr.json deleted": (_delete("positions/zarr.json"), "positions/zarr.json",
                                     "missing"),
    "a coordinate's zarr.json emptied": (_overwrite("frequency/zarr.json", b""),
                                         "frequency/zarr.json", "empty"),
}
COMMANDS = {"status": [], "reduce": ["--out", "{tmp}/tables"], "plot": ["--out", "{tmp}/figs"],
            "verify": []}


def damaged_copy(reference, tmp_path, case: str) -> Path:
    store = Path(shutil.copytree(reference[0], tmp_path / "tiny.zarr"))
    DAMAGE[case][0](store)
    return store


def one_line_naming(err: str, store: Path, case: str) -> bool:
    _, file, what = DAMAGE[case]
    return (err.count("\n") == 1 and "Traceback" not in err
            and err.startswith(f"bbb: error: {store}/{file}: {what}")
            and f"bbb run WORKFLOW --store {store}" in err)


# -- every command names the damaged file ---------------------------------------------------
@pytest.mark.parametrize("command", list(COMMANDS))
@pytest.mark.parametrize("case", list(DAMAGE))
def test_a_store_command_names_the_damaged_metadata_file_in_one_line_and_exits_2(
        case, command, reference, tmp_path, capsys):
    store = damaged_copy(reference, tmp_path, case)
    extra = [a.format(tmp=tmp_path) for a in COMMANDS[command]]
    assert main([command, str(store), *extra]) == 2
    err = capsys.readouterr().err
    assert one_line_naming(err, store, case), err


def test_the_installed_bbb_status_names_a_truncated_root_in_one_line(reference, tmp_path):
    store = damaged_copy(reference, tmp_path, "root truncated")
    out = subprocess.run([str(BBB), "status", str(store)], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 2 and out.stdout == ""
    assert one_line_naming(out.stderr, store, "root truncated"), out.stderr


# -- bbb run rebuilds them ------------------------------------------------------------------
@pytest.mark.parametrize("case", ["root deleted", "done's zarr.json truncated",
                                  "a coordinate's zarr.json emptied"])
def test_run_rebuilds_damaged_metadata_computing_no_done_chunk(
        case, reference, tiny_workflow, tmp_path):
    """The rebuilt store equals the undamaged one bit for bit (arrays and fingerprint), and
    every root attribute but the creation time is the undamaged store's."""
    store = damaged_copy(reference, tmp_path, case)
    said = []
    report = run_study(load_workflow(tiny_workflow), store, workers=1,
                       **{**QUIET, "echo": said.append})
    assert report.computed == [] and report.skipped == 8
    assert said[0].startswith(f"tiny: rebuilt the damaged metadata of {store} "
                              f"({DAMAGE[case][1]})") and "8 done chunks kept" in said[0]
    assert_same_store(reference[0], store)
    want = dict(zarr.open_group(str(reference[0]), mode="r").attrs)
    got = dict(zarr.open_group(str(store), mode="r").attrs)
    rebuilt = {"created", "metadata_rebuilt"} if case == "root deleted" else set()
    assert sorted(set(got) ^ set(want)) == sorted(rebuilt - set(want))
    assert {k: v for k, v in got.items() if k not in rebuilt} == {
        k: v for k, v in want.items() if k not in rebuilt}
    assert main(["verify", str(store)]) == 0


def test_a_rebuilt_root_is_checked_on_a_done_chunk_recomputed_bit_for_bit(
        reference, tiny_workflow, tmp_path):
    store = damaged_copy(reference, tmp_path, "root truncated")
    said = []
    run_study(load_workflow(tiny_workflow), store, workers=1, **{**QUIET, "echo": said.append})
    assert ("chunk 0 of f = 54 Hz, family rest recomputed bit-identical to the stored one"
            in said[0])


# -- or says why it cannot ------------------------------------------------------------------
def test_run_refuses_to_rebuild_a_root_from_a_workflow_of_another_seed_and_changes_nothing(
        reference, tmp_path):
    """Same layout, same coordinates: only a recomputed chunk shows that the seed differs."""
    store = damaged_copy(reference, tmp_path, "root deleted")
    before = sorted(p.relative_to(store) for p in store.rglob("*"))
    other = parse_workflow(TINY.replace("seed = 7", "seed = 8"), source="other.toml")
    with pytest.raises(StoreError, match=r"of the done chunk 0 of f = 54 Hz, family rest is not "
                                         r"what the workflow computes .*another workflow"):
        run_study(other, store, workers=1, **QUIET)
    assert sorted(p.relative_to(store) for p in store.rglob("*")) == before
    assert not (store / "zarr.json").exists()


def test_run_refuses_to_rebuild_from_a_workflow_of_another_layout_naming_the_array(
        reference, tmp_path):
    store = damaged_copy(reference, tmp_path, "root truncated")
    root = (store / "zarr.json").read_bytes()
    other = parse_workflow(TINY.replace("t_max = 10.0", "t_max = 12.0"), source="other.toml")
    with pytest.raises(StoreError, match=rf"{store}/positions/zarr.json: shape \[2, 2, 8, 21\]; "
                                         r"the workflow's \[2, 2, 8, 25\]: not this workflow's"):
        run_study(other, store, workers=1, **QUIET)
    assert (store / "zarr.json").read_bytes() == root


def test_run_refuses_to_rebuild_from_a_workflow_of_other_frequencies_naming_the_array(
        reference, tmp_path):
    store = damaged_copy(reference, tmp_path, "root deleted")
    other = parse_workflow(TINY.replace("[54.0, 60.0]", "[54.0, 61.0]"), source="other.toml")
    with pytest.raises(StoreError, match=rf"{store}/frequency: values differ from the workflow's"):
        run_study(other, store, workers=1, **QUIET)


# -- slow: every damage, every command, as subprocesses; a partial store --------------------
@pytest.mark.slow
@pytest.mark.parametrize("case", list(DAMAGE))
def test_every_command_refuses_then_bbb_run_repairs_bit_identical(
        case, reference, tiny_workflow, tmp_path):
    """The installed `bbb`: status, reduce, plot, verify and run each either name the damaged
    file (exit 2) or, run, rebuild it computing nothing; after that every command succeeds."""
    store = damaged_copy(reference, tmp_path, case)
    for command, extra in COMMANDS.items():
        out = subprocess.run([str(BBB), command, str(store),
                              *(a.format(tmp=tmp_path) for a in extra)],
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 2, (command, out.stderr)
        assert one_line_naming(out.stderr, store, case), (command, out.stderr)
    run = subprocess.run([str(BBB), "run", str(tiny_workflow), "--store", str(store),
                          "--workers", "1", "--no-progress"], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    assert "8 done chunks kept" in run.stdout
    assert f"tiny: all 8 chunks already done in {store}" in run.stdout  # nothing computed
    assert_same_store(reference[0], store)
    for command, extra in COMMANDS.items():
        out = subprocess.run([str(BBB), command, str(store),
                              *(a.format(tmp=tmp_path) for a in extra)],
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, (command, out.stderr)


@pytest.mark.slow
def test_a_partial_store_with_a_deleted_root_computes_exactly_the_chunks_not_done(
        reference, tiny_workflow, tmp_path):
    store = Path(shutil.copytree(reference[0], tmp_path / "tiny.zarr"))
    g = zarr.open_group(str(store), mode="r+")
    g["done"][0, 1, 1] = False  # 54 Hz, launched, chunk 1
    g["done"][1, 0, 0] = False  # 60 Hz, rest, chunk 0
    (store / "positions/c/1/0/0/0").write_bytes(b"torn")  # a write cut short
    (store / "zarr.json").unlink()
    study = load_workflow(tiny_workflow)
    report = run_study(study, store, workers=1, **QUIET)
    assert sorted(report.computed) == [(54.0, "launched", 1), (60.0, "rest", 0)]
    assert report.skipped == 6
    assert_same_store(reference[0], store)


def test_the_rebuilt_done_markers_are_the_stored_ones(reference, tiny_workflow, tmp_path):
    """done's zarr.json deleted in a partial store: the rebuilt array shows the markers the
    chunk files hold (not the fill value, False, everywhere)."""
    store = Path(shutil.copytree(reference[0], tmp_path / "tiny.zarr"))
    zarr.open_group(str(store), mode="r+")["done"][1, 1, 0] = False
    (store / "done/zarr.json").unlink()
    with pytest.raises(StoreError, match=rf"{store}/done/zarr.json: missing"):
        main_like_status(store)
    from pipeline.execute.repair import repair_metadata

    said = []
    assert repair_metadata(load_workflow(tiny_workflow), str(store), said.append)
    done = np.asarray(zarr.open_group(str(store), mode="r")["done"][...])
    assert done.sum() == 7 and not done[1, 1, 0] and "7 done chunks kept" in said[0]
    assert json.loads((store / "done/zarr.json").read_text())["node_type"] == "array"


def main_like_status(store: Path) -> None:
    from pipeline.store.study_store import StudyStore

    StudyStore.open(store)
