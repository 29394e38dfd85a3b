"""The kernel's jitted functions stay small, read off the sources: none takes more than
MAX_ARGS positional arguments and none returns a tuple (at any depth of its return
expression) of more than MAX_TUPLE items — state and options travel as records
(bbb.dynamics.options, slide.Stretch, events.Row).  Each checker is also run on a synthetic
source that breaks it."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from bbb import jit

ROOT = Path(__file__).resolve().parents[3]
KERNEL = ROOT / "bbb" / "dynamics"
MAX_ARGS = 8
MAX_TUPLE = 4
#: the decorators that make a function jitted: numba's, and bbb.jit's
JIT_DECORATORS = {"njit", "jit", *jit.__all__}
#: modules over MAX_ARGS being changed on another branch (the lead removes each once it is
#: merged: test_the_pending_list_names_only_modules_still_over_the_limit fails until then)
PENDING: set[str] = set()


def jitted(source: str) -> list[ast.FunctionDef]:
    """The functions of a source decorated with numba's njit/jit (called or not) or with one of
    bbb.jit's decorators."""
    return [node for node in ast.walk(ast.parse(source)) if isinstance(node, ast.FunctionDef)
            and any(decorator_name(d) in JIT_DECORATORS for d in node.decorator_list)]


def decorator_name(d: ast.expr) -> str:
    # the name a decorator is spelled with: njit, njit(...), numba.njit(...), inlined, ...
    if isinstance(d, ast.Call):
        d = d.func
    return d.attr if isinstance(d, ast.Attribute) else getattr(d, "id", "")


def too_many_arguments(source: str) -> list[tuple[str, int]]:
    """(name, positional arguments) of each jitted function with more than MAX_ARGS."""
    return [(f.name, n) for f in jitted(source)
            if (n := len(f.args.posonlyargs) + len(f.args.args)) > MAX_ARGS]


def too_wide_returns(source: str) -> list[tuple[str, int]]:
    """(name, items) of each jitted function returning a tuple literal of more than MAX_TUPLE."""
    bad = []
    for f in jitted(source):
        widths = [len(t.elts) for r in ast.walk(f) if isinstance(r, ast.Return) and r.value is not None
                  for t in ast.walk(r.value) if isinstance(t, ast.Tuple)]
        if widths and max(widths) > MAX_TUPLE:
            bad.append((f.name, max(widths)))
    return bad


def kernel_modules() -> list[Path]:
    return sorted(KERNEL.rglob("*.py"))


@pytest.mark.parametrize("path", kernel_modules(), ids=lambda p: p.relative_to(KERNEL).as_posix())
def test_no_jitted_function_takes_more_than_eight_positional_arguments(path):
    if path.name in PENDING:
        pytest.skip(f"{path.name} is pending (PENDING)")
    assert too_many_arguments(path.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("path", kernel_modules(), ids=lambda p: p.relative_to(KERNEL).as_posix())
def test_no_jitted_function_returns_a_tuple_of_more_than_four(path):
    assert too_wide_returns(path.read_text(encoding="utf-8")) == []


def test_the_pending_list_names_only_modules_still_over_the_limit():
    over = {p.name for p in kernel_modules() if too_many_arguments(p.read_text(encoding="utf-8"))}
    assert PENDING <= over, f"no longer over the limit, remove from PENDING: {sorted(PENDING - over)}"


def test_a_jitted_function_with_nine_arguments_is_caught():
    src = "from numba import njit\n\n@njit(cache=True)\ndef f(a, b, c, d, e, g, h, i, j):\n    return a\n"
    assert too_many_arguments(src) == [("f", 9)]
    assert too_many_arguments(src.replace(", j)", ")")) == []


def test_a_function_inlined_by_bbb_jit_is_checked_too():
    src = "from bbb.jit import inlined\n\n@inlined\ndef f(a, b, c, d, e, g, h, i, j):\n    return a\n"
    assert too_many_arguments(src) == [("f", 9)]
    assert too_many_arguments(src.replace("@inlined", "@staticmethod")) == []


def test_a_nested_wide_tuple_in_a_return_is_caught():
    src = ("from numba import njit\n\n@njit\ndef f(a):\n    return (a, a, a, a, a), 1\n")
    assert too_wide_returns(src) == [("f", 5)]
    assert too_wide_returns(src.replace("a, a, a, a, a", "a, a, a, a")) == []
