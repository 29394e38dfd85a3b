"""bbb.provenance: the kernel hash covers exactly the sources that determine a trajectory."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import bbb
from bbb.provenance import KERNEL_SOURCES, kernel_hash

BBB_DIR = Path(bbb.__file__).parent


def _python(code: str, path: Path | None = None) -> str:
    """Run ``code`` in a fresh interpreter (with ``path`` first on sys.path); its stdout."""
    env_path = [str(path)] if path else []
    out = subprocess.run([sys.executable, "-c", f"import sys; sys.path[:0] = {env_path!r}\n{code}"],
                         capture_output=True, text=True, check=True)
    return out.stdout.strip()


def _copy_of_bbb(tmp_path: Path) -> Path:
    shutil.copytree(BBB_DIR, tmp_path / "bbb", ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


def test_the_hashed_sources_are_exactly_the_modules_bbb_simulate_runs():
    # a new kernel module (a contact model, say) imported by simulate must join KERNEL_SOURCES;
    # a subpackage's modules by their paths (bbb.dynamics.evolve: dynamics/evolve.py)
    loaded = _python("import bbb.simulate\nprint(' '.join(sorted(m + ('/__init__' if hasattr("
                     "sys.modules[m], '__path__') else '') for m in sys.modules "
                     "if m.startswith('bbb.'))))").split()
    assert sorted(f"{m.removeprefix('bbb.').replace('.', '/')}.py" for m in loaded) \
        == sorted(KERNEL_SOURCES)


def test_the_hash_is_that_of_the_imported_package():
    assert _python("from bbb.provenance import kernel_hash; print(kernel_hash())") == kernel_hash()


def test_editing_a_kernel_source_changes_the_hash(tmp_path):
    root = _copy_of_bbb(tmp_path)
    code = "import bbb.provenance as p; print(p.__file__); print(p.kernel_hash())"
    where, same = _python(code, root).splitlines()
    assert where.startswith(str(root)) and same == kernel_hash()  # the copy is what ran
    for name in KERNEL_SOURCES:
        src = root / "bbb" / name
        text = src.read_text()
        src.write_text(text.replace("\n", "\n\n", 1))  # a blank line: the smallest edit
        assert _python(code, root).splitlines()[1] != kernel_hash(), name
        src.write_text(text)


def test_bumping_the_version_string_leaves_the_hash_alone(tmp_path):
    root = _copy_of_bbb(tmp_path)
    init = root / "bbb" / "__init__.py"
    # the version comes from the package metadata; a release that changes it changes only
    # __init__.py's view of it, which the kernel hash leaves out
    init.write_text(init.read_text() + '\n__version__ = "99.0"\n')
    out = _python("import bbb; from bbb.provenance import kernel_hash; "
                  "print(bbb.__version__); print(kernel_hash())", root).splitlines()
    assert out[0].startswith("99.") and out[1] == kernel_hash()
