"""``bbb verify STORE``: re-check a study store against its own workflow, chunk by chunk.

What is checked (each failure is one :class:`Problem`, naming the array and, for data, the
frequency, family and chunk):

- root attributes: every attribute `bbb run` writes is there; the stored workflow, as this
  version of bbb reads it, gives the stored ``workflow_fingerprint``, and with the stored
  kernel attributes the stored ``fingerprint``; the kernel that made the store
  (``kernel_hash``, ``numba_version``, ``numpy_version``) is this bbb's
  (:func:`bbb.provenance.kernel_identity`), else `bbb run` would refuse to resume the store
  and its chunks cannot be reproduced here; ``params`` are the workflow's stored resolved
  parameters, ``numerics``, ``accuracy`` and ``seeding`` what its stored accuracy and the
  seeding rule give; the layout version is known.  (The TOML source is not re-parsed: what
  a preset name means may change between versions, the stored resolved workflow is what the
  data were made with);
- layout: every array of the workflow's layout exists with its shape, chunks, dtype and
  dimension names, coordinates hold the workflow's values, and there is no other array;
- every done-marker readable, and every chunk marked done (chunks not done are not data yet:
  a re-run recomputes them) intact -- each data array's chunk decodes (its CRC-32C) and holds
  the values its task wrote (their recorded digest), :mod:`pipeline.store.integrity`: a
  deleted, cut, altered or NaN-overwritten chunk is one line, and ``bbb run`` recomputes it;
- every intact done chunk's data are physically sound, by the checks of
  :mod:`pipeline.store.chunk_checks` (a run of a faulty kernel writes intact nonsense).

Reading needs no lock: a done chunk is complete before its marker is written, so a store can
be verified while a run is still filling it.

The checks of the data inside one chunk are another idea (is this particle's record physics
our kernel could have produced?) and live in :mod:`pipeline.store.chunk_checks`.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import zarr

from bbb.params import Params
from bbb.provenance import kernel_identity

from ..workflow.observables.counters import COUNTERS
from ..workflow.schema import as_dict
from ..workflow.study import Study
from .chunk_checks import ON_SURFACE_MM, chunk_problems
from .integrity import read_markers, scan
from .layout import create_layout
from .study_store import (
    JSON_ATTRS,
    KERNEL_ATTRS,
    LAYOUT_VERSION,
    SEEDING,
    StoreError,
    check_metadata,
    is_local,
    missing_store,
    normalize_path,
    read_attrs,
    store_fingerprint,
)
from .study_store import package_version as _version

__all__ = ["Problem", "VerifyReport", "verify_store", "ON_SURFACE_MM", "REQUIRED_ATTRS"]

REQUIRED_ATTRS = ("workflow", "workflow_toml", "params", "numerics", "accuracy", "seeding",
                  "bbb_version", "bbb_store_layout", "created", *KERNEL_ATTRS,
                  "workflow_fingerprint", "fingerprint")
_REPRODUCED = ("params", "numerics", "accuracy", "seeding")  # attrs re-derived from the workflow


@dataclass(frozen=True)
class Problem:
    """One inconsistency: ``where`` names the attribute or the array (and chunk)."""

    where: str
    what: str

    def __str__(self) -> str:
        return f"{self.where}: {self.what}"


@dataclass
class VerifyReport:
    """The outcome of :func:`verify_store`: chunks done / checked and the problems found."""

    path: str
    name: str = "?"
    n_chunks: int = 0
    n_done: int = 0
    chunks_checked: bool = False
    problems: list[Problem] = field(default_factory=list)
    n_damaged: int = 0  # damaged chunks (bytes not those written): `bbb run` recomputes them

    @property
    def ok(self) -> bool:
        return not self.problems

    def summary(self) -> str:
        verdict = "OK" if self.ok else f"{len(self.problems)} inconsistencies"
        if not self.chunks_checked:
            return f"{self.name}: chunks not checked (workflow or layout unusable) in {self.path}: {verdict}"
        repair = (f" ({self.n_damaged} damaged chunks: `bbb run` with the store's workflow "
                  "recomputes them)" if self.n_damaged else "")
        return (f"{self.name}: verified {self.n_done} done of {self.n_chunks} chunks in "
                f"{self.path}: {verdict}{repair}")


def verify_store(path: str | os.PathLike) -> VerifyReport:
    """Check the store at ``path`` (local path or fsspec URL); problems are returned, not raised.

    Raises StoreError only when ``path`` holds no bbb study store at all (nothing to verify),
    or MetadataDamaged (a StoreError) naming a damaged ``zarr.json``: its chunks cannot be
    read as the store describes them until `bbb run` rebuilds it.
    """
    given, path = path, normalize_path(path)
    if is_local(path) and os.path.isfile(path):  # a scene given where a store is asked for
        raise missing_store(path, given)
    report = VerifyReport(path)
    if is_local(path):
        check_metadata(path)  # a damaged zarr.json: MetadataDamaged, naming it
    try:
        # the arrays' own metadata, not the consolidated copy in the root (checked apart)
        g = zarr.open_group(path, mode="r", use_consolidated=False)
    except (FileNotFoundError, zarr.errors.GroupNotFoundError, zarr.errors.NodeTypeValidationError):
        check_metadata(path)
        raise missing_store(path, given) from None
    except Exception as e:  # e.g. a file, or an unreadable zarr.json, where the store should be
        check_metadata(path)
        raise StoreError(f"{path}: cannot open ({type(e).__name__}: {e}); "
                         "allowed: a store made by `bbb run`") from None
    raw = dict(g.attrs)
    attrs = read_attrs(g)
    if "fingerprint" not in attrs and "workflow" not in attrs:
        raise StoreError(f"{path}: not a (complete) bbb study store; "
                         "allowed: a store made by `bbb run`")
    for key in JSON_ATTRS:  # netCDF-safe: nested attributes are JSON strings
        if key in raw and not isinstance(attrs[key], dict):
            report.problems.append(Problem(f"attribute {key}", "not a JSON object string"))
    study = _check_attrs(attrs, report.problems)
    if study is None:  # without its workflow nothing else can be checked
        return report
    report.name = study.name
    if _check_layout(g, study, report.problems):
        _check_chunks(g, study, report, _stored_params(attrs, study))
    _check_consolidated(path, g, report.problems)
    return report


# -- attributes ---------------------------------------------------------------------------------
def _check_attrs(attrs: dict[str, Any], problems: list[Problem]) -> Study | None:
    for key in REQUIRED_ATTRS:
        if key not in attrs:
            problems.append(Problem(f"attribute {key}", "missing"))
    try:
        study = Study.from_dict(attrs["workflow"], text=attrs.get("workflow_toml", ""))
    except Exception as e:  # any malformed dict: KeyError, TypeError, ValueError, ...
        problems.append(Problem("attribute workflow",
                                f"not a readable workflow ({type(e).__name__}: {e})"))
        return None
    try:
        fp = study.fingerprint()
    except Exception as e:  # e.g. a parameter preset this version no longer has
        problems.append(Problem("attribute workflow", f"not usable by bbb {_version()} "
                                f"({type(e).__name__}: {e})"))
        return None
    stored_kernel = {k: attrs.get(k) for k in KERNEL_ATTRS}
    if "workflow_fingerprint" in attrs and attrs["workflow_fingerprint"] != fp:
        problems.append(Problem("attribute workflow_fingerprint",
                                f"{_short(attrs['workflow_fingerprint'])} does not match the "
                                f"stored workflow ({_short(fp)}): the attributes were altered, or "
                                "the parameter presets changed since bbb "
                                f"{attrs.get('bbb_version', '?')} made the store"))
    if "fingerprint" in attrs and all(isinstance(v, str) for v in stored_kernel.values()):
        want = store_fingerprint(fp, stored_kernel)
        if attrs["fingerprint"] != want:
            problems.append(Problem("attribute fingerprint", f"{_short(attrs['fingerprint'])} does "
                                    f"not match the stored workflow and kernel ({_short(want)}): "
                                    "the attributes were altered"))
    kernel = kernel_identity()
    for key in KERNEL_ATTRS:
        if key in attrs and attrs[key] != kernel[key]:
            problems.append(Problem(f"attribute {key}", f"store {attrs[key]}, this bbb "
                                    f"{kernel[key]}: made by another kernel; its chunks cannot be "
                                    "reproduced here and `bbb run` refuses to resume it"))
    resolved = attrs["workflow"].get("resolved_params", study.base_params)
    expected = {
        "params": resolved,
        "numerics": study.accuracy.numerics().as_dict(),
        "accuracy": as_dict(study.accuracy),  # keys added later (target_ci) only when set
        "seeding": SEEDING,
    }
    for key in _REPRODUCED:
        if key not in attrs:
            continue
        got, want = _json(attrs[key]), _json(expected[key])
        if key == "accuracy" and isinstance(got, dict):
            # the preset name and n_resamples do not determine the data; a later run may
            # change n_resamples (recorded in `workflow` for `bbb reduce`)
            got = {k: v for k, v in got.items() if k not in ("preset", "n_resamples")}
            want = {k: v for k, v in want.items() if k not in ("preset", "n_resamples")}
        if got != want:
            problems.append(Problem(f"attribute {key}", f"{_diff(got, want)} (stored vs. the "
                                    "stored workflow's)"))
    layout = attrs.get("bbb_store_layout")
    if "bbb_store_layout" in attrs and layout != LAYOUT_VERSION:
        problems.append(Problem("attribute bbb_store_layout",
                                f"{layout!r}; allowed: {LAYOUT_VERSION}"))
    return study


# -- layout ---------------------------------------------------------------------------------------
def _check_layout(g: zarr.Group, study: Study, problems: list[Problem]) -> bool:
    """Arrays as `bbb run` lays them out for this study; False if chunks cannot be checked."""
    ref = zarr.open_group(zarr.storage.MemoryStore(), mode="w")
    create_layout(ref, study)
    want = dict(ref.arrays())
    try:
        have = dict(g.arrays())
    except Exception as e:
        problems.append(Problem("layout", f"arrays cannot be listed ({type(e).__name__}: {e})"))
        return False
    n_before = len(problems)
    for name in sorted(set(have) - set(want)):
        problems.append(Problem(name, "not an array of this workflow's layout"))
    for name, w in want.items():
        if name not in have:
            problems.append(Problem(name, "missing"))
            continue
        h = have[name]
        for what, a, b in (("shape", h.shape, w.shape), ("chunks", h.chunks, w.chunks),
                           ("dtype", str(h.dtype), str(w.dtype)),
                           ("codecs", _codecs(h), _codecs(w)),
                           ("dimension names", _dims(h), _dims(w))):
            if a != b:
                problems.append(Problem(name, f"{what} {a}; allowed: {b}"))
        if w.shape and len(w.shape) == 1 and h.shape == w.shape and name not in _DATA:
            try:
                same = np.array_equal(np.asarray(h[...]), np.asarray(w[...]))
            except Exception as e:
                problems.append(Problem(name, f"unreadable ({type(e).__name__}: {e})"))
                continue
            if not same:
                problems.append(Problem(name, "coordinate values differ from the workflow's"))
    # chunk checks index every data array by (frequency, family, particle...): they need the
    # data arrays and done to be laid out right
    return not any(p.where in _DATA or p.where in ("layout", "array") for p in problems[n_before:])


def _check_consolidated(path: str, g: zarr.Group, problems: list[Problem]) -> None:
    """The consolidated metadata (what xarray.open_zarr reads) lists the arrays as they are."""
    try:
        meta = zarr.open_group(path, mode="r").metadata.consolidated_metadata
    except Exception as e:
        problems.append(Problem("consolidated metadata", f"unreadable ({type(e).__name__}: {e})"))
        return
    if meta is None:
        return  # not consolidated (yet): readers fall back to the arrays' own metadata
    listed = {k: tuple(v.shape) for k, v in meta.metadata.items() if hasattr(v, "shape")}
    actual = {k: a.shape for k, a in g.arrays()}
    if listed != actual:
        diff = sorted(set(listed) ^ set(actual)) or sorted(
            k for k in listed if listed[k] != actual[k])
        problems.append(Problem("consolidated metadata", f"differs from the arrays ({', '.join(diff)}); "
                                "a finishing `bbb run` rewrites it"))


_DATA = ("positions", "collisions", "n_recorded", "done", "chunk_seconds", "digest",
         *(f"n_{c}" for c in COUNTERS), "held_time", "sliding_time")


# -- chunks --------------------------------------------------------------------------------------
def _stored_params(attrs: dict[str, Any], study: Study) -> Callable[[int], Params]:
    """Params of the point of store index fi from the stored ``params`` attribute (what the
    data were made with), or from the workflow if that attribute is unusable (reported by the
    attribute checks) or does not name them alone (a grid's axes, Gamma)."""
    from_workflow = lambda fi: study.points[fi].params  # noqa: E731
    try:
        base = {k: float(v) for k, v in dict(attrs["params"]).items()}
        Params(f=1.0, **base)
    except Exception:
        return from_workflow
    if study.grid:
        return from_workflow
    return lambda fi: Params(f=float(study.frequencies[fi]), **base)


def _check_chunks(g: zarr.Group, study: Study, report: VerifyReport,
                  params_at: Callable[[int], Params]) -> None:
    problems = report.problems

    def where(array: str, fi, mi, ci) -> str:
        return f"{array}[{study.points[fi].label()}, family {study.families[mi].name}, chunk {ci}]"

    try:
        done, damage = read_markers(g)
        damage += scan(g, done, study.accuracy.chunk_size)
    except Exception as e:  # e.g. an unreadable `array` coordinate
        problems.append(Problem("done", f"chunks cannot be read ({type(e).__name__}: {e})"))
        return
    report.n_chunks, report.n_done = done.size, int(done.sum())
    report.chunks_checked = True
    for d in damage:
        problems.append(Problem(where(d.array, d.fi, d.mi, d.ci), d.why))
    damaged = {(d.fi, d.mi, d.ci) for d in damage}
    report.n_damaged = len(damaged)
    for fi, mi, ci in zip(*np.nonzero(done), strict=True):
        if (fi, mi, ci) in damaged:  # its physics would be that of the damage
            continue
        for array, what in chunk_problems(g, study, int(fi), int(mi), int(ci), params_at):
            problems.append(Problem(where(array, fi, mi, ci), what))


# -- helpers ---------------------------------------------------------------------------------
def _json(o: Any) -> Any:
    # attributes went through JSON: compare like with like (tuples -> lists, inf kept)
    return json.loads(json.dumps(o))


def _diff(got: Any, want: Any) -> str:
    if isinstance(got, dict) and isinstance(want, dict):
        for k in sorted(set(got) | set(want)):
            if got.get(k) != want.get(k):
                return f"{k}: {got.get(k)!r}, expected {want.get(k)!r}"
    return f"{got!r}, expected {want!r}"


def _dims(a: zarr.Array) -> tuple | None:
    names = getattr(a.metadata, "dimension_names", None)
    return tuple(names) if names is not None else None


def _codecs(a: zarr.Array) -> str:
    return ", ".join(c.to_dict()["name"] for c in a.metadata.codecs)


def _short(fp: Any) -> str:
    return str(fp)[:12]
