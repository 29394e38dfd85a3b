"""Registered claims: each claim's rule and scope as canonical text, its hash, and the frozen
list that holds every judged claim to the hash it was judged under.

A claim (:class:`~.record.Claim`) is registered by its ``id`` and the commit it was added at
(``registered``).  Once it has been judged on committed data its entry is *frozen*: the hash
of its canonical rule and scope (:func:`rule_hash`) is written to the study's frozen list (a
JSON file {id: hash} beside its claims) and a test holds the record to it.  A changed rule or a
widened scope is then a new id (T3 → T3b) that ``supersedes`` the old one; the old one stays,
is still judged, and is shown beside the new one.

The canonical text (:func:`canonical`) holds what decides the verdict: the claim's text, its
measure's name, kind, scene, family, f0, window, options (a callable by its qualified name),
band (edges, unit, why), scope, whether the rule is over all parts, and the id it supersedes.
It leaves out what only explains (note, explain) and where it comes from (registered, cases).
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import replace
from pathlib import Path

from .claim import Claim, evaluate_claim

__all__ = ["canonical", "rule_hash", "read_frozen", "frozen_mismatches", "id_problems",
           "case_problems"]


def _plain(x):
    """A JSON-able, order-stable form of a rule's data (floats by repr, callables by name)."""
    if isinstance(x, Mapping):
        return {str(k): _plain(v) for k, v in sorted(x.items(), key=lambda kv: str(kv[0]))}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if isinstance(x, float):
        return repr(x) if not math.isnan(x) else "nan"
    if callable(x):
        return f"{getattr(x, '__module__', '')}.{getattr(x, '__qualname__', repr(x))}"
    return x


def canonical(claim: Claim) -> str:
    """The claim's rule and scope as one canonical JSON text (module docstring)."""
    b = claim.band
    return json.dumps(_plain({
        "id": claim.id, "text": claim.text, "measure": claim.quantity, "kind": claim.kind,
        "scene": claim.scene, "family": claim.family, "f0": claim.f0, "window": claim.window,
        "options": dict(claim.options), "scope": dict(claim.scope),
        "all_parts": claim.all_parts, "supersedes": claim.supersedes,
        "band": None if b is None else {"lo": b.lo, "hi": b.hi, "why": b.why, "unit": b.unit},
    }), ensure_ascii=False, sort_keys=True)


def rule_hash(claim: Claim) -> str:
    """sha256 (hex) of :func:`canonical`."""
    return hashlib.sha256(canonical(claim).encode("utf-8")).hexdigest()


def read_frozen(path: str | Path) -> dict[str, str]:
    """The frozen list {id: hash} of a study (an absent file: none frozen)."""
    p = Path(path)
    return json.loads(p.read_text(encoding="utf-8"))["frozen"] if p.is_file() else {}


def frozen_mismatches(claims: Iterable[Claim], frozen: Mapping[str, str]) -> list[str]:
    """What breaks the frozen list: a frozen id whose record's hash differs (its rule or scope
    changed: register a new id instead), or a frozen id no record has."""
    by_id = {c.id: c for c in claims}
    out = []
    for cid, h in frozen.items():
        if cid not in by_id:
            out.append(f"{cid}: frozen, but no claim has this id (a judged claim stays)")
        elif rule_hash(by_id[cid]) != h:
            out.append(f"{cid}: its rule or scope changed after it was judged (hash "
                       f"{rule_hash(by_id[cid])[:12]} ≠ frozen {h[:12]}); give the new rule a "
                       "new id that supersedes it")
    return out


def id_problems(claims: Sequence[Claim]) -> list[str]:
    """Registration errors: a claim without an id or a registration, a repeated id, or a
    ``supersedes`` naming no claim."""
    ids = [c.id for c in claims]
    out = [f"{c.text[:60]!r}: no id" for c in claims if not c.id]
    out += [f"{c.id}: not registered (no commit)" for c in claims if c.id and not c.registered]
    out += [f"{i}: id used {ids.count(i)} times" for i in sorted(set(ids)) if ids.count(i) > 1]
    out += [f"{c.id}: supersedes {c.supersedes}, which no claim is" for c in claims
            if c.supersedes and c.supersedes not in ids]
    return out


def case_problems(claim: Claim) -> list[str]:
    """What the claim's synthetic cases (its ``cases`` provider) fail to show: none at all;
    fewer than two different verdicts other than 'not measured' (it must turn each way); no
    case that perturbs another and flips its verdict; a case whose verdict is not the one the
    rule gives."""
    if claim.cases is None:
        return [f"{claim.id}: no synthetic-case provider"]
    cases = list(claim.cases())
    out = []
    got = {}
    for c in cases:
        cl = replace(claim, options={**claim.options, **c.options}) if c.options else claim
        got[c.name] = evaluate_claim(cl, c.ctx).verdict
        if got[c.name] != c.verdict:
            out.append(f"{claim.id}, case {c.name!r}: {got[c.name]!r}, expected {c.verdict!r}")
    if len({c.verdict for c in cases} - {"not measured"}) < 2:
        out.append(f"{claim.id}: its cases do not turn it each way (verdicts "
                   f"{sorted({c.verdict for c in cases})})")
    by_name = {c.name: c for c in cases}
    flips = [c for c in cases if c.perturbs in by_name and c.verdict != by_name[c.perturbs].verdict]
    if not flips:
        out.append(f"{claim.id}: no perturbation that flips its verdict")
    out += [f"{claim.id}, case {c.name!r}: perturbs {c.perturbs!r}, which is not a case"
            for c in cases if c.perturbs and c.perturbs not in by_name]
    return out
