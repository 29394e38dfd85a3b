"""A declared schema for TOML input: each key declared once, on a dataclass field, and one
small generic validator that reads a TOML table against those declarations.

A key is a dataclass field whose default is ``key(...)``: its type is the field's annotation,
and the declaration holds its units, range or choices, default and a one-line doc::

    @dataclass(frozen=True)
    class Analysis:
        ci: float = key(0.95, "bootstrap confidence level", units="confidence level",
                        ge=0.5, lt=1)

From the declarations come (a) validation with one-line errors naming the file, the line, the
dotted key and what is allowed, and (b) the reference table in the docs (:func:`reference`),
so the docs cannot drift from what is checked.

Why dataclasses + this validator rather than pydantic or msgspec.  The guarantee that matters
here is the error line ``file:LINE: key: problem; allowed: ...``: neither library knows TOML
line numbers, so their errors (pydantic's multi-line ValidationError, msgspec's
``Expected int, got str - at $.accuracy.n_particles``) would have to be caught, re-mapped to
lines and re-worded to say what is allowed — the same work as validating, plus a dependency
(pydantic-core is a compiled Rust extension) that the numba + numpy + dask stack does not
otherwise need.  Neither expresses the cross-key rules a workflow has (chunk_size divides
n_particles, record_from < t_max, a key valid only for one ``initial``) without custom
validators either.  What a library would add — a typed result object — the frozen dataclasses
already are.  So: the standard library only, ~300 lines, no new dependency.

Supported key types: ``bool``, ``int``, ``float``, ``str``, ``tuple[float, float]`` (a
``[lo, hi]`` pair), ``tuple[float, ...]`` (a non-empty list of numbers), and another declared
dataclass (a sub-table, which may also be switched on by ``true`` or off by ``false``); any of
them ``| None`` when the default is None (meaning: derived, see ``default_doc``).
"""

from __future__ import annotations

import dataclasses
import math
import re
import tomllib
import types
import typing
from dataclasses import dataclass, field
from typing import Any

from .suggest import did_you_mean

__all__ = ["InputError", "Key", "key", "declared", "Reader", "reference", "REQUIRED", "tname"]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()  # a key without a default must be given


class InputError(ValueError):
    """Malformed input: one line with file, line, key and what is allowed."""

    def __init__(self, file: str, key: str, problem: str, allowed: str | None = None,
                 line: int | None = None):
        self.file, self.key, self.problem = file, key, problem
        self.allowed, self.line = allowed, line
        where = f"{file}:{line}" if line else file
        text = f"{where}: {key}: {problem}" if key else f"{where}: {problem}"
        if allowed:
            text += f"; allowed: {allowed}"
        super().__init__(text)


@dataclass(frozen=True)
class Key:
    """The declaration of one key (see :func:`key` for the fields)."""

    doc: str
    default: Any = REQUIRED
    units: str = ""
    gt: float | str | None = None
    ge: float | str | None = None
    lt: float | str | None = None
    le: float | str | None = None
    choices: tuple[str, ...] | None = None
    pattern: str | None = None
    allowed: str | None = None
    note: str = ""
    finite: bool = True
    when: tuple[str, Any] | None = None
    default_doc: str | None = None
    identity: bool = True
    omit_default: bool = False
    name: str = ""
    type: Any = None

    # -- what the type is ----------------------------------------------------------------
    @property
    def base(self) -> Any:
        """The annotation without ``| None``."""
        t = self.type
        if isinstance(t, types.UnionType) or typing.get_origin(t) is typing.Union:
            args = [a for a in typing.get_args(t) if a is not type(None)]
            t = args[0]
        return t

    @property
    def kind(self) -> str:
        t = self.base
        if dataclasses.is_dataclass(t):
            return "table"
        if typing.get_origin(t) is tuple:
            return "list" if typing.get_args(t)[-1] is Ellipsis else "pair"
        return {bool: "bool", int: "int", float: "float", str: "str"}[t]

    # -- what is allowed, in words -------------------------------------------------------
    def allowed_text(self, ctx: dict[str, Any] | None = None) -> str:
        if self.allowed is not None:
            return self.allowed
        if self.choices is not None:
            return ", ".join(self.choices)
        kind = self.kind
        if kind == "table":
            subs = ", ".join(k.name for k in declared(self.base))
            return f"a table{' with ' + subs if subs else ''}, or true/false"
        if kind == "pair":
            lo = self.ge if self.ge is not None else self.gt
            op = "<=" if self.ge is not None else "<"
            rng = f" with {_fmt(lo)} {op} lo <= hi" if lo is not None else " with lo <= hi"
            return f"[lo, hi] {self.units}{rng}".replace("  ", " ")
        lo = ("<", self.gt) if self.gt is not None else ("<=", self.ge) if self.ge is not None else None
        hi = ("<", self.lt) if self.lt is not None else ("<=", self.le) if self.le is not None else None

        def bound(v):
            if isinstance(v, str):  # another key's value
                return f"{v} = {_fmt(ctx[v])}" if ctx and v in ctx else v
            return _fmt(v)

        if lo and hi:
            rng = f"{bound(lo[1])} {lo[0]} {self.name} {hi[0]} {bound(hi[1])}"
        elif lo:
            rng = f"{'>' if lo[0] == '<' else '>='} {bound(lo[1])}"
        elif hi:
            rng = f"{hi[0]} {bound(hi[1])}"
        else:
            rng = {"int": "an integer", "float": "a number", "str": "a string",
                   "bool": "true or false", "list": "a list of numbers"}[kind]
        if self.units:
            text = f"{self.units}, {rng}"
        elif kind == "int" and (lo or hi):
            text = f"an integer {rng}"
        else:
            text = rng
        return f"{text} {self.note}" if self.note else text

    def default_text(self) -> str:
        if self.default_doc is not None:
            return self.default_doc
        d = self.default
        if d is REQUIRED:
            return "required"
        if d is None:
            return "off" if self.kind == "table" else "–"
        if isinstance(d, bool):
            return str(d).lower()
        if isinstance(d, str):
            return f'"{d}"'
        if isinstance(d, tuple):
            return "[" + ", ".join(_fmt(x) for x in d) + "]"
        return _fmt(d)


def key(default: Any = REQUIRED, doc: str = "", **decl: Any) -> Any:
    """A dataclass field declaring a key: ``default`` (REQUIRED, a value, or None = derived),
    a one-line ``doc``, and any of

    units       -- units, or what the number is ("s", "mm/s", "fraction of t_max")
    gt, ge, lt, le -- bounds (a number, or the name of another key whose value bounds it)
    choices     -- the allowed strings;  pattern -- a regular expression a string must match
    allowed     -- the allowed text, when the generated one would not say it (e.g. ranges
                   that bbb.Params checks itself);  note -- appended to the generated text
    finite      -- False lets a float be +-inf (never NaN)
    when        -- (other key, value): valid only when that key of the table has that value;
                   the default applies only then, else the field is None
    default_doc -- how the default reads in the reference
    identity    -- False: not part of the data's identity (names, descriptions)
    omit_default -- left out of stored dicts at its default, so a key added later does not
                   change the fingerprint of stores made before it existed
    """
    decl_ = Key(doc=doc, default=default, **decl)
    fdefault = None if decl.get("when") else default
    if fdefault is REQUIRED:
        return field(metadata={"key": decl_})
    return field(default=fdefault, metadata={"key": decl_})


def declared(cls: type) -> tuple[Key, ...]:
    """The keys declared on a dataclass, in field order, with their names and types."""
    hints = typing.get_type_hints(cls)
    return tuple(dataclasses.replace(f.metadata["key"], name=f.name, type=hints[f.name])
                 for f in dataclasses.fields(cls) if "key" in f.metadata)


def as_dict(obj: Any, *, identity: bool = False) -> dict[str, Any]:
    """``dataclasses.asdict`` without the keys declared omit_default that sit at their
    default and, with ``identity``, without keys declared identity=False."""
    d = dataclasses.asdict(obj)
    for k in declared(type(obj)):
        if (k.omit_default and d.get(k.name) == _plain(k.default)) or (identity and not k.identity):
            d.pop(k.name, None)
    return d


def _plain(v: Any) -> Any:
    return None if v is REQUIRED else v


# ---------------------------------------------------------------------------------------------
class Reader:
    """Reads one TOML text against declarations; every mistake raises ``error`` (an
    InputError subclass) naming the file, the line (when it can be found) and the key."""

    def __init__(self, text: str, source: str, error: type[InputError] = InputError):
        self.text, self.source, self.error = text, source, error
        try:
            self.doc = tomllib.loads(text)
        except tomllib.TOMLDecodeError as e:
            m = re.search(r"\(at line (\d+), column \d+\)", str(e))
            msg = str(e).split(" (at line")[0]
            raise error(source, "", f"TOML syntax error: {msg}",
                        line=int(m.group(1)) if m else None) from None

    def fail(self, path: tuple[str, ...], problem: str, allowed: str | None = None):
        raise self.error(self.source, ".".join(path), problem, allowed, line_of(self.text, path))

    def table(self, raw: Any, path: tuple[str, ...], cls: type,
              ctx: dict[str, Any] | None = None) -> dict[str, Any]:
        """``raw`` (a TOML table, or None when absent) checked against ``cls``'s keys: unknown
        keys, types, ranges; absent keys take their defaults.  Returns {name: value}."""
        keys = declared(cls)
        names = [k.name for k in keys]
        if raw is None:
            raw = {}
        if not isinstance(raw, dict):
            self.fail(path, f"must be a table, got {tname(raw)}",
                      f"[{'.'.join(path)}] with keys {', '.join(names)}")
        for name in raw:
            if name not in names:
                self.fail(path + (name,), "unknown " + ("section" if isinstance(raw[name], dict)
                                                        else "key") + did_you_mean(name, names),
                          ", ".join(names) or "no keys")
        out: dict[str, Any] = {}
        for k in keys:
            out[k.name] = self.value(raw, path + (k.name,), k, {**(ctx or {}), **out})
        return out

    def value(self, tbl: dict, path: tuple[str, ...], k: Key, ctx: dict[str, Any]) -> Any:
        """The value of key ``k`` in table ``tbl`` (at ``path``), validated; the default if
        absent (REQUIRED: an error)."""
        applies = k.when is None or ctx.get(k.when[0]) == k.when[1]
        if k.name not in tbl:
            if k.default is REQUIRED and applies:
                self.fail(path, "missing", k.allowed_text(ctx))
            return _plain(k.default) if applies else None
        if not applies:
            self.fail(path, f'only for {k.when[0]} = "{k.when[1]}"')
        return self.check(tbl[k.name], path, k, ctx)

    def check(self, v: Any, path: tuple[str, ...], k: Key, ctx: dict[str, Any]) -> Any:
        """A given value of ``k``: type, finiteness, range, choices; returns it normalised."""
        kind, allowed = k.kind, (lambda: k.allowed_text(ctx))
        if kind == "table":
            if isinstance(v, bool):
                return k.base(**self.table({}, path, k.base, ctx)) if v else None
            if not isinstance(v, dict):
                subs = ", ".join(s.name for s in declared(k.base))
                self.fail(path, f"must be a table or true/false, got {v!r}",
                          f"[{'.'.join(path)}]{' with ' + subs if subs else ''}, or true/false")
            return k.base(**self.table(v, path, k.base, ctx))
        if kind == "bool":
            if not isinstance(v, bool):
                self.fail(path, f"must be true or false, got {tname(v)} {v!r}", allowed())
            return v
        if kind == "str":
            if not isinstance(v, str):
                self.fail(path, f"must be a string, got {tname(v)} {v!r}", allowed())
            if k.choices is not None and v not in k.choices:
                self.fail(path, f"unknown {k.name} {v!r}", allowed())
            if k.pattern is not None and not re.fullmatch(k.pattern, v):
                self.fail(path, f"bad {k.name} {v!r}", allowed())
            return v
        if kind == "pair":
            if not isinstance(v, list) or len(v) != 2 or not all(_is_number(x) for x in v):
                self.fail(path, f"must be a list of two numbers [lo, hi], got {v!r}", allowed())
            lo, hi = float(v[0]), float(v[1])
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi
                    and self._within(lo, k, ctx)):
                self.fail(path, f"{v!r} is out of range", allowed())
            return lo, hi
        if kind == "list":
            if not isinstance(v, list) or not v:
                self.fail(path, f"must be a non-empty list of numbers, got {v!r}", allowed())
            return tuple(self._number(x, path, k, ctx, "float", "numbers") for x in v)
        return self._number(v, path, k, ctx, kind, "an integer" if kind == "int" else "a number")

    def _number(self, v, path, k: Key, ctx, kind: str, what: str):
        if not _is_number(v) or (kind == "int" and isinstance(v, float)):
            self.fail(path, f"must be {what}, got {tname(v)} {v!r}", k.allowed_text(ctx))
        if kind == "float":
            v = float(v)
            if math.isnan(v) or (k.finite and math.isinf(v)):
                self.fail(path, f"must be finite, got {v!r}", k.allowed_text(ctx))
        if not self._within(v, k, ctx):
            self.fail(path, f"{v!r} is out of range", k.allowed_text(ctx))
        return v

    @staticmethod
    def _within(v: float, k: Key, ctx: dict[str, Any]) -> bool:
        def b(x):
            return ctx[x] if isinstance(x, str) else x

        return ((k.gt is None or v > b(k.gt)) and (k.ge is None or v >= b(k.ge))
                and (k.lt is None or v < b(k.lt)) and (k.le is None or v <= b(k.le)))


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


# ---------------------------------------------------------------------------------------------
def reference(sections: list[tuple[str, type, str]]) -> str:
    """A Markdown table of every declared key: (table header, dataclass, note) per section."""
    lines = ["| key | type | allowed | default | meaning |", "| --- | --- | --- | --- | --- |"]
    for header, cls, note in sections:
        lines.append(f"| **{header}** | | | | {note} |")
        for k in declared(cls):
            lines.append(f"| `{k.name}` | {_type_name(k)} | {_md(k.allowed_text())} | "
                         f"{_md(k.default_text())} | {_md(k.doc)} |")
    return "\n".join(lines) + "\n"


def _type_name(k: Key) -> str:
    return {"bool": "boolean", "int": "integer", "float": "number", "str": "string",
            "pair": "[lo, hi]", "list": "list of numbers", "table": "table"}[k.kind]


def _md(s: str) -> str:
    return s.replace("|", "\\|")


def _fmt(v: Any) -> str:
    """A bound as people write it: 2**63, 1e7, 0.5."""
    if isinstance(v, int) and v >= 2**32 and v & (v - 1) == 0:
        return f"2**{v.bit_length() - 1}"
    if isinstance(v, float) and v.is_integer() and abs(v) < 1e6:
        return str(int(v))
    s = f"{v:g}" if isinstance(v, float) else str(v)
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m.group(1) == "-" else "") + m.group(2), s)


def tname(v: Any) -> str:
    """The TOML name of a value's type."""
    return {bool: "boolean", int: "integer", float: "float", str: "string", list: "array",
            dict: "table"}.get(type(v), type(v).__name__)


def line_of(text: str, path: tuple[str, ...]) -> int | None:
    """The 1-based line of a key (or of a table header) in TOML text, if it can be found."""
    if not path:
        return None
    table: tuple[str, ...] = ()
    header_re = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
    key_re = re.compile(r"^\s*([A-Za-z0-9_\-.\"' ]+?)\s*=")
    best = None
    for i, line in enumerate(text.splitlines(), start=1):
        m = header_re.match(line)
        if m:
            table = tuple(p.strip().strip("\"'") for p in m.group(1).split("."))
            if table == path:
                return i
            if best is None and table[: len(path)] == path:
                best = i  # a table given only by the headers of its sub-tables
            continue
        m = key_re.match(line)
        if m:
            key_ = tuple(p.strip().strip("\"'") for p in m.group(1).split("."))
            full = table + key_
            if full == path:
                return i
            if best is None and full[: len(path)] == path:
                best = i  # the first key inside a table given by dotted keys
            if best is None and len(full) < len(path) and path[: len(full)] == full:
                best = i  # an inline table or array holding the key
    return best
