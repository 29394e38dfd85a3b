"""The registry of the studies' claims: every registered claim by study, the frozen list of
each (``pipeline/studies/<study>/frozen.json``: {id: hash of its rule and scope}, written once
the claim has been judged in the committed report, never rewritten), and the tool that
freezes newly judged claims::

    python -m pipeline.studies.registry            # what is judged but not frozen, what broke
    python -m pipeline.studies.registry --freeze   # freeze the claims judged in figures/REPORT.md

The rules of freezing are :mod:`pipeline.claims.registry`'s.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from pathlib import Path

from ..claims.claim import Claim
from ..claims.registry import frozen_mismatches, read_frozen, rule_hash

__all__ = ["STUDIES", "claims", "all_claims", "frozen_path", "frozen", "judged_ids", "main"]

#: the studies whose claims carry ids in REPORT.md (the contact and protocol studies re-judge
#: the paper's claims under other tables and register none of their own)
STUDIES = ("klages2004", "mechanisms", "transport", "dissipation")
HERE = Path(__file__).resolve().parent
REPORT = HERE.parents[1] / "figures" / "REPORT.md"


def claims(study: str) -> list[Claim]:
    """The study's registered claims."""
    return list(importlib.import_module(f"pipeline.studies.{study}.claims").CLAIMS)


def all_claims() -> dict[str, list[Claim]]:
    return {s: claims(s) for s in STUDIES}


def frozen_path(study: str) -> Path:
    return HERE / study / "frozen.json"


def frozen(study: str) -> dict[str, str]:
    return read_frozen(frozen_path(study))


def judged_ids(report: str) -> set[str]:
    """The claim ids with a verdict in a REPORT.md text."""
    from .klages2004.changes import verdicts

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
