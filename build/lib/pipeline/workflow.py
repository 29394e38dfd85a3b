"""Read and validate a workflow TOML (a *scene*) into a :class:`Study`.

A workflow says what to study and nothing more is computed or stored:

```toml
[study]
name = "smoke"                 # optional; default: the file name without .toml
seed = 2004                    # root of every chunk's SeedSequence

[params]                       # bbb.Params preset and overrides (mm, s, Hz)
preset = "klages2004"
alpha = 0.7

[frequencies]                  # Hz, multiples of 1 mHz; a list ...
values = [54.0, 60.0, 72.0]
# ... or an inclusive grid:  start = 50.0, stop = 99.2, step = 0.4

[families.rest]                # initial-condition families, by name
initial = "rest"
[families.dropped]
initial = "dropped"
drop_height = [0.0, 2.0]       # mm above the surface
[families.launched]
initial = "launched"
launch_speed = [0.0, 200.0]    # mm/s, upward relative to the floor

accuracy = "draft"             # a named preset, or a table with overrides:
# [accuracy]
# preset = "draft"
# n_particles = 128

[observables.positions]        # x at 0, sample_dt, ..., t_max (for the MSD)
[observables.collisions]       # post-collision (t, x, y, vx, vy)
record = 2000                  # per particle
record_from = 20.0             # s

[analysis]                     # how `bbb reduce` reads the positions; see DEFAULT_ANALYSIS
discard = 0.1                  # fraction of t_max dropped as a transient
```

Any mistake raises :class:`WorkflowError`, whose message is one line naming the file, the
line (when it can be found), the key, and what is allowed.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import tomllib
import zlib
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bbb.numerics import Numerics
from bbb.params import PRESETS as PARAM_PRESETS
from bbb.params import Params

from .accuracy import ACCURACY_KNOBS, ACCURACY_PRESETS, DEFAULT_ACCURACY, INT_KNOBS, NUMERICS_KNOBS

__all__ = [
    "WorkflowError",
    "Family",
    "Accuracy",
    "Observables",
    "Analysis",
    "Study",
    "load_workflow",
    "parse_workflow",
    "INITIAL_KINDS",
    "DEFAULT_ANALYSIS",
]

INITIAL_KINDS = ("rest", "dropped", "launched")
PARAM_FIELDS = ("g", "A", "R", "S", "alpha", "beta")
# How `bbb reduce` analyses the positions (passed to bbb.stats).  Fractions, so that they hold
# at every accuracy preset.  discard: fraction of the run dropped at the start as a transient;
# fit_from, fit_to: lag range of the MSD fit 2 D lag + c, as fractions of the analysed duration
# T = (1 - discard) t_max; eb_lag: lag of the ergodicity-breaking parameter, fraction of T;
# eb_tolerance: factor on the Brownian EB expectation; ci, ci_method: bootstrap interval.
DEFAULT_ANALYSIS: dict[str, Any] = dict(
    discard=0.10, fit_from=0.05, fit_to=0.25, eb_lag=0.05, eb_tolerance=2.0, ci=0.95,
    ci_method="percentile",
)
CI_METHODS = ("percentile", "bca", "basic")
_NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
_FAMILY_RE = re.compile(r"^[A-Za-z][A-Za-z0-9_-]*$")


class WorkflowError(ValueError):
    """A malformed workflow: one line with file, line, key and what is allowed."""

    def __init__(
        self, file: str, key: str, problem: str, allowed: str | None = None, line: int | None = None
    ):
        self.file, self.key, self.problem = file, key, problem
        self.allowed, self.line = allowed, line
        where = f"{file}:{line}" if line else file
        text = f"{where}: {key}: {problem}" if key else f"{where}: {problem}"
        if allowed:
            text += f"; allowed: {allowed}"
        super().__init__(text)


@dataclass(frozen=True)
class Family:
    """One initial-condition family: a name and the ``bbb.simulate`` options it needs.

    drop_height  -- (lo, hi) mm above the surface, for ``initial = "dropped"``
    launch_speed -- (lo, hi) mm/s upward relative to the floor, for ``initial = "launched"``
    """

    name: str
    initial: str
    drop_height: tuple[float, float] | None = None
    launch_speed: tuple[float, float] | None = None

    @property
    def key(self) -> int:
        """A stable 32-bit number for the seed: depends on the name only, not on its position."""
        return zlib.crc32(self.name.encode("utf-8"))

    def simulate_kwargs(self) -> dict[str, Any]:
        kw: dict[str, Any] = {"initial": self.initial}
        if self.drop_height is not None:
            kw["drop_height"] = self.drop_height
        if self.launch_speed is not None:
            kw["launch_speed"] = self.launch_speed
        return kw


@dataclass(frozen=True)
class Accuracy:
    """Every knob that trades time for accuracy (units in pipeline/accuracy.py)."""

    preset: str
    n_particles: int
    chunk_size: int
    t_max: float
    sample_dt: float
    tol_t: float
    v_stick: float
    max_step: float
    n_resamples: int

    @property
    def n_chunks(self) -> int:
        return self.n_particles // self.chunk_size

    def numerics(self) -> Numerics:
        return Numerics(**{k: getattr(self, k) for k in NUMERICS_KNOBS})


@dataclass(frozen=True)
class Observables:
    """What is recorded: positions at the sample times and/or post-collision states.

    collisions_record -- post-collision states kept per particle (None: collisions off)
    collisions_from   -- record collisions at t >= this, s
    """

    positions: bool
    collisions_record: int | None = None
    collisions_from: float = 0.0

    @property
    def collisions(self) -> bool:
        return self.collisions_record is not None


@dataclass(frozen=True)
class Analysis:
    """How ``bbb reduce`` analyses the positions (fractions; see DEFAULT_ANALYSIS)."""

    discard: float
    fit_from: float
    fit_to: float
    eb_lag: float
    eb_tolerance: float
    ci: float
    ci_method: str

    def duration(self, t_max: float) -> float:
        """The analysed duration T = (1 - discard) t_max, s."""
        return (1.0 - self.discard) * t_max


@dataclass(frozen=True)
class Study:
    """A validated workflow.  Frequencies are in Hz, rounded to 1 mHz."""

    name: str
    source: str
    seed: int
    preset: str
    overrides: dict[str, float]
    frequencies: tuple[float, ...]
    families: tuple[Family, ...]
    accuracy: Accuracy
    observables: Observables
    analysis: Analysis
    text: str = field(default="", compare=False, repr=False)

    # -- derived quantities -------------------------------------------------------------------
    def params(self, f: float) -> Params:
        return Params.preset(self.preset, f=float(f), **self.overrides)

    @property
    def base_params(self) -> dict[str, float]:
        """The resolved parameters except f (which varies over the grid)."""
        d = Params.preset(self.preset, f=1.0, **self.overrides).as_dict()
        del d["f"]
        return d

    @property
    def f_mhz(self) -> tuple[int, ...]:
        return tuple(round(f * 1000) for f in self.frequencies)

    def sample_times(self) -> np.ndarray:
        """Position sample times, s: 0, dt, ..., t_max."""
        n = round(self.accuracy.t_max / self.accuracy.sample_dt)
        return np.arange(n + 1, dtype=np.float64) * self.accuracy.sample_dt

    def seed_sequence(self, f: float, family: Family, chunk: int) -> np.random.SeedSequence:
        """The seed of one chunk, keyed by values (f in mHz, family name hash, chunk index), so
        adding frequencies or families never changes the results of the others."""
        return np.random.SeedSequence(self.seed, spawn_key=(round(f * 1000), family.key, chunk))

    # -- serialisation ------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Everything resolved (preset numbers written out), JSON-able."""
        return {
            "name": self.name,
            "source": self.source,
            "seed": self.seed,
            "params": {"preset": self.preset, **self.overrides},
            "resolved_params": self.base_params,
            "frequencies": list(self.frequencies),
            "families": [_drop_none(asdict(fam)) for fam in self.families],
            "accuracy": asdict(self.accuracy),
            "observables": asdict(self.observables),
            "analysis": asdict(self.analysis),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any], text: str = "") -> Study:
        params = dict(d["params"])
        preset = params.pop("preset")
        fams = tuple(
            Family(
                name=fd["name"],
                initial=fd["initial"],
                drop_height=_tuple_or_none(fd.get("drop_height")),
                launch_speed=_tuple_or_none(fd.get("launch_speed")),
            )
            for fd in d["families"]
        )
        an = dict(d["analysis"])
        return cls(
            name=d["name"],
            source=d["source"],
            seed=int(d["seed"]),
            preset=preset,
            overrides={k: float(v) for k, v in params.items()},
            frequencies=tuple(float(f) for f in d["frequencies"]),
            families=fams,
            accuracy=Accuracy(**d["accuracy"]),
            observables=Observables(**d["observables"]),
            analysis=Analysis(**an),
            text=text,
        )

    def data_identity(self) -> dict[str, Any]:
        """The parts that determine the stored numbers (not the name, not reduce settings)."""
        acc = asdict(self.accuracy)
        del acc["preset"], acc["n_resamples"]
        return {
            "seed": self.seed,
            "params": self.base_params,
            "f_mhz": list(self.f_mhz),
            "families": [_drop_none(asdict(fam)) for fam in self.families],
            "accuracy": acc,
            "observables": asdict(self.observables),
        }

    def fingerprint(self) -> str:
        blob = json.dumps(self.data_identity(), sort_keys=True, default=_json_default)
        return hashlib.sha256(blob.encode()).hexdigest()


# ---------------------------------------------------------------------------------------------
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
    return _Reader(text, source).study()


# ---------------------------------------------------------------------------------------------
_TOP = ("study", "params", "frequencies", "families", "accuracy", "observables", "analysis")


class _Reader:
    def __init__(self, text: str, source: str):
        self.text, self.source = text, source
        self.default_name = Path(source).stem if source and not source.startswith("<") else "study"

    # -- error helpers --------------------------------------------------------------------------
    def fail(self, path: tuple[str, ...], problem: str, allowed: str | None = None):
        line = _line_of(self.text, path)
        raise WorkflowError(self.source, ".".join(path), problem, allowed, line)

    def table(self, doc: dict, path: tuple[str, ...], allowed_keys: tuple[str, ...]) -> dict:
        """doc[path] as a table (empty if absent) with no keys beyond allowed_keys."""
        val = doc.get(path[-1], {})
        if not isinstance(val, dict):
            self.fail(path, f"must be a table, got {_tname(val)}", f"[{'.'.join(path)}] with keys "
                      + ", ".join(allowed_keys))
        for k in val:
            if k not in allowed_keys:
                self.fail(path + (k,), "unknown key", ", ".join(allowed_keys) or "no keys")
        return val

    def number(self, tbl: dict, path: tuple[str, ...], default=None, *, integer=False,
               check=None, allowed: str = "") -> Any:
        key = path[-1]
        if key not in tbl:
            if default is None:
                self.fail(path, "missing", allowed)
            return default
        v = tbl[key]
        kind = "an integer" if integer else "a number"
        wrong_type = isinstance(v, bool) or not isinstance(v, int | float)
        if wrong_type or (integer and isinstance(v, float)):
            self.fail(path, f"must be {kind}, got {_tname(v)} {v!r}", allowed)
        if not integer:
            v = float(v)
            if not math.isfinite(v):
                self.fail(path, f"must be finite, got {v!r}", allowed)
        if check is not None and not check(v):
            self.fail(path, f"{v!r} is out of range", allowed)
        return v

    def pair(self, tbl: dict, path: tuple[str, ...], allowed: str) -> tuple[float, float]:
        v = tbl[path[-1]]
        if (not isinstance(v, list) or len(v) != 2
                or any(isinstance(x, bool) or not isinstance(x, int | float) for x in v)):
            self.fail(path, f"must be a list of two numbers [lo, hi], got {v!r}", allowed)
        lo, hi = float(v[0]), float(v[1])
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo <= hi):
            self.fail(path, f"{v!r} is out of range", allowed)
        return lo, hi

    # -- sections -------------------------------------------------------------------------------
    def study(self) -> Study:
        try:
            doc = tomllib.loads(self.text)
        except tomllib.TOMLDecodeError as e:
            m = re.search(r"\(at line (\d+), column \d+\)", str(e))
            msg = str(e).split(" (at line")[0]
            raise WorkflowError(self.source, "", f"TOML syntax error: {msg}",
                                line=int(m.group(1)) if m else None) from None
        for k in doc:
            if k not in _TOP:
                self.fail((k,), "unknown top-level key", ", ".join(_TOP))

        st = self.table(doc, ("study",), ("name", "description", "seed"))
        name = st.get("name", self.default_name)
        if not isinstance(name, str) or not _NAME_RE.match(name):
            self.fail(("study", "name"), f"bad name {name!r}",
                      "letters, digits, '_', '-', '.' (it names the store)")
        if "description" in st and not isinstance(st["description"], str):
            self.fail(("study", "description"), "must be a string")
        seed = self.number(st, ("study", "seed"), 2004, integer=True,
                           check=lambda v: 0 <= v < 2**63, allowed="an integer 0 <= seed < 2**63")

        preset, overrides = self.params(doc)
        freqs = self.frequencies(doc)
        for f in freqs:  # every frequency must give valid Params
            try:
                Params.preset(preset, f=f, **overrides)
            except ValueError as e:
                fld = re.search(r"Params\.(\w+)", str(e))
                key = fld.group(1) if fld else ""
                path = ("frequencies",) if key == "f" else ("params", key) if key else ("params",)
                if key in ("g", "A", "R", "S", "alpha", "beta") and key not in overrides:
                    path = ("params", "preset")
                self.fail(path, f"invalid parameters at f = {f:g} Hz: {e}")
        families = self.families(doc)
        acc = self.accuracy(doc)
        obs = self.observables(doc, acc)
        an = self.analysis(doc)
        return Study(name=name, source=self.source, seed=seed, preset=preset, overrides=overrides,
                     frequencies=freqs, families=families, accuracy=acc, observables=obs,
                     analysis=an, text=self.text)

    def params(self, doc: dict) -> tuple[str, dict[str, float]]:
        tbl = self.table(doc, ("params",), ("preset",) + PARAM_FIELDS)
        preset = tbl.get("preset", "klages2004")
        if preset not in PARAM_PRESETS:
            self.fail(("params", "preset"), f"unknown preset {preset!r}",
                      ", ".join(sorted(PARAM_PRESETS)))
        overrides = {}
        for k in PARAM_FIELDS:
            if k in tbl:
                v = tbl[k]
                if isinstance(v, bool) or not isinstance(v, int | float) or math.isnan(v):
                    self.fail(("params", k), f"must be a number, got {v!r}", _PARAM_ALLOWED[k])
                if math.isinf(v) and k != "R":
                    self.fail(("params", k), f"must be finite, got {v!r}", _PARAM_ALLOWED[k])
                overrides[k] = float(v)
        try:
            Params.preset(preset, f=1.0, **overrides)
        except ValueError as e:
            fld = re.search(r"Params\.(\w+)", str(e))
            key = fld.group(1) if fld and fld.group(1) in overrides else None
            self.fail(("params", key) if key else ("params",), str(e))
        return preset, overrides

    def frequencies(self, doc: dict) -> tuple[float, ...]:
        if "frequencies" not in doc:
            self.fail(("frequencies",), "missing",
                      "[frequencies] values = [...] or start/stop/step")
        raw = doc["frequencies"]
        allowed_f = "finite frequencies > 0 Hz, multiples of 0.001 Hz"
        if isinstance(raw, list):
            tbl, path = {"values": raw}, ("frequencies",)
        else:
            tbl = self.table(doc, ("frequencies",), ("values", "start", "stop", "step"))
            path = ("frequencies", "values")
        if "values" in tbl:
            if set(tbl) - {"values"}:
                self.fail(("frequencies",), "give either values or start/stop/step, not both")
            vals = tbl["values"]
            if not isinstance(vals, list) or not vals:
                self.fail(path, f"must be a non-empty list of numbers, got {vals!r}", allowed_f)
            mhz = [self._mhz(v, path, allowed_f) for v in vals]
        else:
            for k in ("start", "stop", "step"):
                if k not in tbl:
                    self.fail(("frequencies", k), "missing",
                              "[frequencies] values = [...] or start, stop, step (Hz)")
            start = self._mhz(tbl["start"], ("frequencies", "start"), allowed_f)
            stop = self._mhz(tbl["stop"], ("frequencies", "stop"), allowed_f)
            step = self._mhz(tbl["step"], ("frequencies", "step"), "a multiple of 0.001 Hz > 0")
            if stop < start:
                self.fail(("frequencies", "stop"), "stop < start", "stop >= start")
            if (stop - start) % step:
                self.fail(("frequencies", "step"), "stop - start is not a multiple of step",
                          "an inclusive grid start, start + step, ..., stop")
            mhz = list(range(start, stop + 1, step))
        if len(set(mhz)) != len(mhz):
            dup = sorted({m for m in mhz if mhz.count(m) > 1})
            self.fail(path, f"repeated frequencies {[m / 1000 for m in dup]} (after mHz rounding)",
                      "distinct frequencies")
        return tuple(m / 1000 for m in mhz)

    def _mhz(self, v: Any, path: tuple[str, ...], allowed: str) -> int:
        if isinstance(v, bool) or not isinstance(v, int | float):
            self.fail(path, f"must be numbers, got {_tname(v)} {v!r}", allowed)
        if not math.isfinite(v) or v <= 0:
            self.fail(path, f"{v!r} is out of range", allowed)
        m = round(v * 1000)
        # f enters the seed as an integer number of mHz, so it must be exactly representable.
        if abs(v * 1000 - m) > 1e-6 * max(1.0, abs(v)):
            self.fail(path, f"{v!r} is not a multiple of 0.001 Hz", allowed)
        return m

    def families(self, doc: dict) -> tuple[Family, ...]:
        if "families" not in doc:
            return (Family("rest", "rest"),)
        fams = doc["families"]
        if not isinstance(fams, dict) or not fams:
            self.fail(("families",), "must be one or more tables [families.NAME]",
                      "[families.rest] initial = \"rest\"")
        out = []
        for name, tbl in fams.items():
            path = ("families", name)
            if not _FAMILY_RE.match(name):
                self.fail(path, f"bad family name {name!r}", "a letter, then letters, digits, _ -")
            if not isinstance(tbl, dict):
                self.fail(path, f"must be a table, got {_tname(tbl)}",
                          "[families.NAME] initial = ...")
            for k in tbl:
                if k not in ("initial", "drop_height", "launch_speed", "description"):
                    self.fail(path + (k,), "unknown key",
                              "initial, drop_height, launch_speed, description")
            initial = tbl.get("initial", name if name in INITIAL_KINDS else None)
            if initial not in INITIAL_KINDS:
                self.fail(path + ("initial",), f"unknown initial condition {initial!r}"
                          if initial is not None else "missing", ", ".join(INITIAL_KINDS))
            drop = launch = None
            if "drop_height" in tbl:
                if initial != "dropped":
                    self.fail(path + ("drop_height",), "only for initial = \"dropped\"")
                drop = self.pair(tbl, path + ("drop_height",), "[lo, hi] mm with 0 <= lo <= hi")
            elif initial == "dropped":
                drop = (0.0, 2.0)
            if "launch_speed" in tbl:
                if initial != "launched":
                    self.fail(path + ("launch_speed",), "only for initial = \"launched\"")
                launch = self.pair(tbl, path + ("launch_speed",),
                                   "[lo, hi] mm/s with 0 <= lo <= hi")
            elif initial == "launched":
                launch = (0.0, 200.0)
            out.append(Family(name, initial, drop, launch))
        keys = [f.key for f in out]
        if len(set(keys)) != len(keys):  # crc32 collision: astronomically rare, but checked
            self.fail(("families",), "two family names hash to the same seed key; rename one")
        return tuple(out)

    def accuracy(self, doc: dict) -> Accuracy:
        raw = doc.get("accuracy", DEFAULT_ACCURACY)
        presets = ", ".join(ACCURACY_PRESETS)
        if isinstance(raw, str):
            tbl: dict = {"preset": raw}
            ppath = ("accuracy",)
        else:
            tbl = self.table(doc, ("accuracy",), ("preset",) + ACCURACY_KNOBS)
            ppath = ("accuracy", "preset")
        preset = tbl.get("preset", DEFAULT_ACCURACY)
        if preset not in ACCURACY_PRESETS:
            self.fail(ppath, f"unknown accuracy preset {preset!r}", presets)
        vals = dict(ACCURACY_PRESETS[preset])
        for k in ACCURACY_KNOBS:
            if k in tbl:
                integer = k in INT_KNOBS
                vals[k] = self.number(tbl, ("accuracy", k), integer=integer,
                                      check=lambda v: v > 0, allowed=f"{_ACC_ALLOWED[k]}")
        try:
            Numerics(**{k: vals[k] for k in NUMERICS_KNOBS})
        except ValueError as e:
            fld = re.search(r"Numerics\.(\w+)", str(e))
            self.fail(("accuracy", fld.group(1) if fld else "preset"), str(e))
        if vals["n_particles"] % vals["chunk_size"]:
            self.fail(("accuracy", "chunk_size"),
                      f"{vals['chunk_size']} does not divide n_particles = {vals['n_particles']}",
                      "a divisor of n_particles (every chunk holds the same number of particles)")
        n = vals["t_max"] / vals["sample_dt"]
        if abs(n - round(n)) > 1e-9 * n:
            self.fail(("accuracy", "sample_dt"),
                      f"t_max = {vals['t_max']:g} s is not a multiple of sample_dt = "
                      f"{vals['sample_dt']:g} s", "a sample_dt that divides t_max")
        if n > 10**6:
            self.fail(("accuracy", "sample_dt"), f"{round(n)} samples per trajectory is too many",
                      "t_max / sample_dt <= 1e6")
        if vals["n_resamples"] < 10:
            self.fail(("accuracy", "n_resamples"), f"{vals['n_resamples']} is too few", ">= 10")
        for k in INT_KNOBS:
            vals[k] = int(vals[k])
        for k in ACCURACY_KNOBS:
            if k not in INT_KNOBS:
                vals[k] = float(vals[k])
        return Accuracy(preset=preset, **vals)

    def observables(self, doc: dict, acc: Accuracy) -> Observables:
        if "observables" not in doc:
            self.fail(("observables",), "missing",
                      "[observables.positions] and/or [observables.collisions]")
        tbl = self.table(doc, ("observables",), ("positions", "collisions"))
        on = {}
        for k, opts in (("positions", ()), ("collisions", ("record", "record_from"))):
            v = tbl.get(k, False)
            if isinstance(v, bool):
                on[k] = (v, {})
            elif isinstance(v, dict):
                self.table(tbl, ("observables", k), opts)
                on[k] = (True, v)
            else:
                self.fail(("observables", k), f"must be a table or true/false, got {v!r}",
                          f"[observables.{k}]" + (f" with {', '.join(opts)}" if opts else ""))
        if not (on["positions"][0] or on["collisions"][0]):
            self.fail(("observables",), "nothing to record",
                      "[observables.positions] and/or [observables.collisions]")
        rec, rec_from = None, 0.0
        if on["collisions"][0]:
            c = on["collisions"][1]
            rec = self.number(c, ("observables", "collisions", "record"), 1000, integer=True,
                              check=lambda v: 1 <= v <= 10**7,
                              allowed="post-collision states per particle, 1 <= record <= 1e7")
            rec_from = self.number(c, ("observables", "collisions", "record_from"), 0.0,
                                   check=lambda v: 0 <= v < acc.t_max,
                                   allowed=f"s, 0 <= record_from < t_max = {acc.t_max:g}")
        return Observables(positions=on["positions"][0], collisions_record=rec,
                           collisions_from=float(rec_from))

    def analysis(self, doc: dict) -> Analysis:
        tbl = self.table(doc, ("analysis",), tuple(DEFAULT_ANALYSIS))
        d = dict(DEFAULT_ANALYSIS)
        limits = {
            "discard": (lambda v: 0 <= v <= 0.9, "fraction of t_max, 0 <= discard <= 0.9"),
            "fit_from": (lambda v: 0 < v < 1, "fraction of the analysed duration, 0 < v < 1"),
            "fit_to": (lambda v: 0 < v < 1, "fraction of the analysed duration, 0 < v < 1"),
            "eb_lag": (lambda v: 0 < v < 1, "fraction of the analysed duration, 0 < v < 1"),
            "eb_tolerance": (lambda v: v >= 1, "factor on the Brownian EB, >= 1"),
            "ci": (lambda v: 0.5 <= v < 1, "confidence level, 0.5 <= ci < 1"),
        }
        for k, (check, allowed) in limits.items():
            d[k] = self.number(tbl, ("analysis", k), d[k], check=check, allowed=allowed)
        if "ci_method" in tbl and tbl["ci_method"] not in CI_METHODS:
            self.fail(("analysis", "ci_method"), f"unknown method {tbl['ci_method']!r}",
                      ", ".join(CI_METHODS))
        d["ci_method"] = tbl.get("ci_method", d["ci_method"])
        if d["fit_from"] >= d["fit_to"]:
            self.fail(("analysis", "fit_to"), "fit_to <= fit_from", "fit_from < fit_to")
        return Analysis(**d)


_PARAM_ALLOWED = {
    "g": "g > 0 (mm/s²)", "A": "A >= 0 (mm)", "R": "R >= S/2 (mm), or inf",
    "S": "S > 0 (mm)", "alpha": "0 < alpha <= 1", "beta": "0 <= beta <= 1",
}
_ACC_ALLOWED = {
    "n_particles": "an integer > 0", "chunk_size": "an integer > 0 dividing n_particles",
    "t_max": "s, > 0", "sample_dt": "s, > 0, dividing t_max", "tol_t": "s, 0 < tol_t <= 1e-6",
    "v_stick": "mm/s, > 0", "max_step": "floor periods, 0 < max_step <= 1",
    "n_resamples": "an integer >= 10",
}


def _line_of(text: str, path: tuple[str, ...]) -> int | None:
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
            continue
        m = key_re.match(line)
        if m:
            key = tuple(p.strip().strip("\"'") for p in m.group(1).split("."))
            full = table + key
            if full == path:
                return i
            if best is None and full[: len(path)] == path:
                best = i  # the first key inside a table given by dotted keys
            if best is None and len(full) < len(path) and path[: len(full)] == full:
                best = i  # an inline table or array holding the key
    return best


def _tname(v: Any) -> str:
    return {bool: "boolean", int: "integer", float: "float", str: "string", list: "array",
            dict: "table"}.get(type(v), type(v).__name__)


def _drop_none(d: dict) -> dict:
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in d.items() if v is not None}


def _tuple_or_none(v):
    return None if v is None else tuple(float(x) for x in v)


def _json_default(o):
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(type(o))
