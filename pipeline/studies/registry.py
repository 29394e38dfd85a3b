"""The registry of the studies: which studies there are, in the order ``make figures`` runs
them and the report shows them (:data:`STUDIES`, each package's ``STUDY``, a
:class:`~pipeline.studies.interface.Study`), every registered claim by study, the frozen list
of each (``pipeline/studies/<study>/frozen.json``: {id: hash of its rule and scope}, written
once the claim has been judged in the committed report, never rewritten), and the tool that
freezes newly judged claims::

    python -m pipeline.studies.registry            # what is judged but not frozen, what broke
    python -m pipeline.studies.registry --freeze   # freeze the claims judged in figures/REPORT.md

A list in a module, not entry points: the studies live in this repository, their order is the
report's (and a study may read a table an earlier one wrote), a new study is seen without
reinstalling the package, and tests/test_layout.py checks that every study folder is listed.
The rules of freezing are :mod:`pipeline.claims.registry`'s.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from pathlib import Path

from ..claims.changes import verdicts
from ..claims.claim import Claim
from ..claims.registry import frozen_mismatches, read_frozen, rule_hash
from .interface import Study

__all__ = ["STUDIES", "TOOLS", "study", "studies", "claims", "claim", "all_claims",
           "frozen_path", "frozen", "judged_ids", "main"]

#: the studies, in the order make figures runs them and REPORT.md shows their sections
STUDIES = ("klages2004", "mechanisms", "transport", "contact", "protocol", "dissipation",
           "impacts", "onset", "basins", "ratchet")
#: study folders that are tools, not part of the figure run (``bbb accuracy``)
TOOLS = ("accuracy",)
HERE = Path(__file__).resolve().parent
REPORT = HERE.parents[1] / "figures" / "REPORT.md"


def study(name: str) -> Study:
    """The study ``name`` (its package's ``STUDY``); one line naming the registered ones if
    there is none."""
    if name not in STUDIES:
        raise KeyError(f"no study {name!r}; registered: {', '.join(STUDIES)}")
    s = importlib.import_module(f"pipeline.studies.{name}").STUDY
    if not isinstance(s, Study) or s.name != name:
        raise TypeError(f"pipeline.studies.{name}.STUDY is not the Study named {name!r}")
    return s


def studies() -> list[Study]:
    """Every registered study, in order."""
    return [study(n) for n in STUDIES]


def claims(name: str) -> list[Claim]:
    """The claims study ``name`` registers (those not already another study's records: the
    contact and protocol studies re-judge the paper's claims and register none)."""
    earlier = {id(c) for n in STUDIES[:STUDIES.index(name)] for c in study(n).claims}
    return [c for c in study(name).claims if id(c) not in earlier]


def claim(name: str, claim_id: str) -> Claim:
    """The claim registered by study ``name`` under ``claim_id`` (a record to re-judge)."""
    found = [c for c in claims(name) if c.id == claim_id]
    if not found:
        raise KeyError(f"study {name} registers no claim {claim_id!r}")
    return found[0]


def all_claims() -> dict[str, list[Claim]]:
    """{study: the claims it registers}, the studies that register claims."""
    return {s: cs for s in STUDIES if (cs := claims(s))}


def frozen_path(study: str) -> Path:
    return HERE / study / "frozen.json"


def frozen(study: str) -> dict[str, str]:
    return read_frozen(frozen_path(study))


def judged_ids(report: str) -> set[str]:
    """The claim ids with a verdict in a REPORT.md text."""
    return set(verdicts(report))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.studies.registry",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--freeze", action="store_true",
                    help="freeze every claim judged in figures/REPORT.md that is not yet frozen")
    a = ap.parse_args(argv)
    judged = judged_ids(REPORT.read_text(encoding="utf-8")) if REPORT.is_file() else set()
    bad = 0
    for study, cs in all_claims().items():
        fz = frozen(study)
        for msg in frozen_mismatches(cs, fz):
            print(f"{study}: {msg}")
            bad += 1
        new = {c.id: rule_hash(c) for c in cs if c.id in judged and c.id not in fz}
        if new and a.freeze:
            fz.update(new)
            frozen_path(study).write_text(json.dumps({"frozen": dict(sorted(fz.items()))},
                                                     indent=1) + "\n", encoding="utf-8")
            print(f"{study}: froze {', '.join(new)}")
        elif new:
            print(f"{study}: judged, not frozen: {', '.join(new)}")
    return 2 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
