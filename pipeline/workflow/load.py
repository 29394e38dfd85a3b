"""Read a workflow TOML (a *scene*) into a :class:`Study`, the validated workflow.

A workflow says what to study, and nothing it does not ask for is computed or stored.  Its
keys are declared once in :mod:`pipeline.workflow.keys` (type, units, range, default, doc);
:mod:`pipeline.workflow.schema` checks each table against them, and the rules that involve several
keys (chunk_size divides n_particles, every frequency gives valid bbb.Params, ...) are here.
``python -m pipeline.workflow --reference [--write]`` (:mod:`pipeline.workflow.__main__`)
prints (writes into pipeline/README.md) the reference table generated from the declarations.

```toml
[study]
name = "smoke"                 # optional; default: the file name without .toml
seed = 2004                    # root of every chunk's SeedSequence

[params]                       # bbb.Params preset and overrides (mm, s)
preset = "klages2004"
alpha = 0.7

[frequencies]                  # Hz, multiples of 1 mHz; a list ...
values = [54.0, 60.0, 72.0]
# ... or an inclusive grid:  start = 50.0, stop = 99.2, step = 0.4

# [grid]                       # optional sweep axes over [params] keys (pipeline.workflow.grid):
# beta = [0.9, 0.99]           # the points are every combination with [frequencies], f innermost

[families.launched]            # initial-condition families, by name
initial = "launched"
launch_speed = [0.0, 200.0]    # mm/s, upward relative to the floor

accuracy = "draft"             # a named preset, or [accuracy] preset = ... plus overrides

[observables.positions]        # x at 0, sample_dt, ..., t_max (for the MSD)
[observables.collisions]       # post-collision states
record = 2000

[analysis]                     # how `bbb reduce` reads the positions
discard = 0.1
```

The result is a :class:`pipeline.workflow.study.Study` (also importable from here).  Any mistake raises
:class:`WorkflowError`, whose message is one line naming the file, the line (when it can be
found), the key, and what is allowed.
"""

from __future__ import annotations

import re
from pathlib import Path

from bbb.numerics import Numerics

from .accuracy import ACCURACY_PRESETS, NUMERICS_KNOBS
from .grid import Grid, check_points, read_grid
from .identity import f_key
from .keys import (
    ALLOWED_F,
    DEFAULT_ANALYSIS,
    INITIAL_KINDS,
    PARAM_FIELDS,
    TABLES,
    Accuracy,
    Analysis,
    Family,
    FrequenciesTable,
    Observables,
    ParamsTable,
    RefineTable,
    StudyTable,
    observables_table,
    reference_markdown,
)
from .observables.registry import scene_tables
from .schema import Reader, as_dict, declared, line_of, tname
from .study import (  # the validated workflow; importable from here as before the split
    GridNotRunnable,
    Study,
    WorkflowError,
    resolve_params,
)
from .suggest import did_you_mean

__all__ = [
    "WorkflowError",
    "Family",
    "Accuracy",
    "Observables",
    "Analysis",
    "Study",
    "load_workflow",
    "parse_workflow",
    "GridNotRunnable",
    "reference_markdown",
    "INITIAL_KINDS",
    "DEFAULT_ANALYSIS",
]


# -- reading ----------------------------------------------------------------------------------
def load_workflow(path: str | Path) -> Study:
    """Read and validate a workflow file; raises WorkflowError (one line) on any mistake."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise WorkflowError(str(p), "", "no such workflow file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise WorkflowError(str(p), "", f"cannot read: {e}") from None
    return parse_workflow(text, source=str(p))


def parse_workflow(text: str, source: str = "<workflow>") -> Study:
    """Validate a workflow given as TOML text; ``source`` names it in errors."""
    r = Reader(text, source, WorkflowError)
    doc = r.doc
    for k in doc:
        if k not in TABLES:
            r.fail((k,), f"unknown {'section' if isinstance(doc[k], dict) else 'top-level key'}"
                   + did_you_mean(k, TABLES), ", ".join(TABLES))
    st = r.table(doc.get("study"), ("study",), StudyTable)
    name = st["name"]
    if name is None:  # the file name, which must then be a valid name too
        stem = Path(source).stem if source and not source.startswith("<") else "study"
        name = r.check(stem, ("study", "name"), _key(StudyTable, "name"), {})
    grid, invalid, grid_refine = read_grid(r, doc)
    preset, overrides = _params(r, doc, grid)
    freqs, refine = _frequencies(r, doc)
    if grid:
        check_points(r, preset, overrides, grid, invalid, freqs)
    for f in freqs if not grid else ():  # every frequency must give valid Params
        try:
            resolve_params(preset, f, overrides)
        except ValueError as e:
            fld = _field_of(e, "Params")
            path = ("frequencies",) if fld == "f" else ("params", fld) if fld else ("params",)
            if fld in PARAM_FIELDS and fld not in overrides:
                path = ("params", "Gamma" if fld == "A" and "Gamma" in overrides else "preset")
            r.fail(path, f"invalid parameters at f = {f:g} Hz: {e}")
    acc = _accuracy(r, doc)
    obs = _observables(r, doc, acc)
    study = Study(name=name, source=source, seed=st["seed"], preset=preset, overrides=overrides,
                  frequencies=freqs, families=_families(r, doc, acc.n_particles), accuracy=acc,
                  observables=obs, analysis=_analysis(r, doc), refine=refine, grid=grid,
                  invalid=invalid, grid_refine=grid_refine, text=text)
    if grid and refine is not None:
        r.fail(("frequencies", "refine"), "frequency refinement of a map",
               "[grid.refine] with a resolution f = ... (it refines along f at every grid "
               "line, and along the grid's axes)")
    if grid_refine is not None and grid_refine.quantity == "v" and not {"tilt", "throw"} & (
            set(overrides) | {a for a, _ in grid}) and study.mirror_symmetric:
        r.fail(("grid", "refine", "quantity"), "v on a level floor vibrated vertically (v = 0 "
               "by symmetry)", 'quantity = "D", or a tilt or throw in [params] or [grid]')
    if grid_refine is not None and not obs.positions:
        r.fail(("grid", "refine"), "refinement without positions (D and v need them)",
               "[observables.positions] in the workflow")
    _mirror_pairs(r, study)
    return study


def _mirror_pairs(r: Reader, study: Study) -> None:
    """On a conveyor mirror pairs fill whole chunks, for every family or for none (a row of
    `bbb reduce` pools the families, and its bootstraps resample pairs)."""
    paired = [study.pairing(fam) == "pairs" for fam in study.families]
    for fam, p in zip(study.families, paired, strict=True):
        if p and study.accuracy.chunk_size % 2:
            r.fail(("families", fam.name, "mirror"), f"mirror pairs on this floor (tilt or "
                   f"throw) fill each chunk with pairs, but chunk_size = "
                   f"{study.accuracy.chunk_size} is odd",
                   "an even [accuracy] chunk_size, or mirror = false")
        if p != paired[0]:
            r.fail(("families", fam.name, "mirror"), f"mirror = {str(p).lower()} here but "
                   f"{str(paired[0]).lower()} for family {study.families[0].name!r}",
                   "the same mirror for every family on a floor with tilt or throw")


def _params(r: Reader, doc: dict, grid: Grid = ()) -> tuple[str, dict[str, float | str]]:
    tbl = r.table(doc.get("params"), ("params",), ParamsTable)
    overrides: dict[str, float | str] = {k: float(tbl[k]) for k in PARAM_FIELDS
                                         if tbl[k] is not None}
    if tbl["contact"] != "stick":
        # only a non-default model is an override: stick scenes keep their fingerprints
        overrides["contact"] = tbl["contact"]
    if tbl["floor"] != "arc":  # likewise the floor's shape
        overrides["floor"] = tbl["floor"]
    if tbl["Gamma"] is not None:  # the amplitude in g: A at each point's f (resolve_params)
        if tbl["A"] is not None:
            r.fail(("params", "Gamma"), "given with A (the amplitude twice)",
                   "A (mm) or Gamma (peak floor acceleration in g), not both")
        overrides["Gamma"] = float(tbl["Gamma"])
    if grid:  # whether [params] and the grid's values go together is each point's check
        return tbl["preset"], overrides
    try:
        resolve_params(tbl["preset"], 1.0, overrides)
    except ValueError as e:
        fld = _field_of(e, "Params")
        if fld == "A" and "Gamma" in overrides:
            fld = "Gamma"
        r.fail(("params", fld) if fld in overrides else ("params",), str(e))
    return tbl["preset"], overrides


#: the two forms of [frequencies], as an error's "allowed"
FREQUENCY_FORMS = ("values = [60.0, 72.0] (Hz), or start = 50.0, stop = 90.0, step = 0.5 (Hz, an "
                   "inclusive grid); also `frequencies = [60.0, 72.0]` before any table")


def _frequencies(r: Reader, doc: dict) -> tuple[tuple[float, ...], RefineTable | None]:
    if "frequencies" not in doc:
        r.fail(("frequencies",), "missing", FREQUENCY_FORMS)
    raw = doc["frequencies"]
    if isinstance(raw, list):  # frequencies = [...]
        path = ("frequencies",)
        tbl = {"values": r.check(raw, path, _key(FrequenciesTable, "values"), {}), "start": None,
               "refine": None}
    else:
        path = ("frequencies", "values")
        tbl = r.table(raw, ("frequencies",), FrequenciesTable)
    if tbl["values"] is not None:
        if any(tbl.get(k) is not None for k in ("start", "stop", "step")):
            r.fail(("frequencies",), "give either values or start/stop/step, not both")
        mhz = [_mhz(r, v, path, ALLOWED_F) for v in tbl["values"]]
    else:
        given = [k for k in ("start", "stop", "step") if tbl[k] is not None]
        for k in ("start", "stop", "step"):
            if tbl[k] is None:
                # an empty table names its header's line; a grid missing a key, the table's
                # line too (the absent key has none)
                at = ("frequencies", given[0]) if given else ("frequencies",)
                raise r.error(r.source, f"frequencies.{k}" if given else "frequencies",
                              "missing" if given else "empty: neither values nor start, stop, step",
                              FREQUENCY_FORMS, line_of(r.text, at))
        start, stop, step = (_mhz(r, tbl[k], ("frequencies", k), _key(FrequenciesTable, k)
                                  .allowed_text()) for k in ("start", "stop", "step"))
        if stop < start:
            r.fail(("frequencies", "stop"), "stop < start", "stop >= start")
        if (stop - start) % step:
            r.fail(("frequencies", "step"), "stop - start is not a multiple of step",
                   "an inclusive grid start, start + step, ..., stop")
        mhz = list(range(start, stop + 1, step))
    if len(set(mhz)) != len(mhz):
        dup = sorted({m for m in mhz if mhz.count(m) > 1})
        r.fail(path, f"repeated frequencies {[m / 1000 for m in dup]} (after mHz rounding)",
               "distinct frequencies")
    refine = tbl["refine"]
    if refine is not None:
        if not refine.extrema and not refine.jumps:
            r.fail(("frequencies", "refine"), "refines nothing (extrema = false, jumps = false)",
                   "extrema = true and/or jumps = true, or no refine")
        if len(mhz) < 3:
            r.fail(("frequencies", "refine"), f"needs at least 3 frequencies to find an "
                   f"extremum, got {len(mhz)}", "a grid of 3 or more frequencies")
    return tuple(m / 1000 for m in mhz), refine


def _mhz(r: Reader, v: float, path: tuple[str, ...], allowed: str) -> int:
    m = f_key(v)
    # f enters the seed as an integer number of mHz, so it must be exactly representable.
    if abs(v * 1000 - m) > 1e-6 * max(1.0, abs(v)):
        r.fail(path, f"{v!r} is not a multiple of 0.001 Hz", allowed)
    return m


def _families(r: Reader, doc: dict, n_particles: int) -> tuple[Family, ...]:
    if "families" not in doc:
        return (Family("rest", "rest"),)
    fams = doc["families"]
    if not isinstance(fams, dict) or not fams:
        r.fail(("families",), "must be one or more tables [families.NAME]",
               '[families.rest] initial = "rest"')
    out = []
    for name, tbl in fams.items():
        path = ("families", name)
        if not _FAMILY_RE.fullmatch(name):
            r.fail(path, f"bad family name {name!r}", "a letter, then letters, digits, _ -")
        if isinstance(tbl, dict) and "initial" not in tbl and name in INITIAL_KINDS:
            tbl = {"initial": name, **tbl}  # [families.rest] means initial = "rest"
        if not isinstance(tbl, dict):
            r.fail(path, f"must be a table, got {tname(tbl)}", "[families.NAME] initial = ...")
        out.append(Family(name, **r.table(tbl, path, Family)))
        if (bad := out[-1].lattice_problem(n_particles)) is not None:  # one particle per cell
            r.fail((*path, bad[0]), bad[1], bad[2])
    keys = [f.key for f in out]
    if len(set(keys)) != len(keys):  # crc32 collision: astronomically rare, but checked
        r.fail(("families",), "two family names hash to the same seed key; rename one")
    return tuple(out)


def _accuracy(r: Reader, doc: dict) -> Accuracy:
    raw = doc.get("accuracy")
    if isinstance(raw, str):  # accuracy = "draft"
        vals = {k.name: None for k in declared(Accuracy)}
        vals["preset"] = r.check(raw, ("accuracy",), _key(Accuracy, "preset"), {})
    else:
        vals = r.table(raw, ("accuracy",), Accuracy)
    preset = ACCURACY_PRESETS[vals["preset"]]
    _target_keys(r, vals, raw if isinstance(raw, dict) else {})
    for k in declared(Accuracy):
        if vals[k.name] is None:
            vals[k.name] = preset.get(k.name)
        if vals[k.name] is not None:
            vals[k.name] = {"int": int, "float": float}.get(k.kind, str)(vals[k.name])
    try:
        Numerics(**{k: vals[k] for k in NUMERICS_KNOBS})
    except ValueError as e:
        r.fail(("accuracy", _field_of(e, "Numerics") or "preset"), str(e))
    if vals["n_particles"] % vals["chunk_size"]:
        r.fail(("accuracy", "chunk_size"),
               f"{vals['chunk_size']} does not divide n_particles = {vals['n_particles']}",
               "a divisor of n_particles (every chunk holds the same number of particles)")
    n = vals["t_max"] / vals["sample_dt"]
    if abs(n - round(n)) > 1e-9 * n:
        r.fail(("accuracy", "sample_dt"), f"t_max = {vals['t_max']:g} s is not a multiple of "
               f"sample_dt = {vals['sample_dt']:g} s", "a sample_dt that divides t_max")
    if n > 10**6:
        r.fail(("accuracy", "sample_dt"), f"{round(n)} samples per trajectory is too many",
               "t_max / sample_dt <= 1e6")
    return Accuracy(**vals)


def _target_keys(r: Reader, vals: dict, raw: dict) -> None:
    """target_ci, d_resolved, max_particles: the cap becomes n_particles (the store's size)."""
    if vals["target_ci"] is None:
        for k in ("d_resolved", "max_particles"):
            if vals[k] is not None:
                r.fail(("accuracy", k), "only with target_ci",
                       "target_ci = 0.03 (say) beside it, or no " + k)
        return
    if "n_particles" in raw:
        r.fail(("accuracy", "n_particles"), "with target_ci the number of particles is chosen "
               "per (frequency, family)", "max_particles = N for the cap, instead of n_particles")
    if vals["max_particles"] is None:  # the preset's n_particles caps it
        vals["max_particles"] = ACCURACY_PRESETS[vals["preset"]]["n_particles"]
    vals["n_particles"] = vals["max_particles"]


def _observables(r: Reader, doc: dict, acc: Accuracy) -> Observables:
    on = ("[observables.positions] and/or [observables.collisions] (also [observables.contact], "
          "[observables.jumps], [observables.lyapunov])")
    if "observables" not in doc:
        r.fail(("observables",), "missing", on)
    obs = r.table(doc["observables"], ("observables",), observables_table(), {"t_max": acc.t_max})
    if all(v is None for v in obs.values()):
        r.fail(("observables",), "nothing to record", on)
    adaptive = "target_ci" if acc.adaptive else "frequencies.refine" if _has_refine(doc) else None
    if adaptive and obs["positions"] is None:
        r.fail(("observables", "positions"), f"{adaptive} needs D, so positions",
               "[observables.positions] beside " + adaptive)
    coll, lyap = obs["collisions"], obs["lyapunov"]
    if lyap is not None and lyap.particles > acc.n_particles:
        r.fail(("observables", "lyapunov", "particles"),
               f"{lyap.particles} > n_particles = {acc.n_particles}",
               f"1 … {acc.n_particles} (accuracy n_particles)")
    return Observables(positions=obs["positions"] is not None,
                       collisions_record=coll.record if coll else None,
                       collisions_from=float(coll.record_from) if coll else 0.0,
                       contact=obs["contact"] is not None,
                       jumps=obs["jumps"] is not None,
                       lyapunov_particles=lyap.particles if lyap else None,
                       lyapunov_d0=float(lyap.d0) if lyap else 1e-8,
                       lyapunov_discard=float(lyap.discard) if lyap else 0.1,
                       collisions_x_jumps=int(coll.x_jumps) if coll else 0,
                       more=tuple((o.name, tuple(as_dict(obs[o.name]).items()))
                                  for o in scene_tables() if obs[o.name] is not None))



def _analysis(r: Reader, doc: dict) -> Analysis:
    an = r.table(doc.get("analysis"), ("analysis",), Analysis)
    if an["fit_from"] >= an["fit_to"]:
        r.fail(("analysis", "fit_to"), "fit_to <= fit_from", "fit_from < fit_to")
    return Analysis(**{k: float(v) if k != "ci_method" else v for k, v in an.items()})


# -- small helpers ----------------------------------------------------------------------------
_FAMILY_RE = re.compile(r"[A-Za-z][A-Za-z0-9_-]*")


def _key(cls: type, name: str):
    return next(k for k in declared(cls) if k.name == name)


def _field_of(e: ValueError, cls: str) -> str | None:
    """'Params.alpha = ... is out of range' -> 'alpha'."""
    m = re.search(rf"{cls}\.(\w+)", str(e))
    return m.group(1) if m else None


def _has_refine(doc: dict) -> bool:
    fr = doc.get("frequencies")
    return isinstance(fr, dict) and fr.get("refine") not in (None, False)

