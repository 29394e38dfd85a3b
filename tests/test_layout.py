"""The house rules of the layout (docs/design.md, issues 11 and 24), read off the source files: modules
stay under 400 lines unless they say why, ``bbb/`` never imports ``pipeline/``, the kernel (the
modules ``bbb.provenance`` hashes) never imports the analyses (``bbb/analysis/``), the engine
(``pipeline/`` outside ``studies/``) never imports a study, no study imports another (each
study folder is listed in the registry), the engine's layers import one way
(workflow <- store <- execute <- tables <- plot <- claims <- the entry points and studies: a layer
imports only layers below it), no re-export module ("shim") and none of the old paths that shims
once kept, module names unique, no import cycle of any length among the modules of ``bbb/`` and
``pipeline/`` (lazy imports count), no ``_private`` name imported from another module,
``pipeline.api`` never imports ``pipeline.cli`` or ``pipeline.commands``, and every package folder
is in the wheel. Each rule's checker is also run on a synthetic tree that breaks it (the
``*_is_caught`` tests)."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MAX_LINES = 400
#: folders of plug-ins, each module named for the study or observable it is (not held to
#: unique module names)
PLUG_IN_FOLDERS = ("pipeline/studies/", "pipeline/workflow/observables/")
#: the engine's layers, bottom first (docs/design.md): pipeline/<layer>/ may import only
#: pipeline/<a layer at or below it>/; every other pipeline module (api, cli, make_figures,
#: studies/) is above them all
LAYERS = ("workflow", "store", "execute", "tables", "plot", "claims")
#: the old paths that re-export modules ("shims") kept after their moves, all removed (no
#: release ever carried them): old module -> where its code lives.  None imports any more
#: (test_no_old_module_path_imports_any_more); a new shim is caught by test_no_module_is_a_shim
MOVED = {
    **{f"bbb.{m}": f"bbb.analysis.{m}" for m in (
        "approx", "extrema", "gk_contrast", "greenkubo", "locking", "lyapunov", "stationarity",
        "transport", "stats", "stats.bootstrap", "stats.ergodicity", "stats.interval")},
    "bbb.liftoff": "bbb.analysis.liftoff_onset",
    "bbb.kernel": "bbb.dynamics.evolve", "bbb.conveyor": "bbb.dynamics.evolve",
    "bbb.search": "bbb.dynamics.search", "bbb.conveyor_search": "bbb.dynamics.search",
    "bbb.contact": "bbb.dynamics.slide", "bbb.conveyor_contact": "bbb.dynamics.contact_step",
    "bbb.dynamics.contact_level": "bbb.dynamics.contact_step",
    "bbb.dynamics.contact_conveyor": "bbb.dynamics.contact_step",
    "bbb.dynamics.bounds_level": "bbb.dynamics.bounds", "bbb.dynamics.bounds_conveyor": "bbb.dynamics.bounds",
    "pipeline.studies.transport.signs": "pipeline.claims.signs",
    "pipeline.cluster": "pipeline.execute.cluster", "pipeline.reduce": "pipeline.tables.reduce",
    "pipeline.run": "pipeline.execute.run", "pipeline.identity": "pipeline.workflow.identity",
    "pipeline.studies.figure_style": "pipeline.plot.style",
    "pipeline.claims.record": "pipeline.claims.claim",  # renamed: bbb.record is what a run records
}
#: moved modules whose old path is now a package: its __init__ re-exported the module's
#: names, and now imports nothing
MOVED_TO_PACKAGE = {"pipeline.workflow": "pipeline.workflow.load",
                    "pipeline.store": "pipeline.store.study_store",
                    "pipeline.claims": "pipeline.claims.claim"}
#: engine modules allowed to import pipeline.studies: the entry points over engine and
#: studies (docs/design.md), each with why
ENTRY_POINTS = {
    "pipeline/make_figures.py": "`python -m pipeline.make_figures` runs every study the "
                                "registry (pipeline.studies.registry) lists",
    "pipeline/commands/run_accuracy.py": "`bbb accuracy` runs the accuracy study (a lazy import in "
                                         "its command)",
}
#: over 400 lines without a 'Size:' line yet, being changed on other branches (the lead splits
#: them or states their reason when merging, then removes them here:
#: test_the_pending_list_names_only_files_still_pending fails until then)
PENDING: set[str] = set()


def modules(*packages: str, root: Path = ROOT) -> list[Path]:
    return sorted(p for pkg in packages for p in (root / pkg).rglob("*.py"))


def rel(path: Path, root: Path = ROOT) -> str:
    return path.relative_to(root).as_posix()


def module_name(path: Path, root: Path = ROOT) -> str:
    """pkg/mod.py -> "pkg.mod"; pkg/__init__.py -> "pkg"."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def too_long_without_reason(path: Path) -> bool:
    """More than MAX_LINES lines and no docstring line starting 'Size:' with a reason after it."""
    text = path.read_text(encoding="utf-8")
    if len(text.splitlines()) <= MAX_LINES:
        return False
    doc = ast.get_docstring(ast.parse(text)) or ""
    return not any(line.strip().startswith("Size:") and len(line.strip()) > len("Size:") + 10
                   for line in doc.splitlines())


def from_module(node: ast.ImportFrom, package: list[str]) -> str:
    """The dotted module of ``from <module> import ...`` written in ``package``, relative
    imports resolved."""
    if not node.level:
        return node.module or ""
    base = package[: len(package) - node.level + 1]
    return ".".join(base + ([node.module] if node.module else []))


def imported_modules(path: Path, root: Path = ROOT) -> set[str]:
    """Absolute names of every module ``path`` imports, at any depth (relative imports
    resolved against its package; ``from X import y`` also counts as importing ``X.y``)."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    package = parts[:-1]  # of pkg/mod.py: pkg; of pkg/__init__.py: pkg too
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            mod = from_module(node, package)
            out.add(mod)
            out.update(f"{mod}.{a.name}" for a in node.names)
    return out


def test_no_module_is_over_400_lines_without_its_reason_in_the_docstring():
    long = [rel(p) for p in modules("bbb", "pipeline")
            if rel(p) not in PENDING and too_long_without_reason(p)]
    assert long == [], f"over {MAX_LINES} lines with no 'Size:' line in the docstring: {long}"


def test_the_pending_list_names_only_files_still_pending():
    done = sorted(f for f in PENDING if not too_long_without_reason(ROOT / f))
    assert done == [], f"no longer pending, remove from PENDING: {done}"


def test_bbb_imports_nothing_from_pipeline():
    bad = {rel(p): sorted(m for m in imported_modules(p) if m.split(".")[0] == "pipeline")
           for p in modules("bbb")}
    assert {k: v for k, v in bad.items() if v} == {}


def analysis_imports_of(sources: tuple[str, ...], root: Path = ROOT) -> dict[str, list[str]]:
    """{bbb/<source>: the bbb.analysis modules it imports} for each of ``sources`` (file names
    under bbb/, as :data:`bbb.provenance.KERNEL_SOURCES`), those importing none left out."""
    found = {f"bbb/{s}": sorted(m for m in imported_modules(root / "bbb" / s, root)
                                if m == "bbb.analysis" or m.startswith("bbb.analysis."))
             for s in sources}
    return {k: v for k, v in found.items() if v}


def test_the_kernel_never_imports_the_analyses():
    from bbb.provenance import KERNEL_SOURCES

    assert analysis_imports_of(KERNEL_SOURCES) == {}


def test_no_engine_module_imports_a_study_except_the_entry_points():
    engine = [p for p in modules("pipeline") if not rel(p).startswith("pipeline/studies/")]
    bad = {rel(p): sorted(m for m in imported_modules(p) if m.startswith("pipeline.studies"))
           for p in engine if rel(p) not in ENTRY_POINTS}
    assert {k: v for k, v in bad.items() if v} == {}
    # the entry points do import a study (else they need no exception)
    assert all(any(m.startswith("pipeline.studies") for m in imported_modules(ROOT / f))
               for f in ENTRY_POINTS)


def study_folders(root: Path = ROOT) -> list[str]:
    """The study folders: packages directly under pipeline/studies/."""
    return sorted(p.parent.name for p in (root / "pipeline" / "studies").glob("*/__init__.py"))


def cross_study_imports(root: Path = ROOT) -> list[tuple[str, str]]:
    """(module, imported module) of every import by a module of one study folder of a module of
    another, or by a shared module of pipeline/studies/ (interface, report, ...) of any study's
    (lazy imports count): a study is reached only through the registry, which imports none."""
    folders = set(study_folders(root))
    out = []
    for p in modules("pipeline/studies", root=root):
        parts = p.relative_to(root / "pipeline" / "studies").parts
        own = parts[0] if len(parts) > 1 else None  # None: a shared module
        out += [(module_name(p, root), m) for m in sorted(imported_modules(p, root))
                if m.split(".")[:2] == ["pipeline", "studies"] and len(m.split(".")) > 2
                and m.split(".")[2] in folders and m.split(".")[2] != own]
    return out


def test_no_study_imports_another_study():
    assert cross_study_imports() == []


def test_every_study_folder_is_registered():
    from pipeline.studies.registry import STUDIES, TOOLS

    assert sorted(STUDIES + TOOLS) == study_folders()


def import_graph(*packages: str, root: Path = ROOT) -> dict[str, set[str]]:
    """{module: the modules of ``packages`` it imports}, every import at any depth (a lazy
    import inside a function closes a cycle as surely as one at the top)."""
    paths = {module_name(p, root): p for p in modules(*packages, root=root)}
    return {m: {x for x in imported_modules(p, root) if x in paths and x != m}
            for m, p in paths.items()}


def import_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles of ``graph``: each strongly connected component of more than one
    module (Tarjan's algorithm, iterative), as a sorted list of names."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return sorted(out)


def private_imports(*packages: str, root: Path = ROOT) -> set[tuple[str, str]]:
    """(importing module, name) of every ``_private`` name (one leading underscore, not a
    dunder) imported from another module: ``from m import _x``, ``import m._x``."""
    out = set()
    for p in modules(*packages, root=root):
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                names = [a.name for a in node.names] + (node.module or "").split(".")
            elif isinstance(node, ast.Import):
                names = [part for a in node.names for part in a.name.split(".")]
            else:
                continue
            out.update((module_name(p, root), n) for n in names
                       if n.startswith("_") and not n.startswith("__"))
    return out


def imports_cli(api: Path, root: Path = ROOT) -> list[str]:
    """The ``pipeline.cli`` and ``pipeline.commands`` modules ``api`` imports, at any depth."""
    return sorted(m for m in imported_modules(api, root)
                  if m.split(".")[:2] in (["pipeline", "cli"], ["pipeline", "commands"]))


def layer_of(module: str) -> int:
    """Index of ``module``'s layer in LAYERS; len(LAYERS) for a pipeline module above them."""
    parts = module.split(".")
    if len(parts) > 1 and parts[1] in LAYERS:
        return LAYERS.index(parts[1])
    return len(LAYERS)


def upward_imports(root: Path = ROOT) -> list[tuple[str, str]]:
    """(module, imported module) of every import of a pipeline module from a higher layer
    (lazy imports count)."""
    graph = import_graph("pipeline", root=root)
    return sorted((m, x) for m, targets in graph.items() for x in targets
                  if layer_of(x) > layer_of(m))


def package_folders(*packages: str, root: Path = ROOT) -> set[str]:
    """Dotted names of every folder of ``packages`` holding an ``__init__.py``."""
    return {module_name(p, root) for p in modules(*packages, root=root) if p.name == "__init__.py"}


def test_the_engine_layers_import_only_layers_below_them():
    assert upward_imports() == []


def test_every_layer_folder_exists_and_nothing_of_the_engine_is_left_flat():
    """The layers are folders; only the entry points and the package files stay at the top of
    pipeline/."""
    assert all((ROOT / "pipeline" / layer / "__init__.py").is_file() for layer in LAYERS)
    top = {p.name for p in (ROOT / "pipeline").glob("*.py")}
    allowed = {"__init__.py", "__main__.py", "api.py", "cli.py", "make_figures.py", "gallery.py"}
    assert top <= allowed, f"flat engine modules, put them in a layer: {sorted(top - allowed)}"


def is_shim(path: Path) -> bool:
    """A module that only re-exports: besides its docstring, ``__all__``, ``from __future__``
    and an ``if __name__ == "__main__":`` block, it holds nothing but imports (at least one),
    or it star-imports (``from m import *``) anything.  Package files (``__init__.py``) may
    gather their package's names, so only their star imports count."""
    body = ast.parse(path.read_text(encoding="utf-8")).body
    if any(isinstance(n, ast.ImportFrom) and any(a.name == "*" for a in n.names) for n in body):
        return True
    if path.name == "__init__.py":
        return False
    rest = [n for n in body
            if not (isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant))  # docstring
            and not (isinstance(n, ast.ImportFrom) and n.module == "__future__")
            and not (isinstance(n, ast.Assign | ast.AnnAssign)
                     and [getattr(x, "id", None) for x in getattr(n, "targets", [getattr(n, "target", None)])]
                     == ["__all__"])
            and not (isinstance(n, ast.If) and "__name__" in ast.dump(n.test))]
    return bool(rest) and all(isinstance(n, ast.Import | ast.ImportFrom) for n in rest)


def duplicate_basenames(*packages: str, root: Path = ROOT) -> dict[str, list[str]]:
    """{file name: its paths} for every module file name (package files and ``__main__.py``
    aside) that occurs more than once under ``packages``."""
    seen: dict[str, list[str]] = {}
    for p in modules(*packages, root=root):
        if p.name not in ("__init__.py", "__main__.py"):
            seen.setdefault(p.name, []).append(rel(p, root))
    return {k: v for k, v in seen.items() if len(v) > 1}


def engine_duplicates(root: Path = ROOT) -> dict[str, list[str]]:
    """:func:`duplicate_basenames` of bbb/ and pipeline/ with the plug-in folders left out."""
    found = {k: [f for f in v if not f.startswith(PLUG_IN_FOLDERS)]
             for k, v in duplicate_basenames("bbb", "pipeline", root=root).items()}
    return {k: v for k, v in found.items() if len(v) > 1}


def test_no_module_is_a_shim():
    shims = [rel(p) for p in modules("bbb", "pipeline") if is_shim(p)]
    assert shims == [], f"re-export modules: import from the real module instead: {shims}"


@pytest.mark.parametrize("old", sorted(MOVED))
def test_no_old_module_path_imports_any_more(old):
    assert importlib.util.find_spec(MOVED[old]) is not None, f"{MOVED[old]} is missing"
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(old)


@pytest.mark.parametrize("old", sorted(MOVED_TO_PACKAGE))
def test_an_old_module_path_now_a_package_re_exports_nothing(old):
    init = ROOT.joinpath(*old.split(".")) / "__init__.py"
    imports = [n for n in ast.parse(init.read_text(encoding="utf-8")).body
               if isinstance(n, ast.Import | ast.ImportFrom)]
    assert imports == [], f"{rel(init)} imports: import {MOVED_TO_PACKAGE[old]} instead"
    assert not hasattr(importlib.import_module(old), "__all__")


def test_module_file_names_are_unique_in_bbb_and_the_engine():
    """The library and the engine name each module once; the plug-in folders are left out: the
    studies (pipeline/studies/) share one template (claims.py, figures.py, cases.py, report.py
    in each study's folder) and each observable plug-in (pipeline/workflow/observables/) is
    named for what it records, as the table that reduces it is (tables/collisions.py)."""
    assert engine_duplicates() == {}


def test_every_package_folder_ships_in_the_wheel():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    listed = set(config["tool"]["setuptools"]["packages"])
    missing = package_folders("bbb", "pipeline") - listed
    assert missing == set(), f"add to [tool.setuptools] packages in pyproject.toml: {sorted(missing)}"
    where = config["tool"]["setuptools"].get("package-dir", {})
    gone = sorted(m for m in listed if not ROOT.joinpath(*where.get(m, m).split(".")).is_dir())
    assert gone == [], f"listed in pyproject.toml's packages, but no such folder: {gone}"


def data_folders_not_listed(config: dict, root: Path = ROOT) -> list[str]:
    """Folders below a listed package that hold data files (.toml, .json) without being a listed
    package themselves, and package-data patterns reaching into a subfolder: setuptools warns
    about each at every build ("Package would be ignored")."""
    st = config["tool"]["setuptools"]
    listed, where = set(st["packages"]), st.get("package-dir", {})
    out = [f"{pkg}: {pat}" for pkg, pats in st.get("package-data", {}).items()
           for pat in pats if "/" in pat]
    for pkg in sorted(listed):
        folder = root.joinpath(*where.get(pkg, pkg).split("."))
        for sub in sorted(p for p in folder.iterdir() if p.is_dir() and not p.name.startswith(
                ("_", "."))):
            name = f"{pkg}.{sub.name}"
            if name not in listed and (any(sub.glob("*.toml")) or any(sub.glob("*.json"))):
                out.append(name)
    return out


def test_every_folder_of_package_data_is_a_listed_package():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert data_folders_not_listed(config) == []


def test_no_import_cycle_of_any_length_among_bbb_and_pipeline_modules():
    assert import_cycles(import_graph("bbb", "pipeline")) == []


def test_no_private_name_is_imported_from_another_module():
    found = private_imports("bbb", "pipeline")
    assert found == set(), f"_private names imported across modules: {sorted(found)}"


def test_the_api_never_imports_the_cli():
    assert imports_cli(ROOT / "pipeline" / "api.py") == []


# -- each rule's checker on a tree that breaks it -----------------------------------------------
def _tree(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root


def test_a_study_importing_another_study_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "pipeline/__init__.py": "", "pipeline/studies/__init__.py": "",
        "pipeline/studies/registry.py": "import importlib\n",
        "pipeline/studies/a/__init__.py": "", "pipeline/studies/b/__init__.py": "",
        "pipeline/studies/a/claims.py": "from . import figures\nfrom ..registry import study\n",
        "pipeline/studies/a/figures.py": "",
        "pipeline/studies/b/claims.py": "def f():\n    from ..a.claims import study\n",
        "pipeline/studies/report.py": "from .a import figures\n",
    })
    assert cross_study_imports(root) == [("pipeline.studies.b.claims", "pipeline.studies.a.claims"),
                                         ("pipeline.studies.b.claims",
                                          "pipeline.studies.a.claims.study"),
                                         ("pipeline.studies.report", "pipeline.studies.a"),
                                         ("pipeline.studies.report",
                                          "pipeline.studies.a.figures")]


def test_an_import_cycle_closed_by_a_lazy_import_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "pkg/__init__.py": "",
        "pkg/a.py": "from .b import f\n",
        "pkg/b.py": "def f():\n    from pkg.sub import c\n",
        "pkg/sub/__init__.py": "",
        "pkg/sub/c.py": "from .. import a\n",
        "pkg/d.py": "import pkg.a\n",  # imports into the cycle, is not in it
    })
    assert import_cycles(import_graph("pkg", root=root)) == [["pkg.a", "pkg.b", "pkg.sub.c"]]
    (root / "pkg/sub/c.py").write_text("import numpy\n")
    assert import_cycles(import_graph("pkg", root=root)) == []


def test_a_private_import_across_modules_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "pkg/__init__.py": "",
        "pkg/a.py": "_x = 1\ndef __dunder__(): pass\n",
        "pkg/b.py": "from .a import __dunder__\nfrom . import a as _a\n",  # allowed
        "pkg/c.py": "def g():\n    from pkg.a import _x\n",
        "pkg/d.py": "import pkg._hidden\n",
    })
    assert private_imports("pkg", root=root) == {("pkg.c", "_x"), ("pkg.d", "_hidden")}


def test_a_kernel_module_importing_an_analysis_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "bbb/__init__.py": "", "bbb/analysis/__init__.py": "", "bbb/analysis/stats.py": "",
        "bbb/dynamics/__init__.py": "",
        "bbb/dynamics/a.py": "def f():\n    from ..analysis import stats\n",
        "bbb/simulate.py": "from .dynamics import a\n",
    })
    assert analysis_imports_of(("dynamics/a.py", "simulate.py"), root) == {
        "bbb/dynamics/a.py": ["bbb.analysis", "bbb.analysis.stats"]}


def test_the_api_importing_the_cli_is_caught(tmp_path):
    root = _tree(tmp_path, {"pipeline/__init__.py": "", "pipeline/cli.py": "",
                            "pipeline/api.py": "def f():\n    from .cli import default_store_path\n"})
    assert imports_cli(root / "pipeline/api.py", root) == ["pipeline.cli",
                                                           "pipeline.cli.default_store_path"]
    (root / "pipeline/api.py").write_text("from .commands.common import load\n")
    assert imports_cli(root / "pipeline/api.py", root) == ["pipeline.commands.common",
                                                           "pipeline.commands.common.load"]


def test_a_layer_importing_a_layer_above_it_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "pipeline/__init__.py": "",
        "pipeline/api.py": "from .tables.reduce import f\n",  # the top imports down: allowed
        "pipeline/workflow/__init__.py": "", "pipeline/workflow/study.py": "",
        "pipeline/store/__init__.py": "",
        "pipeline/store/layout.py": "from ..workflow.study import Study\n"  # down: allowed
                                    "def g():\n    from ..execute.adaptive import STOP\n",  # up
        "pipeline/execute/__init__.py": "", "pipeline/execute/adaptive.py": "",
        "pipeline/tables/__init__.py": "",
        "pipeline/tables/reduce.py": "from pipeline import api\n",  # up, to the top
        "pipeline/claims/__init__.py": "",
    })
    assert upward_imports(root) == [("pipeline.store.layout", "pipeline.execute.adaptive"),
                                    ("pipeline.tables.reduce", "pipeline"),  # its __init__
                                    ("pipeline.tables.reduce", "pipeline.api")]
    (root / "pipeline/store/layout.py").write_text("from ..workflow.study import Study\n")
    (root / "pipeline/tables/reduce.py").write_text("from ..execute import adaptive\n")
    assert upward_imports(root) == []


def test_a_package_folder_missing_from_the_wheel_is_caught(tmp_path):
    root = _tree(tmp_path, {"pkg/__init__.py": "", "pkg/a.py": "", "pkg/sub/__init__.py": "",
                            "pkg/sub/scenes/x.toml": ""})
    assert package_folders("pkg", root=root) == {"pkg", "pkg.sub"}


def test_a_shim_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "pkg/__init__.py": '"""A package gathering its names."""\nfrom .real import f\n',  # allowed
        "pkg/real.py": '"""Real."""\n\ndef f():\n    return 1\n',
        "pkg/old.py": '"""Moved to pkg.real."""\nfrom __future__ import annotations\n\n'
                      'from .real import f\n\n__all__ = ["f"]\n',
        "pkg/star.py": '"""Real, and a star import."""\nfrom .real import *\n\nX = 1\n',
        "pkg/starred/__init__.py": "from ..real import *\n",
        "pkg/main.py": '"""An entry point."""\n\nif __name__ == "__main__":\n'
                       '    from pkg.real import f\n    f()\n',  # runs, re-exports nothing
        "pkg/uses.py": "from .real import f\n\nY = f()\n",  # imports and does something
        "pkg/oldmain.py": 'from .real import f\n\nif __name__ == "__main__":\n    f()\n',  # and runs
    })
    assert [rel(p, root) for p in modules("pkg", root=root) if is_shim(p)] == [
        "pkg/old.py", "pkg/oldmain.py", "pkg/star.py", "pkg/starred/__init__.py"]


def test_a_module_name_used_twice_is_caught(tmp_path):
    root = _tree(tmp_path, {
        "bbb/__init__.py": "", "bbb/a/__init__.py": "", "bbb/b/__init__.py": "",
        "bbb/a/liftoff.py": "", "bbb/b/liftoff.py": "", "bbb/a/__main__.py": "",
        "bbb/b/__main__.py": "", "pipeline/__init__.py": "", "pipeline/x/__init__.py": "",
        "pipeline/x/run.py": "", "pipeline/studies/s/run.py": "",  # a study: its own template
        "pipeline/studies/s/claims.py": "", "pipeline/studies/t/claims.py": "",
        "pipeline/record.py": "", "bbb/record.py": "",
    })
    assert engine_duplicates(root) == {"liftoff.py": ["bbb/a/liftoff.py", "bbb/b/liftoff.py"],
                                       "record.py": ["bbb/record.py", "pipeline/record.py"]}
