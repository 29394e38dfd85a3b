"""The batch jobs of a run, beside its store: ``<store>.jobs`` while ``bbb run --cluster slurm``
runs (written when its jobs are submitted, removed when they are cancelled at its end), and
what ``bbb status`` shows of them.

The record names the run (host, pid, start) and the SLURM job name every job of the run
carries (``bbb-`` and 8 hex digits, unique per run: dask-jobqueue's ``job_name``), so that
``squeue --name`` lists the run's jobs, pending or running, however many were submitted,
replaced or cancelled by elastic scaling since.  A store at an fsspec URL keeps the record as
the object ``<url>.jobs``.
"""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess

from .lock import pid_alive
from .study_store import is_local, normalize_path

__all__ = ["jobs_path", "record_jobs", "read_jobs", "clear_jobs", "squeue", "jobs_dict", "jobs_text"]


def jobs_path(store: str) -> str:
    return normalize_path(store).rstrip("/") + ".jobs"


def _fs(path: str):
    import fsspec

    return fsspec.core.url_to_fs(path)


def record_jobs(store: str, record: dict) -> None:
    """Write the record of the run's jobs beside ``store`` (replacing an older one)."""
    path = jobs_path(store)
    text = json.dumps(record, sort_keys=True)
    if is_local(path):
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    else:
        fs, p = _fs(path)
        fs.pipe_file(p, text.encode())


def read_jobs(store: str) -> dict | None:
    """The record beside ``store``; None if there is none (or it cannot be read)."""
    path = jobs_path(store)
    try:
        if is_local(path):
            with open(path) as fh:
                return json.load(fh)
        fs, p = _fs(path)
        return json.loads(fs.cat_file(p))
    except (OSError, ValueError, ImportError):
        return None


def clear_jobs(store: str) -> None:
    path = jobs_path(store)
    try:
        if is_local(path):
            os.remove(path)
        else:
            fs, p = _fs(path)
            fs.rm_file(p)
    except (OSError, ImportError):
        pass


def squeue(job_name: str, timeout: float = 30.0) -> list[list[str]] | str:
    """[[job id, state, time used, nodes or reason], ...] of the jobs named ``job_name``, or
    why they cannot be listed here (one line)."""
    exe = shutil.which("squeue")
    if exe is None:
        return "squeue not found on this machine"
    try:
        res = subprocess.run([exe, "-h", f"--name={job_name}", "-o", "%i|%T|%M|%R"],
                             capture_output=True, text=True, timeout=timeout)
    except (OSError, subprocess.TimeoutExpired) as e:
        return f"squeue failed ({e})"
    if res.returncode != 0:
        said = (res.stderr.strip() or res.stdout.strip()).splitlines()
        return f"squeue failed ({said[0] if said else f'exit status {res.returncode}'})"
    return [line.split("|") for line in res.stdout.splitlines() if line.strip()]


def jobs_dict(store: str) -> dict | None:
    """The run's jobs as `bbb status --json` gives them; None if no run with jobs is recorded:
    {"record": the record (cluster, job_name, host, pid, jobs, started), "run_alive": whether
    the run's process is alive (true when it runs on another host: not checkable here),
    "queue": [{"job_id", "state", "time", "nodes_or_reason"}, ...] from squeue, or null with
    "queue_error": why squeue could not list them}."""
    rec = read_jobs(store)
    if rec is None:
        return None
    alive = rec.get("host") != socket.gethostname() or pid_alive(rec.get("pid"))
    listed = squeue(rec.get("job_name", "?"))
    if isinstance(listed, str):
        return {"record": rec, "run_alive": alive, "queue": None, "queue_error": listed}
    queue = [{"job_id": j[0], "state": j[1], "time": j[2],
              "nodes_or_reason": j[3] if len(j) > 3 else ""} for j in listed]
    return {"record": rec, "run_alive": alive, "queue": queue, "queue_error": None}


def jobs_text(store: str) -> str | None:
    """What ``bbb status`` prints of the run's jobs; None if no run with jobs is recorded."""
    d = jobs_dict(store)
    if d is None:
        return None
    rec = d["record"]
    name = rec.get("job_name", "?")
    lines = [f"{rec.get('cluster', 'batch')} jobs of the run on host {rec.get('host', '?')} "
             f"(pid {rec.get('pid', '?')}, since {rec.get('started', '?')}): job name {name}, "
             f"{rec.get('jobs', '?')} jobs requested"]
    if not d["run_alive"]:
        lines.append(f"that run is gone (killed?): its jobs may remain; cancel them with "
                     f"scancel --name={name}")
    if d["queue"] is None:
        lines.append(f"{d['queue_error']}; on the login node: squeue --name={name}")
        return "\n".join(lines)
    if not d["queue"]:
        lines.append("no job in the queue")
        return "\n".join(lines)
    lines.append(f"{'JOBID':>10} {'STATE':<11} {'TIME':>10}  NODELIST(REASON)")
    lines += [f"{j['job_id']:>10} {j['state']:<11} {j['time']:>10}  {j['nodes_or_reason']}"
              for j in d["queue"]]
    return "\n".join(lines)
