"""`bbb status` of a map: one line a point, with its grid values, and its done chunks."""

from __future__ import annotations

from pipeline.execute.task import compute_chunk
from pipeline.store.status import status_text
from pipeline.store.study_store import StudyStore
from pipeline.workflow.load import parse_workflow

from ..helpers import TINY


def test_status_lists_every_point_of_a_map_with_its_values_and_done_chunks(tmp_path):
    study = parse_workflow(TINY + '[grid]\ncontact = ["stick", "slide"]\n', source="m.toml")
    store = StudyStore.create_or_open(tmp_path / "m.zarr", study)
    compute_chunk(store, 3, 0, 1)  # slide, 60 Hz, rest, chunk 1
    lines = status_text(store).splitlines()
    assert lines[0].startswith("tiny: 1/16 chunks done") and "4 points (contact x f)" in lines[0]
    assert lines[1].split() == ["f", "(Hz)", "contact", "rest", "launched"]
    assert [ln.split() for ln in lines[2:]] == [
        ["54", "stick", "0/2", "0/2"], ["60", "stick", "0/2", "0/2"],
        ["54", "slide", "0/2", "0/2"], ["60", "slide", "1/2", "0/2"]]


def test_status_lists_a_runs_batch_jobs_or_says_why_it_cannot(tmp_path, monkeypatch):
    """A record of a run's SLURM jobs beside the store (pipeline/store/jobs.py): status names
    the run and its job name; where squeue is not found it says so and what to run on the
    login node; a record whose run is gone from this host says how to cancel what is left;
    no record, no jobs section; the record is removed by clear_jobs."""
    import os
    import socket

    from pipeline.store.jobs import clear_jobs, jobs_path, read_jobs, record_jobs

    study = parse_workflow(TINY, source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "t.zarr", study)
    assert "jobs of the run" not in status_text(store)
    record = {"cluster": "slurm", "job_name": "bbb-0123abcd", "host": socket.gethostname(),
              "pid": os.getpid(), "jobs": 2, "started": "2026-11-25T12:00:00+00:00"}
    record_jobs(store.path, record)
    assert read_jobs(store.path) == record and jobs_path(store.path).endswith("t.zarr.jobs")
    monkeypatch.setenv("PATH", str(tmp_path))  # no squeue here
    lines = status_text(store).splitlines()
    jobs = lines[lines.index(next(ln for ln in lines if "jobs of the run" in ln)):]
    assert jobs[0].startswith(f"slurm jobs of the run on host {socket.gethostname()} "
                              f"(pid {os.getpid()}, since 2026-11-25T12:00:00+00:00): job name "
                              "bbb-0123abcd, 2 jobs requested")
    assert jobs[1] == ("squeue not found on this machine; on the login node: "
                       "squeue --name=bbb-0123abcd")
    record_jobs(store.path, {**record, "pid": 2**22 + 12345})  # no such process
    assert ("that run is gone (killed?): its jobs may remain; cancel them with "
            "scancel --name=bbb-0123abcd") in status_text(store)
    clear_jobs(store.path)
    assert read_jobs(store.path) is None and "jobs of the run" not in status_text(store)
