"""The keys of a workflow TOML, each declared once: type, units, range or choices, default and
a one-line doc, as fields of one frozen dataclass per TOML table (:func:`pipeline.workflow.schema.key`).

Size: the whole schema as data, one small dataclass per TOML table and the maps read off
them (parameter units, grid axes); split, the declarations of one file would be in two.

:mod:`pipeline.workflow.load` reads a file against these declarations (plus the rules that involve
several keys) into a Study; :func:`reference_markdown` writes them as the reference table in
pipeline/README.md, so the docs say exactly what is checked.

Adding a key is one declaration in the dataclass of its table, e.g. for the scenes to come
(their behaviour is each scene's own work; declare them ``omit_default=True`` so that stores
made before the key existed keep their fingerprint):

    # class Accuracy:
    target_ci: float | None = key(None, "relative 95 % CI half-width of D to reach",
                                  units="fraction of D", gt=0, lt=1, omit_default=True)
    # class ParamsTable (a non-float key is not a bbb.Params override):
    contact: str = key("stick", "contact model", choices=("stick", "slide", "coulomb"),
                       omit_default=True)
    # class ObservablesTable (a table switched on by its header or `= true`):
    jumps: JumpsTable | None = key(None, "displacement over every floor period")
    # class FrequenciesTable (an inline table: refine = { extrema = true, to = 0.1 }):
    refine: RefineTable | None = key(None, "add frequencies around extrema")
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from bbb.numerics import NUMERICS_RANGES, Numerics
from bbb.params import CONTACT_MODELS, FLOORS, GAMMA_MAX, PARAM_RANGES
from bbb.params import PRESETS as PARAM_PRESETS

from .accuracy import ACCURACY_PRESETS, DEFAULT_ACCURACY, NUMERICS_KNOBS
from .identity import family_key
from .observables.registry import scene_tables
from .schema import REQUIRED, declared, key, reference

__all__ = ["Family", "Accuracy", "RefineTable", "GridTable", "GridRefineTable", "GridRefine",
           "REFINE_QUANTITIES", "GRID_AXES", "INVALID_POLICIES",
           "Observables", "observables_table", "Analysis", "SECTIONS", "DEFAULT_ANALYSIS",
           "INITIAL_KINDS", "CI_METHODS", "PARAM_FIELDS", "PARAM_UNITS", "PARAM_LONG_NAMES",
           "reference_markdown",
           "readme_with_reference", "README"]

INITIAL_KINDS = ("rest", "dropped", "launched")
CI_METHODS = ("percentile", "bca", "basic")
F_MAX = PARAM_RANGES["f"].hi
ALLOWED_F = f"frequencies {PARAM_RANGES['f'].text('f')}, multiples of 0.001 Hz"


def _allowed(name: str) -> str:
    # a [params] key's range as bbb.Params states it (bbb.params.PARAM_RANGES): one source
    return PARAM_RANGES[name].text(name)


def _knob(name: str) -> dict[str, float]:
    # a bbb.Numerics knob's bounds (bbb.numerics.NUMERICS_RANGES), checked here as there
    rng = NUMERICS_RANGES[name]
    return {"gt" if rng.lo_open else "ge": rng.lo, "lt" if rng.hi_open else "le": rng.hi}


# -- the declarations, one dataclass per TOML table -------------------------------------------
@dataclass(frozen=True)
class StudyTable:
    name: str | None = key(None, "names the study and its store (runs/NAME.zarr)",
                           pattern=r"[A-Za-z0-9][A-Za-z0-9_.-]*",
                           allowed="letters, digits, '_', '-', '.' (it names the store)",
                           default_doc="the file name without .toml")
    description: str = key("", "free text")
    seed: int = key(2004, "root of every chunk's SeedSequence", ge=0, lt=2**63)


# bbb.Params checks its own ranges (R >= S/2 involves two keys, Γ three) and says what is
# allowed; the texts here are its texts (bbb.params.PARAM_RANGES), for the reference and for
# type errors.
@dataclass(frozen=True)
class ParamsTable:
    preset: str = key("klages2004", "named parameter set (bbb.params.PRESETS)",
                      choices=tuple(sorted(PARAM_PRESETS)))
    g: float | None = key(None, "gravitational acceleration", allowed=_allowed("g"),
                          default_doc="preset")
    A: float | None = key(None, "floor amplitude; y_f = -A sin(2 pi f t)",
                          allowed=_allowed("A") + f", and Γ ≤ {GAMMA_MAX:g}",
                          default_doc="preset")
    # not a bbb.Params field: the workflow turns it into A at each point's f (study.resolve_params)
    Gamma: float | None = key(None, "peak floor acceleration Γ = A (2 pi f)² / g at each "
                              "point's f, instead of A", ge=0, le=GAMMA_MAX,
                              allowed=f"0 ≤ Gamma ≤ {GAMMA_MAX:g} (in g), not with A",
                              omit_default=True, default_doc="–")
    R: float | None = key(None, "scatterer (arc) radius",
                          allowed=f"S/2 ≤ R ≤ {PARAM_RANGES['R'].hi:g} (mm), or inf",
                          finite=False, default_doc="preset")
    S: float | None = key(None, "distance between scatterer centres", allowed=_allowed("S"),
                          default_doc="preset")
    alpha: float | None = key(None, "normal restitution, Eq. (5)", allowed=_allowed("alpha"),
                              default_doc="preset")
    beta: float | None = key(None, "tangential restitution, Eq. (6)", allowed=_allowed("beta"),
                             default_doc="preset")
    # the conveyor (bbb.dynamics with a Frame, docs/physics.md "Transport"); omit_default and left out of
    # Params.as_dict at 0 and 90, so every scene without them keeps its fingerprint
    tilt: float | None = key(None, "inclination of the floor's plane (downhill towards -x)",
                             allowed=_allowed("tilt"), omit_default=True,
                             default_doc="0 (level)")
    throw: float | None = key(None, "angle of the vibration to the floor's plane",
                              allowed=_allowed("throw"), omit_default=True,
                              default_doc="90 (vertical, the paper's)")
    contact: str = key("stick", "sustained-contact model (docs/physics.md, Contact models)",
                       choices=CONTACT_MODELS)
    mu: float | None = key(None, "Coulomb friction coefficient", allowed=_allowed("mu"),
                           when=("contact", "coulomb"), default_doc="0")
    # the floor's shape (docs/physics.md, "Floors"); omit_default and left out of
    # Params.as_dict at their defaults, so every arc scene keeps its fingerprint
    floor: str = key("arc", "floor shape: the paper's arcs (R, S), flat (R = inf), a sine or a "
                     "sawtooth (depth, S; sawtooth also peak), level and stick only for sine and "
                     "sawtooth", choices=FLOORS, omit_default=True)
    depth: float | None = key(None, "top-to-valley depth of a sine or sawtooth floor (the "
                              "sine's amplitude is depth/2; S is its wavelength or period)",
                              allowed=_allowed("depth") + ", > 0 on a sine or sawtooth, else 0",
                              omit_default=True, default_doc="0")
    peak: float | None = key(None, "where a sawtooth's peak sits, as a fraction of S from its "
                             "left valley (0.5: symmetric teeth)", allowed=_allowed("peak"),
                             omit_default=True, default_doc="0.5")


INVALID_POLICIES = ("refuse", "skip")


@dataclass(frozen=True)
class GridTable:
    """The settings of ``[grid]``; its other keys are the axes (:data:`GRID_AXES`), read by
    pipeline.workflow.load."""

    invalid: str = key("refuse", "a point whose parameters bbb.Params refuses (e.g. slide on "
                       "near-vertical cusps): refuse the workflow, naming the point, or skip "
                       "the point", choices=INVALID_POLICIES)


REFINE_QUANTITIES = ("D", "v")


@dataclass(frozen=True)
class GridRefineTable:
    """The settings of ``[grid.refine]``; its other keys are resolutions, one per axis
    refined (``f = 0.5``, ``alpha = 0.05``), read by pipeline.workflow.grid."""

    extrema: bool = key(True, "split the gaps next to every significant extremum along a "
                        "refined axis (bbb.analysis.extrema)")
    jumps: bool = key(True, "split the gaps between neighbours whose values differ beyond "
                      "their CIs")
    quantity: str = key("D", "what is compared: D (all families pooled) or the drift v",
                        choices=REFINE_QUANTITIES)


@dataclass(frozen=True)
class GridRefine:
    """A map's refinement rule (``[grid.refine]``, pipeline.execute.grid_refine): the
    resolution of every refined axis, (axis, finest gap) in the workflow's order (f in Hz,
    another axis in its own unit), and the settings of :class:`GridRefineTable`."""

    to: tuple[tuple[str, float], ...]
    extrema: bool = True
    jumps: bool = True
    quantity: str = "D"


@dataclass(frozen=True)
class FrequenciesTable:
    values: tuple[float, ...] | None = key(None, "the frequencies, distinct after rounding to "
                                           "1 mHz (or `frequencies = [...]`)",
                                           gt=0, le=F_MAX, allowed=ALLOWED_F)
    start: float | None = key(None, "first frequency of an inclusive grid (instead of values)",
                              gt=0, le=F_MAX, allowed=ALLOWED_F)
    stop: float | None = key(None, "last frequency of the grid, >= start", gt=0, le=F_MAX,
                             allowed=ALLOWED_F)
    step: float | None = key(None, "grid spacing; stop - start must be a multiple of it", gt=0,
                             allowed="a multiple of 0.001 Hz > 0")
    refine: RefineTable | None = key(None, "after the grid, add frequencies around the "
                                     "significant extrema of D(f) (pipeline/execute/adaptive.py)",
                                     omit_default=True)


@dataclass(frozen=True)
class RefineTable:
    """Adaptive frequency refinement: ``refine = { extrema = true, to = 0.1 }``."""

    to: float = key(REQUIRED, "until its neighbours are at most this far from each extremum",
                    units="Hz", ge=0.002, note="(new frequencies sit on the 1 mHz grid)")
    extrema: bool = key(True, "bracket every significant extremum of D(f) (bbb.analysis.extrema)")
    jumps: bool = key(False, "also split gaps wider than `to` between neighbours whose D "
                      "differ beyond their CIs", omit_default=True)


@dataclass(frozen=True)
class Family:
    """One initial-condition family: a name and the ``bbb.simulate`` options it needs."""

    name: str
    initial: str = key(REQUIRED, "initial condition", choices=INITIAL_KINDS,
                       default_doc="NAME, if it is one of these")
    drop_height: tuple[float, float] | None = key(
        (0.0, 2.0), "released at rest this high above the surface", units="mm", ge=0,
        when=("initial", "dropped"), default_doc='[0, 2] for initial = "dropped"')
    launch_speed: tuple[float, float] | None = key(
        (0.0, 200.0), "launched upward at this speed relative to the floor", units="mm/s", ge=0,
        when=("initial", "launched"), default_doc='[0, 200] for initial = "launched"')
    # None: the floor decides (Study.pairing); omit_default keeps every older fingerprint
    mirror: bool | None = key(None, "mirror pairs: on a mirror-symmetric floor each particle's "
                              "image counts in the estimates (the drift v = 0 exactly, nothing "
                              "more simulated); elsewhere half of each chunk are the mirror "
                              "partners of the other half (antithetic drift estimates)",
                              omit_default=True, default_doc="true on a level floor vibrated "
                              "vertically (tilt = 0, throw = 90), else false")
    lattice: tuple[float, float] | None = key(
        None, "a grid of initial conditions instead of random draws: [n_phase, n_value] "
        "floor phases × drop heights (dropped) or launch speeds (launched), each cell's "
        "centre, n_phase·n_value = n_particles (bbb.ensemble.lattice_state)", units="cells",
        ge=1, omit_default=True, default_doc="none: random draws")
    offset: float | None = key(None, "the lattice's offset from the arc's centre", units="mm",
                               omit_default=True, default_doc="none (0 with a lattice)")
    description: str = key("", "free text", identity=False, omit_default=True)

    @property
    def key(self) -> int:
        """A stable 32-bit number for the seed: depends on the name only, not on its position."""
        return family_key(self.name)

    def lattice_problem(self, n_particles: int) -> tuple[str, str, str] | None:
        """(key, problem, allowed) when a lattice does not fit: cells not whole numbers, not
        one particle per cell, not dropped or launched, an offset without a lattice."""
        if self.lattice is None:
            return None if self.offset is None else (
                "offset", "is a lattice's offset", "offset only with lattice = [n_phase, n_value]")
        a, b = self.lattice
        if a != int(a) or b != int(b):
            return "lattice", f"{list(self.lattice)} are not whole numbers", "integers ≥ 1"
        if int(a) * int(b) != n_particles:
            return ("lattice", f"{int(a)} × {int(b)} cells for n_particles = {n_particles}",
                    "n_phase · n_value = [accuracy] n_particles")
        if self.initial not in ("dropped", "launched"):
            return "lattice", f"a lattice of {self.initial!r} states", 'initial = "dropped" or "launched"'
        return None

    def simulate_kwargs(self) -> dict[str, Any]:
        kw: dict[str, Any] = {"initial": self.initial}
        if self.drop_height is not None:
            kw["drop_height"] = self.drop_height
        if self.launch_speed is not None:
            kw["launch_speed"] = self.launch_speed
        return kw


@dataclass(frozen=True)
class Accuracy:
    """Every knob that trades time for accuracy; the presets are in pipeline/workflow/accuracy.py."""

    preset: str = key(DEFAULT_ACCURACY, "named preset the other knobs default to (or "
                      '`accuracy = "NAME"`)', choices=tuple(ACCURACY_PRESETS))
    n_particles: int = key(None, "particles per (frequency, family)", gt=0, default_doc="preset")
    chunk_size: int = key(None, "particles per Dask task and per store chunk", gt=0,
                          note="dividing n_particles", default_doc="preset")
    t_max: float = key(None, "simulated time per particle", units="s", gt=0, default_doc="preset")
    sample_dt: float = key(None, "spacing of the position samples", units="s", gt=0,
                           note="dividing t_max, at most 1e6 samples", default_doc="preset")
    tol_t: float = key(None, "root-finding tolerance on the collision time", units="s",
                       default_doc="preset", **_knob("tol_t"))
    v_stick: float = key(None, "sticking threshold of creeping cascades", units="mm/s",
                         default_doc="preset", **_knob("v_stick"))
    max_step: float = key(None, "first bracketing step of the collision search",
                          units="floor periods", default_doc="preset", **_knob("max_step"))
    n_resamples: int = key(None, "bootstrap resamples per diffusion coefficient", ge=10,
                           allowed=">= 10 (an integer)", default_doc="preset")
    # Target-driven sampling (pipeline/execute/adaptive.py); off (None) = a fixed n_particles.
    target_ci: float | None = key(None, "CI half-width of D to reach per (frequency, family), "
                                  "relative to D; chunks are added in waves until it is met",
                                  units="fraction of D", gt=0, lt=1, omit_default=True,
                                  default_doc="off: n_particles everywhere")
    d_resolved: float | None = key(None, "with target_ci: a CI half-width (absolute) at which "
                                   "a D near 0 counts as resolved", units="mm²/s", gt=0,
                                   omit_default=True, default_doc="off")
    max_particles: int | None = key(None, "with target_ci: at most this many particles per "
                                    "(frequency, family); sizes the store (n_particles = it)",
                                    gt=0, omit_default=True, default_doc="n_particles")

    @property
    def n_chunks(self) -> int:
        """Chunks per (frequency, family) in the store (with target_ci: the cap)."""
        return self.n_particles // self.chunk_size

    @property
    def adaptive(self) -> bool:
        """Whether the ensemble size is chosen per (frequency, family) by target_ci."""
        return self.target_ci is not None

    def numerics(self) -> Numerics:
        return Numerics(**{k: getattr(self, k) for k in NUMERICS_KNOBS})


@dataclass(frozen=True)
class PositionsTable:
    """x at 0, sample_dt, ..., t_max: what the MSD needs.  No keys."""


@dataclass(frozen=True)
class CollisionsTable:
    record: int = key(1000, "post-collision states kept per particle",
                      units="post-collision states per particle", ge=1, le=1e7)
    record_from: float = key(0.0, "record collisions from this time on", units="s", ge=0,
                             lt="t_max")
    x_jumps: int = key(0, "also store x and t differences between the first x_jumps + 1 "
                       "collisions from record_from (the per-collision Green–Kubo expansion); "
                       "0: off", units="jumps per particle", ge=0, le=1e6, omit_default=True)


@dataclass(frozen=True)
class ContactTable:
    """Per particle, the time held at rest on the floor and the time sliding on an arc (s,
    bbb.record.CONTACT_TIME_NAMES).  No keys."""


@dataclass(frozen=True)
class JumpsTable:
    """Δx over every floor period 0 … floor(t_max f) (the Green–Kubo expansion).  No keys."""


@dataclass(frozen=True)
class LyapunovTable:
    particles: int = key(REQUIRED, "particles per (frequency, family) whose largest Lyapunov "
                         "exponent is measured: the first ones of the ensemble",
                         gt=0, note="at most n_particles")
    d0: float = key(1e-8, "separation of the companion trajectory after each renormalisation",
                    units="g/ω² and g/ω", gt=0, lt=1e-3)
    discard: float = key(0.1, "periods dropped at the start as a transient",
                         units="fraction of t_max", ge=0, lt=0.9)


@dataclass(frozen=True)
class ObservablesTable:
    positions: PositionsTable | None = key(None, "x at the sample times 0, sample_dt, ..., t_max "
                                       "(an empty [observables.positions] switches it on)")
    collisions: CollisionsTable | None = key(None, "post-collision states (t, x, y, vx, vy, phase)")
    contact: ContactTable | None = key(None, "per-particle time held and time sliding, s "
                                       "(an empty [observables.contact] switches it on)")
    jumps: JumpsTable | None = key(None, "x(n+1)/f − x(n/f) for every floor period n "
                                   "(an empty [observables.jumps] switches it on)")
    lyapunov: LyapunovTable | None = key(None, "per-particle largest Lyapunov exponent "
                                         "(bbb.analysis.lyapunov, two trajectories)")


def observables_table() -> type:
    """The [observables] table: the engine's (ObservablesTable) and every plug-in's own
    ([observables.NAME], :func:`pipeline.workflow.observables.registry.scene_tables`)."""
    more = scene_tables()
    if not more:
        return ObservablesTable
    return dataclasses.make_dataclass(
        "ObservablesTable", [(o.name, o.scene | None, key(None, o.doc)) for o in more],
        bases=(ObservablesTable,), frozen=True)


@dataclass(frozen=True)
class Observables:
    """What is recorded: positions at the sample times and/or post-collision states.

    collisions_record -- post-collision states kept per particle (None: collisions off)
    collisions_from   -- record collisions at t >= this, s
    """

    positions: bool
    collisions_record: int | None = None
    collisions_from: float = 0.0
    # declared omit_default: a store made before these existed keeps its fingerprint
    contact: bool = key(False, "time held and sliding per particle", omit_default=True)
    jumps: bool = key(False, "Δx over every floor period", omit_default=True)
    lyapunov_particles: int | None = key(None, "particles with a Lyapunov exponent",
                                         omit_default=True)
    lyapunov_d0: float = key(1e-8, "companion separation", omit_default=True)
    lyapunov_discard: float = key(0.1, "transient of λ, fraction of t_max", omit_default=True)
    collisions_x_jumps: int = key(0, "per-collision x jumps per particle", omit_default=True)
    # the plug-ins' own tables (pipeline.workflow.observables.registry.scene_tables), given
    more: tuple = key((), "((name, ((key, value), ...)), ...) of the plug-ins' own tables",
                      omit_default=True)

    def __post_init__(self):
        # as stored (JSON lists) or as read: the same tuples, so that equal scenes compare equal
        object.__setattr__(self, "more", tuple((str(n), tuple((str(k), v) for k, v in kv))
                                               for n, kv in self.more))

    def more_of(self, name: str) -> tuple | None:
        """The keys of the plug-in table ``name`` as the scene gave them (None: not selected)."""
        return next((kv for n, kv in self.more if n == name), None)

    @property
    def lyapunov(self) -> bool:
        return self.lyapunov_particles is not None

    @property
    def collisions(self) -> bool:
        return self.collisions_record is not None


@dataclass(frozen=True)
class Analysis:
    """How ``bbb reduce`` analyses the positions (fractions, so that they hold at every
    accuracy); passed to bbb.analysis.stats."""

    discard: float = key(0.10, "dropped at the start of the run as a transient",
                         units="fraction of t_max", ge=0, le=0.9)
    fit_from: float = key(0.05, "first lag of the MSD fit 2 D lag + c",
                          units="fraction of T = (1 - discard) t_max", gt=0, lt=1)
    fit_to: float = key(0.25, "last lag of the MSD fit, > fit_from",
                        units="fraction of T", gt=0, lt=1)
    eb_lag: float = key(0.05, "lag of the ergodicity-breaking parameter EB",
                        units="fraction of T", gt=0, lt=1)
    eb_tolerance: float = key(2.0, "factor on the Brownian EB below which EB passes",
                              units="factor on the Brownian EB", ge=1)
    ci: float = key(0.95, "bootstrap confidence level", units="confidence level", ge=0.5, lt=1)
    ci_method: str = key("percentile", "bootstrap interval", choices=CI_METHODS)

    def duration(self, t_max: float) -> float:
        """The analysed duration T = (1 - discard) t_max, s."""
        return (1.0 - self.discard) * t_max


DEFAULT_ANALYSIS: dict[str, Any] = {k.name: k.default for k in declared(Analysis)}
#: the bbb.Params overrides a [params] table may hold (Gamma is not one: it becomes A)
PARAM_FIELDS = tuple(k.name for k in declared(ParamsTable) if k.kind == "float" and k.name != "Gamma")
#: the keys a [grid] axis may sweep: every [params] key but the preset, in their declared order
GRID_AXES = tuple(k.name for k in declared(ParamsTable) if k.name != "preset")
#: the unit of every [params] key (UDUNITS/CF: "1" dimensionless, "" not a quantity): the
#: store's axis coordinates and the tables' axis columns (pipeline.tables.units) read it here
PARAM_UNITS: dict[str, str] = {"g": "mm/s^2", "A": "mm", "Gamma": "1", "R": "mm", "S": "mm",
                               "alpha": "1", "beta": "1", "tilt": "degree", "throw": "degree",
                               "contact": "", "mu": "1", "floor": "", "depth": "mm", "peak": "1"}
#: the long name of every [params] key: its one-line doc in the declaration
PARAM_LONG_NAMES: dict[str, str] = {k.name: k.doc for k in declared(ParamsTable)
                                    if k.name != "preset"}
# The tables of a workflow, as in the reference: (header, declarations, note).
SECTIONS: list[tuple[str, type, str]] = [
    ("[study]", StudyTable, ""),
    ("[params]", ParamsTable, "bbb.Params, mm and s; `f` comes from [frequencies]"),
    ("[frequencies]", FrequenciesTable, "Hz, multiples of 1 mHz: `values`, or `start, stop, "
     "step`; required"),
    ("[grid]", GridTable, "sweep axes: `NAME = [v1, v2, ...]` for any [params] key but preset "
     "(" + ", ".join(GRID_AXES) + "), distinct values of its type, not also in [params]; "
     "the points are every combination of the axes, in their order, with [frequencies] "
     "innermost"),
    ("[grid.refine]", GridRefineTable, "refinement of a map in every direction: a "
     "resolution per refined axis, `f = 0.5` (Hz, on the 1 mHz grid), `alpha = 0.05` (any "
     "numeric grid axis, in its unit); gaps wider than that are split while they border a "
     "significant extremum or jump"),
    ("[frequencies.refine]", RefineTable, "an inline table, e.g. `refine = { extrema = true, "
     "to = 0.1 }`"),
    ("[families.NAME]", Family, "NAME: a letter, then letters, digits, _ -; default: one "
     "family `rest`"),
    ("[accuracy]", Accuracy, '`accuracy = "NAME"` for a preset as it is'),
    ("[observables]", ObservablesTable, "at least one; required"),
    ("[observables.collisions]", CollisionsTable, ""),
    ("[observables.lyapunov]", LyapunovTable, "e.g. `[observables.lyapunov] particles = 64`"),
    ("[analysis]", Analysis, "settings of `bbb reduce`, not of the stored data"),
]
TABLES = ("study", "params", "frequencies", "grid", "families", "accuracy", "observables", "analysis")


# -- the reference in pipeline/README.md ------------------------------------------------------
README = Path(__file__).resolve().parents[1] / "README.md"  # pipeline/README.md
MARKERS = ("<!-- workflow-reference: generated by `python -m pipeline.workflow --reference "
           "--write`; do not edit -->", "<!-- end of workflow-reference -->")


def reference_markdown() -> str:
    """The workflow reference: every declared key with its type, range, default and doc (the
    observables' own tables after the engine's)."""
    return reference(SECTIONS + [(f"[observables.{o.name}]", o.scene, o.doc)
                                 for o in scene_tables()])


def readme_with_reference(readme: str) -> str:
    """``readme`` with the text between the markers replaced by :func:`reference_markdown`."""
    start, end = readme.index(MARKERS[0]) + len(MARKERS[0]), readme.index(MARKERS[1])
    return readme[:start] + "\n" + reference_markdown() + readme[end:]


