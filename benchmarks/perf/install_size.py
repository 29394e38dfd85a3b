"""What a default install of bbb weighs: a fresh venv, ``pip install`` of a revision's tree
(no extras unless asked), its install time, and the size of every installed distribution --
each attributed to the direct requirements of bbb that pull it in, so a line "bokeh" says what
dropping bokeh saves.

    python -m benchmarks.perf.install_size                      # the working tree
    python -m benchmarks.perf.install_size --ref 30adf75        # another revision (git archive)
    python -m benchmarks.perf.install_size --extras dashboard   # with an extra

The install time depends on pip's cache (warm here: the wheels were downloaded before) and
on the machine's load; the sizes do not.  Sizes are the files of each distribution's RECORD,
MB = 10^6 bytes; "venv" is every file below the venv (pip itself and the interpreter links
included).
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path

from ..common import ROOT, cpu_name

#: run inside the new venv: every distribution's size, and bbb's direct requirements' closures
PROBE = r"""
import json, os, sys
from importlib import metadata
from pip._vendor.packaging.requirements import Requirement
from pip._vendor.packaging.utils import canonicalize_name as canon

extras = set(sys.argv[1].split(",")) - {""}
dists = {canon(d.metadata["Name"]): d for d in metadata.distributions()}
size = {}
for name, d in dists.items():
    total = 0
    for f in d.files or ():
        p = d.locate_file(f)
        if os.path.isfile(p):
            total += os.path.getsize(p)
    size[name] = total

def requires(name, want):
    out = []
    for r in dists[name].requires or ():
        req = Requirement(r)
        env = [{"extra": e} for e in (want or {""})]
        if req.marker is None or any(req.marker.evaluate(e) for e in env):
            out.append((canon(req.name), set(req.extras)))
    return out

def closure(name, want):
    seen, todo = set(), [(name, want)]
    while todo:
        n, w = todo.pop()
        if n not in dists or (n, frozenset(w)) in seen:
            continue
        seen.add((n, frozenset(w)))
        todo += requires(n, w)
    return {n for n, _ in seen}

direct = {n: closure(n, w) for n, w in requires("bbb", extras)}
print(json.dumps({"size": size, "direct": {k: sorted(v) for k, v in direct.items()}}))
"""


def install(tree: Path, extras: str, venv: Path) -> float:
    """A new venv at ``venv`` with ``tree`` pip-installed (non-editable); the install's wall s."""
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = venv / "bin" / "python"
    subprocess.run([py, "-m", "pip", "install", "-q", "--upgrade", "pip"], check=True,
                   capture_output=True)
    spec = f"{tree}[{extras}]" if extras else str(tree)
    t0 = time.perf_counter()
    subprocess.run([py, "-m", "pip", "install", "-q", spec], check=True, capture_output=True)
    return time.perf_counter() - t0


def measure(venv: Path, extras: str) -> dict:
    out = subprocess.run([venv / "bin" / "python", "-c", PROBE, extras], check=True,
                         capture_output=True, text=True).stdout
    data = json.loads(out)
    data["venv"] = sum(p.stat().st_size for p in venv.rglob("*") if p.is_file() and not p.is_symlink())
    return data


def table(data: dict, wall: float, label: str) -> str:
    size, direct = data["size"], data["direct"]
    owners: dict[str, list[str]] = {}
    for top, deps in direct.items():
        for d in deps:
            owners.setdefault(d, []).append(top)
    lines = [f"# {label}: install {wall:.0f} s wall; venv {data['venv'] / 1e6:.0f} MB, "
             f"distributions {sum(size.values()) / 1e6:.0f} MB",
             f"{'requirement of bbb':<20} {'own MB':>8} {'only via it MB':>15}  (its closure)"]
    for top in sorted(direct, key=lambda t: -size.get(t, 0)):
        only = sum(size.get(d, 0) for d in direct[top] if owners[d] == [top])
        lines.append(f"{top:<20} {size.get(top, 0) / 1e6:>8.1f} {only / 1e6:>15.1f}  "
                     f"{', '.join(d for d in direct[top] if d != top)}")
    lines.append(f"{'distribution':<20} {'MB':>8}")
    for name, b in sorted(size.items(), key=lambda kv: -kv[1]):
        if b >= 1e6:
            lines.append(f"{name:<20} {b / 1e6:>8.1f}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ref", help="a git revision (default: the working tree)")
    ap.add_argument("--extras", default="", help="comma-separated extras, e.g. dashboard")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "tree"  # a copy: an in-place build would leave build/ behind
        tree.mkdir()
        label = "working tree"
        if args.ref:
            arch = subprocess.run(["git", "archive", args.ref], cwd=ROOT, check=True,
                                  capture_output=True).stdout
            subprocess.run(["tar", "-x", "-C", str(tree)], input=arch, check=True)
            rev = subprocess.run(["git", "rev-parse", "--short", args.ref], cwd=ROOT,
                                 check=True, capture_output=True, text=True).stdout.strip()
            label = f"{args.ref} ({rev})"
        else:
            files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT,
                                   check=True, capture_output=True, text=True).stdout.split("\0")
            for f in filter(None, files):
                if (ROOT / f).is_file():
                    (tree / f).parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(ROOT / f, tree / f)
        if args.extras:
            label += f" [{args.extras}]"
        venv = Path(tmp) / "venv"
        wall = install(tree, args.extras, venv)
        print(f"# {datetime.now(UTC):%Y-%m-%d %H:%M} UTC; CPU {cpu_name()}; Python "
              f"{sys.version.split()[0]}; pip cache warm")
        print(table(measure(venv, args.extras), wall, label))


if __name__ == "__main__":
    main()
