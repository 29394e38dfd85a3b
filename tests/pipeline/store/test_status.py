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


def test_status_json_gives_done_and_total_chunks_per_point_and_family_and_the_jobs(
        tmp_path, monkeypatch, capsys):
    """`bbb status STORE --json`: one JSON object with the documented keys (STATUS_KEYS,
    docs/cli.md); the jobs section is null without a run's record, else the record."""
    import json
    import socket

    from pipeline.cli import main
    from pipeline.store.jobs import record_jobs
    from pipeline.store.status import STATUS_KEYS

    study = parse_workflow(TINY, source="t.toml")
    store = StudyStore.create_or_open(tmp_path / "t.zarr", study)
    compute_chunk(store, 1, 0, 1)  # 60 Hz, rest, chunk 1
    assert main(["status", str(store.path), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert set(got) == set(STATUS_KEYS)
    assert (got["name"], got["chunks_done"], got["chunks_total"]) == ("tiny", 1, 8)
    assert got["axes"] == ["f"] and got["families"] == ["rest", "launched"]
    assert [(p["f"], p["grid"], p["families"]["rest"]["done"], p["families"]["launched"]["done"])
            for p in got["points"]] == [(54.0, {}, 0, 0), (60.0, {}, 1, 0)]
    assert got["points"][0]["families"]["rest"] == {"done": 0, "total": 2, "stop": None}
    assert got["jobs"] is None
    record = {"cluster": "slurm", "job_name": "bbb-0123abcd", "host": socket.gethostname(),
              "pid": 2**22 + 12345, "jobs": 2, "started": "2026-11-25T12:00:00+00:00"}
    record_jobs(store.path, record)
    monkeypatch.setenv("PATH", str(tmp_path))  # no squeue here
    assert main(["status", str(store.path), "--json"]) == 0
    jobs = json.loads(capsys.readouterr().out)["jobs"]
    assert jobs == {"record": record, "run_alive": False, "queue": None,
                    "queue_error": "squeue not found on this machine"}


def test_status_json_of_a_map_gives_each_points_grid_values(tmp_path, capsys):
    import json

    from pipeline.cli import main

    study = parse_workflow(TINY + '[grid]\ncontact = ["stick", "slide"]\n', source="m.toml")
    store = StudyStore.create_or_open(tmp_path / "m.zarr", study)
    compute_chunk(store, 3, 0, 1)  # slide, 60 Hz, rest, chunk 1
    assert main(["status", str(store.path), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["axes"] == ["contact", "f"]
    assert [(p["grid"]["contact"], p["f"], p["families"]["rest"]["done"]) for p in got["points"]] == [
        ("stick", 54.0, 0), ("stick", 60.0, 0), ("slide", 54.0, 0), ("slide", 60.0, 1)]


def test_every_status_json_key_is_documented_in_the_pipeline_readme():
    from pathlib import Path

    from pipeline.store.status import STATUS_KEYS

    readme = (Path(__file__).resolve().parents[3] / "pipeline" / "README.md").read_text()
    table = readme[readme.index("`bbb status STORE --json` prints"):].split("\n\n")[1]
    rows = [ln for ln in table.splitlines() if ln.startswith("| `")]
    documented = {k.strip("` ") for ln in rows for k in ln.split("|")[1].split(",")}
    assert set(STATUS_KEYS) <= documented
