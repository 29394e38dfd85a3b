"""Claims as data: a declared record per claim, judged by one rule that uses the measured CI.

This module knows no paper.  A study declares its claims as a list of :class:`Claim` records
(the paper's sentence, the quantity, where it is measured, the tolerance band and why);
:func:`evaluate` measures each with the function the claim holds (generic ones in
:mod:`pipeline.claims.measures`, a study's own beside its claims) and judges the measured
:class:`Quantity` -- a value with its CI -- against the claim's :class:`Band`.

The verdict rule (:func:`judge`), fixed before looking at any claim it turns:

=====================  ===================================================================
agrees                 the whole CI lies inside the tolerance band
agrees within the CI   the value lies inside the band, but its CI reaches beyond an edge:
                       the verdict would flip inside the CI
inconclusive           the value lies outside the band, but its CI reaches into it
disagrees              the whole CI lies outside the band (or the feature is not found)
partly                 several parts: some agree and some do not, or only a curve other
                       than the claim's main one agrees
not measured           the table the claim needs is missing, or (a rule stated over all
                       its parts, :attr:`Claim.all_parts`) one of its parts is
=====================  ===================================================================

Two further kinds of row are never 'agrees' or 'disagrees':

=====================  ===================================================================
consistent /           a claim of kind "consistency" (:attr:`Claim.kind`): a result compared
inconsistent           with itself (shared seeds or chunks) -- the rule above, read as a
                       check of the pipeline, not a test of the paper
by construction        a claim that holds by the design of the ensemble (a measure returns
                       it, its note saying why)
=====================  ===================================================================

A quantity without a CI (lo = hi = value) is judged by its value alone, and the report says
"no CI".  Several parts are combined by :func:`combine`.

Each claim is registered (:mod:`.registry`): an ``id``, its ``scope`` and the commit it was
``registered`` at; once judged on committed data its rule and scope are frozen, and a changed
rule or a widened scope is a new id that ``supersedes`` the old one.  ``cases`` names the
provider of its synthetic cases (:class:`Case`), with which the registry's test turns it each
way.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

__all__ = ["VERDICTS", "KINDS", "CONSISTENT", "INCONSISTENT", "BY_CONSTRUCTION", "Quantity",
           "Band", "Part", "Measured", "Claim", "Case", "Row", "Measure", "measure", "judge",
           "combine", "evaluate", "POSITIVE"]

CONSISTENT, INCONSISTENT, BY_CONSTRUCTION = "consistent", "inconsistent", "by construction"
VERDICTS = ("agrees", "agrees within the CI", "inconclusive", "partly", "disagrees",
            "not measured", CONSISTENT, INCONSISTENT, BY_CONSTRUCTION)
#: what a claim is: a measurement of the paper's claim, or a check of a result against itself
KINDS = ("measurement", "consistency")
#: the verdicts that say a claim holds (alone, or with its CI reaching beyond the band)
POSITIVE = ("agrees", "agrees within the CI")
#: a measure: (claim, ctx) -> Measured (ctx: the tables, stores, curves, ... it reads)
Measure = Callable[["Claim", Mapping], "Measured"]


@dataclass(frozen=True)
class Quantity:
    """A measured number with its CI (lo ≤ value ≤ hi, same unit), and how the CI was got."""

    value: float
    lo: float = math.nan
    hi: float = math.nan
    unit: str = ""
    ci: str = ""  # where the CI comes from, e.g. "bootstrap over particles"

    @property
    def has_ci(self) -> bool:
        return not (math.isnan(self.lo) or math.isnan(self.hi))

    def text(self, fmt: str = ".4g") -> str:
        u = f" {self.unit}" if self.unit else ""
        if not self.has_ci:
            return f"{self.value:{fmt}}{u} (no CI)"
        return f"{self.value:{fmt}}{u} [{self.lo:{fmt}}, {self.hi:{fmt}}]"


@dataclass(frozen=True)
class Band:
    """The tolerance band a quantity must lie in, and why (the paper's own resolution)."""

    lo: float
    hi: float
    why: str
    unit: str = ""

    @classmethod
    def around(cls, target: float, tol: float, why: str, unit: str = "") -> Band:
        return cls(target - tol, target + tol, why, unit)

    def text(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        if math.isinf(self.hi) and math.isinf(self.lo):
            return ""  # the parts carry their own bands; only the why is shown
        if math.isinf(self.hi):
            return f"≥ {self.lo:g}{u}"
        if math.isinf(self.lo):
            return f"≤ {self.hi:g}{u}"
        mid, half = 0.5 * (self.lo + self.hi), 0.5 * (self.hi - self.lo)
        return f"{mid:g} ± {half:g}{u}"


@dataclass(frozen=True)
class Part:
    """One measured part of a claim: a curve's or a family's quantity.

    main  -- the claim's own curve/family (others can only make the verdict 'partly')
    band  -- overrides the claim's band (claims with several targets)
    found -- False: the feature (an extremum, a peak) is not there: 'disagrees'
    """

    label: str
    q: Quantity
    text: str = ""
    main: bool = True
    band: Band | None = None
    found: bool = True


@dataclass
class Measured:
    """What a measure returns: the parts to judge, or ``missing`` (why not measured)."""

    parts: list[Part] = field(default_factory=list)
    text: str = ""  # extra measured text after the parts
    note: str = ""
    missing: str = ""
    verdict: str | None = None  # a measure that decides itself (its rule stated in ``note``)


@dataclass(frozen=True)
class Claim:
    """One claim of a paper, declared.

    text     -- the paper's sentence (short form)
    measure  -- the function that measures it: measure(claim, ctx) -> Measured, named by the
                :func:`measure` decorator (its name is the claim's :attr:`quantity`)
    scene    -- the table it is measured in ("figure2", "locking", ...)
    band     -- tolerance band and why (None: the measure decides)
    family   -- initial-condition family of the claim's main curve
    f0, window  -- where: frequency (Hz) and the half-width searched around it
    options  -- measure-specific settings (e.g. {"kind": "max"}, {"column": "k_max"})
    note     -- a fixed note shown whatever the verdict
    explain  -- optional callable(ctx) -> str: an explanation added when the verdict is not
                'agrees'
    id       -- its registered id ("5", "M2b", "T3"); a changed rule or scope is a new id
    scope    -- what it is judged on: {"scenes": ..., "lines": ..., "families": ...,
                "frequencies": ...} (plain data, part of the frozen rule)
    registered -- "<date> <commit>" of the commit that registered it
    supersedes -- the id of the claim whose rule or scope this one changes ('' for none)
    kind     -- "measurement", or "consistency" (a result compared with itself: its verdict
                is 'consistent' / 'inconsistent', never 'agrees' / 'disagrees')
    all_parts -- the rule is stated over all its parts (both sides, every line): a part not
                measured makes the claim 'not measured'
    cases    -- its synthetic-case provider: () -> [Case, ...] (the registry's test)
    """

    text: str
    measure: Measure
    scene: str = ""
    band: Band | None = None
    family: str = "rest"
    f0: float = math.nan
    window: float = 0.0
    options: Mapping = field(default_factory=dict)
    note: str = ""
    explain: Callable[[Mapping], str] | None = None
    id: str = ""
    scope: Mapping = field(default_factory=dict)
    registered: str = ""
    supersedes: str = ""
    kind: str = "measurement"
    all_parts: bool = False
    cases: Callable[[], Sequence[Case]] | None = None

    @property
    def quantity(self) -> str:
        """The name of the claim's measure ("extremum", "klages2004.loops", ...)."""
        return getattr(self.measure, "measure_name", self.measure.__name__)


@dataclass(frozen=True)
class Case:
    """A synthetic input of a claim with the verdict it must give.

    ctx      -- what the claim's measure reads (as :func:`evaluate` would pass it)
    verdict  -- the verdict the rule must give on it
    perturbs -- the name of the case this one perturbs: its verdict must differ from that
                case's (e.g. an absurd threshold that must turn a claim to 'disagrees')
    options  -- settings merged into the claim's options for this case only (a perturbed
                threshold)
    """

    name: str
    ctx: Mapping
    verdict: str
    perturbs: str = ""
    options: Mapping = field(default_factory=dict)


@dataclass(frozen=True)
class Row:
    """One claim in the report: what the paper says, what we measured, the verdict, the
    tolerance it was judged by (and why), a plain note; its registered id and registration."""

    claim: str
    measured: str
    verdict: str
    note: str = ""
    judged_by: str = ""
    id: str = ""


def measure(name: str):
    """Decorator: name a measure (``fn.measure_name``, shown as its claims' quantity).  Nothing
    is registered: a claim holds its measure function."""
    def deco(fn):
        fn.measure_name = name
        return fn
    return deco


def judge(q: Quantity, band: Band) -> str:
    """The verdict of one quantity against one band (rule in the module docstring)."""
    v = q.value
    if math.isnan(v):
        return "not measured"
    lo, hi = (q.lo, q.hi) if q.has_ci else (v, v)
    if band.lo <= lo and hi <= band.hi:
        return "agrees"
    if hi < band.lo or lo > band.hi:
        return "disagrees"
    return "agrees within the CI" if band.lo <= v <= band.hi else "inconclusive"


def combine(verdicts: Sequence[str]) -> str:
    """One verdict from several parts: all agree -> agrees; all positive, some only within
    the CI -> agrees within the CI; none positive and all disagree -> disagrees; none
    disagrees but some are inconclusive -> inconclusive; any other mix -> partly."""
    vs = [v for v in verdicts if v != "not measured"]
    if not vs:
        return "not measured"
    if all(v == "agrees" for v in vs):
        return "agrees"
    if all(v in POSITIVE for v in vs):
        return "agrees within the CI"
    if all(v == "disagrees" for v in vs):
        return "disagrees"
    if not any(v == "disagrees" for v in vs) and not any(v == "partly" for v in vs):
        return "inconclusive"
    return "partly"


def _margin(q: Quantity, band: Band) -> str:
    """How the CI sits against the band edge nearest the value, for the note."""
    if not q.has_ci:
        return ""
    edge = min((e for e in (band.lo, band.hi) if math.isfinite(e)),
               key=lambda e: abs(e - q.value), default=math.nan)
    if math.isnan(edge):
        return ""
    return (f"value {q.value:.4g} is {abs(q.value - edge):.3g} from the band edge {edge:g}, "
            f"inside its CI [{q.lo:.4g}, {q.hi:.4g}]")


def evaluate_claim(claim: Claim, ctx: Mapping) -> Row:
    """Measure one claim and judge it."""
    if not callable(claim.measure):
        raise TypeError(f"claim {claim.text!r}: its measure {claim.measure!r} is not a function "
                        "measure(claim, ctx) -> Measured")
    m = claim.measure(claim, ctx)
    band = claim.band
    judged_by = ("" if band is None else f"{band.text()}: {band.why}" if band.text()
                 else band.why)
    text = _registered_text(claim)
    if claim.kind == "consistency":
        judged_by = ("consistency check (a result compared with itself), not a test of the "
                     "claim: " + judged_by)
    if m.missing:
        return Row(text, m.missing, "not measured", claim.note, judged_by, claim.id)
    texts, main_v, other_v, flips = [], [], [], []
    for p in m.parts:
        b = p.band or band
        if not p.found:
            v = "disagrees"
        elif b is None:
            v = "not measured"
        else:
            v = judge(p.q, b)
        if v in ("agrees within the CI", "inconclusive") and b is not None:
            flips.append(f"{p.label}: {_margin(p.q, b)}")
        texts.append(f"{p.label}: {p.text or p.q.text()}" + (f" → {v}" if len(m.parts) > 1 else ""))
        (main_v if p.main else other_v).append(v)
    if m.verdict is not None:
        verdict = m.verdict
    else:
        verdict = combine(main_v) if main_v else "disagrees"
        if verdict not in POSITIVE and any(v in POSITIVE for v in other_v):
            verdict = "partly"
        if claim.all_parts and "not measured" in main_v + other_v:
            verdict = "not measured"
    if claim.kind == "consistency" and verdict != "not measured":
        verdict = CONSISTENT if verdict in POSITIVE else INCONSISTENT
    notes = [claim.note, m.note]
    if flips:
        notes.append("The verdict flips inside the CI: " + "; ".join(flips) + ".")
    if verdict != "agrees" and claim.explain is not None:
        notes.append(claim.explain(ctx))
    measured = "; ".join(t for t in texts + [m.text] if t)
    return Row(text, measured, verdict, " ".join(n for n in notes if n).strip(), judged_by,
               claim.id)


def _registered_text(claim: Claim) -> str:
    """The claim's text with its registration, and the id it supersedes."""
    if not claim.registered:
        return claim.text
    after = f"; supersedes {claim.supersedes}" if claim.supersedes else ""
    return f"{claim.text} (registered {claim.registered}{after})"


def evaluate(claims: Sequence[Claim], ctx: Mapping) -> list[Row]:
    """One row per claim, in order."""
    return [evaluate_claim(c, ctx) for c in claims]
