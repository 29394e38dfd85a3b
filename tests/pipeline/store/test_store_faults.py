"""A store that knows its own bytes: each fault a user can inflict on a chunk, injected into a
copy of a real store (the tiny workflow run through a real LocalCluster), is named by
`bbb verify` (exit 1), refused by the readers in one line naming the chunk (exit 2), and
undone by `bbb run`, which recomputes exactly the damaged chunks: the store is then bit for
bit an undamaged run's (helpers.assert_same_store).

Tiny store: frequency 0 = 54 Hz, 1 = 60 Hz; family 0 = rest, 1 = launched; particles 0-3 are
chunk 0, 4-7 chunk 1.  Chunk files: ``ARRAY/c/<point>/<family>/<chunk>[/0...]``.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import zarr

from pipeline.cli import main
from pipeline.execute.run import run_study
from pipeline.store.study_store import StoreDamaged, StudyStore
from pipeline.tables.collisions import states
from pipeline.workflow.load import load_workflow

from ..helpers import QUIET, assert_same_store

POINT = {0: "f = 54 Hz", 1: "f = 60 Hz"}
FAMILY = {0: "rest", 1: "launched"}
CRC = "unreadable: its bytes fail their CRC-32C"
DIGEST = "values differ from those its task wrote"
MARKER = "done-marker unreadable: its bytes fail their CRC-32C"


def _delete(rel):
    def inject(store: Path):
        path = store / rel
        assert path.is_file()  # a chunk with values other than fill: its loss is a fault
        path.unlink()
    return inject


def _flip(rel, byte):
    def inject(store: Path):
        data = bytearray((store / rel).read_bytes())
        data[byte] ^= 0x10
        (store / rel).write_bytes(bytes(data))
    return inject


def _cut(rel):
    def inject(store: Path):
        data = (store / rel).read_bytes()
        (store / rel).write_bytes(data[: len(data) // 2])
    return inject


def _replace(rel, data: bytes):
    def inject(store: Path):
        assert (store / rel).is_file()
        (store / rel).write_bytes(data)
    return inject


def _through_zarr(name, index, value):
    """Values written through Zarr, as a user's script would: the chunk file carries a fresh,
    valid CRC-32C, so only the recorded digest can tell."""
    def inject(store: Path):
        zarr.open_group(str(store), mode="r+")[name][index] = value
    return inject


# name: (inject, (array, point, family, chunk), what verify says of it); together they damage
# 7 of the 8 chunks (60 Hz, launched, chunk 1 stays intact)
FAULTS = {
    "deleted counter chunk": (_delete("n_liftoffs/c/1/0/1"), ("n_liftoffs", 1, 0, 1), DIGEST),
    "flipped byte in a positions chunk": (
        _flip("positions/c/1/0/0/0", 40), ("positions", 1, 0, 0), CRC),
    "truncated collisions chunk": (
        _cut("collisions/c/0/1/0/0/0"), ("collisions", 0, 1, 0), CRC),
    "NaN-filled positions chunk": (
        _through_zarr("positions", (0, 0, slice(4, 8)), np.nan), ("positions", 0, 0, 1), DIGEST),
    "inf in a collisions chunk": (
        _through_zarr("collisions", (0, 0, 5, 0, 2), np.inf), ("collisions", 0, 0, 1), DIGEST),
    "empty done-marker": (_replace("done/c/0/0/0", b""), ("done", 0, 0, 0), MARKER),
    "corrupt done-marker": (
        _replace("done/c/0/1/1", b"\x28\xb5\x2f\xfd not a marker"), ("done", 0, 1, 1), MARKER),
    "truncated digest chunk": (_cut("digest/c/1/1/0/0"), ("digest", 1, 1, 0), CRC),
}


def _where(array, fi, mi, ci) -> str:
    return f"{array}[{POINT[fi]}, family {FAMILY[mi]}, chunk {ci}]"


def _damaged_copy(reference, tmp_path, *cases) -> Path:
    store = Path(shutil.copytree(reference[0], tmp_path / "damaged.zarr"))
    for case in cases:
        FAULTS[case][0](store)
    return store


# -- verify ------------------------------------------------------------------------------
@pytest.mark.parametrize("case", list(FAULTS))
def test_verify_names_each_fault_in_one_line_and_exits_1(case, reference, tmp_path, capsys):
    _, (array, fi, mi, ci), what = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    assert main(["verify", str(store)]) == 1
    out = capsys.readouterr().out.strip().splitlines()
    assert len(out) == 2, out  # the fault's line, the summary
    assert out[0].startswith(f"{_where(array, fi, mi, ci)}: {what}"), out[0]
    assert "1 damaged chunks: `bbb run` with the store's workflow recomputes them" in out[1]


def test_verify_names_every_fault_of_a_store_damaged_in_many_places(reference, tmp_path, capsys):
    store = _damaged_copy(reference, tmp_path, *FAULTS)
    assert main(["verify", str(store)]) == 1
    lines = capsys.readouterr().out.strip().splitlines()[:-1]
    want = sorted(f"{_where(*where)}: {what}" for _, where, what in FAULTS.values())
    assert len(lines) == len(want)
    assert all(line.startswith(w) for line, w in zip(sorted(lines), want, strict=True)), lines


# -- the readers -------------------------------------------------------------------------
READ_BY_REDUCE = [c for c, (_, where, _) in FAULTS.items() if where[0] != "collisions"]


@pytest.mark.parametrize("case", READ_BY_REDUCE)
def test_reduce_of_a_damaged_store_exits_2_in_one_line_naming_the_chunk(
        case, reference, tmp_path, capsys):
    _, where, _ = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    assert main(["reduce", str(store), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith(f"bbb: error: {store}: {_where(*where)} is damaged: "), err
    assert "run `bbb run` with its workflow on this store" in err


@pytest.mark.parametrize("case", [c for c in FAULTS if "collisions" in c])
def test_reading_a_damaged_collisions_chunk_raises_store_damaged_naming_it(case, reference,
                                                                          tmp_path):
    # the tiny store's tables do not read collisions: its post-collision states do
    _, (array, fi, mi, ci), _ = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    with pytest.raises(StoreDamaged, match=re.escape(f"{_where(array, fi, mi, ci)} is damaged")):
        states(store, [54.0, 60.0][fi], FAMILY[mi])


@pytest.mark.parametrize("case", ["empty done-marker", "corrupt done-marker"])
def test_status_of_a_store_with_a_damaged_marker_exits_2_naming_it(case, reference, tmp_path,
                                                                   capsys):
    # status reads the done-markers only; the data's damage is verify's and reduce's to find
    _, where, _ = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    assert main(["status", str(store)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"bbb: error: {store}: {_where(*where)} is "
                                                   "damaged: "), err


def test_a_damaged_read_raises_store_damaged_carrying_array_point_family_and_chunk(
        reference, tmp_path):
    store = _damaged_copy(reference, tmp_path, "deleted counter chunk")
    with pytest.raises(StoreDamaged) as e:
        StudyStore.open(store).read_done("n_liftoffs", 1, 0)
    d = e.value
    assert (d.array, d.point, d.family, d.chunk, d.more) == ("n_liftoffs", "f = 60 Hz", "rest", 1, 0)


def test_a_chunk_marked_done_without_its_digest_is_damaged(reference, tmp_path):
    """A done-marker set by hand (or a digest lost) on a chunk: it is not known to hold what
    a task wrote."""
    store = _damaged_copy(reference, tmp_path)
    zarr.open_group(str(store), mode="r+")["digest"][1, 1, 1, :] = -1
    with pytest.raises(StoreDamaged, match=r"positions\[f = 60 Hz, family launched, chunk 1\] is "
                                           r"damaged: marked done but no digest was recorded"):
        StudyStore.open(store).read_done("positions", 1, 1)


# -- repair --------------------------------------------------------------------------------
def test_run_repairs_every_damaged_chunk_in_one_line_bit_identical_to_an_undamaged_run(
        reference, tiny_workflow, tmp_path, capsys):
    store = _damaged_copy(reference, tmp_path, *FAULTS)
    chunks = sorted({where[1:] for _, where, _ in FAULTS.values()})
    assert main(["run", str(tiny_workflow), "--store", str(store), "--workers", "1",
                 "--no-progress"]) == 0
    out = capsys.readouterr().out
    repaired = [line for line in out.splitlines() if line.startswith("tiny: repaired")]
    assert len(repaired) == 1 and repaired[0].startswith(
        f"tiny: repaired {len(chunks)} damaged chunks: "), out
    assert f"({len(chunks)} computed, {len(chunks)} of them repaired, {8 - len(chunks)} already " \
           "done)" in out
    assert_same_store(reference[0], store)
    assert main(["verify", str(store)]) == 0


def test_run_on_an_intact_store_computes_nothing(reference, tiny_workflow, tmp_path):
    store = _damaged_copy(reference, tmp_path)
    report = run_study(load_workflow(tiny_workflow), store, workers=1, **QUIET)
    assert report.computed == [] and report.repaired == [] and report.skipped == 8


@pytest.mark.slow
@pytest.mark.parametrize("case", list(FAULTS))
def test_run_recomputes_exactly_the_damaged_chunk(case, reference, tiny_workflow, tmp_path):
    _, (_, fi, mi, ci), _ = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    report = run_study(load_workflow(tiny_workflow), store, workers=1, **QUIET)
    key = ([54.0, 60.0][fi], FAMILY[mi], ci)
    assert report.repaired == [key] and report.computed == [key] and report.skipped == 7
    assert_same_store(reference[0], store)


@pytest.mark.slow
@pytest.mark.parametrize("case", ["deleted counter chunk", "NaN-filled positions chunk"])
def test_plot_of_a_damaged_store_exits_2_in_one_line_naming_the_chunk(
        case, reference, tmp_path, capsys):
    _, where, _ = FAULTS[case]
    store = _damaged_copy(reference, tmp_path, case)
    assert main(["plot", str(store), "--out", str(tmp_path / "fig"), "--format", "png"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"bbb: error: {store}: {_where(*where)} is "
                                                   "damaged: "), err
