"""bbb.provenance: the kernel hash covers exactly the sources that determine a trajectory, and
of them only the code as it compiles: comments and docstrings change nothing, code does."""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import sys
from pathlib import Path

import bbb
from bbb.provenance import KERNEL_SOURCES, kernel_hash, normalised, python_minor

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


HASH_OF_COPY = "import bbb.provenance as p; print(p.__file__); print(p.kernel_hash())"


def _hash_of_copy(root: Path) -> str:
    """The kernel hash a fresh interpreter computes from the copy of bbb at ``root``."""
    where, value = _python(HASH_OF_COPY, root).splitlines()
    assert where.startswith(str(root))  # the copy is what ran
    return value


def test_the_copy_of_bbb_hashes_as_the_package(tmp_path):
    # what the tests below edit is a faithful copy: unedited, it gives this package's hash
    assert _hash_of_copy(_copy_of_bbb(tmp_path)) == kernel_hash()


def test_editing_code_in_any_kernel_source_changes_the_hash(tmp_path):
    # one statement more in each source in turn (the smallest code edit), hashed afresh from
    # the copy's files by one interpreter running the copy
    root = _copy_of_bbb(tmp_path)
    code = ("import bbb.provenance as p, pathlib\n"
            "for name in p.KERNEL_SOURCES:\n"
            "    src = pathlib.Path(p.__file__).parent / name\n"
            "    text = src.read_text()\n"
            "    src.write_text(text + '\\n_EDITED = 1\\n')\n"
            "    p.kernel_hash.cache_clear()\n"
            "    print(name, p.kernel_hash())\n"
            "    src.write_text(text)\n")
    hashes = dict(line.split() for line in _python(code, root).splitlines())
    assert sorted(hashes) == sorted(KERNEL_SOURCES)
    assert [n for n, h in hashes.items() if h == kernel_hash()] == []


def test_changing_a_default_tolerance_changes_the_hash(tmp_path):
    root = _copy_of_bbb(tmp_path)
    src = root / "bbb" / "numerics.py"
    text = src.read_text()
    assert text.count("tol_t: float = 1e-12") == 1  # the default in the dataclass
    src.write_text(text.replace("tol_t: float = 1e-12", "tol_t: float = 1e-13"))
    assert _hash_of_copy(root) != kernel_hash()


def test_editing_comments_and_blank_lines_in_every_kernel_source_keeps_the_hash(tmp_path):
    root = _copy_of_bbb(tmp_path)
    changed = 0
    for name in KERNEL_SOURCES:
        src = root / "bbb" / name
        lines = src.read_text().splitlines(keepends=True)
        edited = [line.replace("#", "# edited,", 1) if line.lstrip().startswith("#") else line
                  for line in lines]
        changed += sum(a != b for a, b in zip(lines, edited, strict=True))
        src.write_text("# a new first comment\n\n" + "".join(edited) + "\n\n# and a last one\n")
    assert changed > 100  # the kernel's own comments were edited, not only the added ones
    assert _hash_of_copy(root) == kernel_hash()


def test_editing_docstrings_in_every_kernel_source_keeps_the_hash(tmp_path):
    root = _copy_of_bbb(tmp_path)
    for name in KERNEL_SOURCES:
        src = root / "bbb" / name
        text = src.read_text()
        assert text.startswith('"""'), f"{name}: no module docstring"
        # the module docstring and the first function's (or class's) docstring, reworded
        text = '"""Edited. ' + text[3:]
        text = text.replace('    """', '    """Edited. ', 1)
        src.write_text(text)
    assert _hash_of_copy(root) == kernel_hash()


def test_a_docstring_is_dropped_but_an_equal_string_in_code_is_not():
    code = 'def f(x):\n    """Twice x."""\n    return 2 * x\n'
    assert normalised(code) == normalised(code.replace("Twice x.", "Double it, mm."))
    assert normalised(code) == normalised("def f(x):  # why\n\n    return (2 *\n            x)\n")
    assert normalised(code) != normalised(code.replace("2 * x", "3 * x"))
    assert normalised('x = "a"\n') != normalised('x = "b"\n')  # a string the code uses


def test_the_hash_names_the_python_minor_version_it_was_computed_under():
    # ast.dump's text may change between minor versions: the hash starts from the version
    root = Path(bbb.__file__).parent
    h = hashlib.sha256(f"python {python_minor()}\0".encode())
    for name in sorted(KERNEL_SOURCES):
        h.update(name.encode() + b"\0" + normalised((root / name).read_text()).encode() + b"\0")
    assert h.hexdigest() == kernel_hash()
    assert python_minor() == ".".join(map(str, sys.version_info[:2]))


def test_bumping_the_version_string_leaves_the_hash_alone(tmp_path):
    root = _copy_of_bbb(tmp_path)
    init = root / "bbb" / "__init__.py"
    # the version comes from the package metadata; a release that changes it changes only
    # __init__.py's view of it, which the kernel hash leaves out
    init.write_text(init.read_text() + '\n__version__ = "99.0"\n')
    out = _python("import bbb; from bbb.provenance import kernel_hash; "
                  "print(bbb.__version__); print(kernel_hash())", root).splitlines()
    assert out[0].startswith("99.") and out[1] == kernel_hash()
