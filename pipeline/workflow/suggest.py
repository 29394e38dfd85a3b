""""Did you mean ...": the closest of the allowed names to a misspelled one (difflib), for
the one-line errors of an unknown key, section or scene name."""

from __future__ import annotations

import difflib
from collections.abc import Iterable

__all__ = ["closest", "did_you_mean"]


def closest(word: str, allowed: Iterable[str], n: int = 1) -> list[str]:
    """Up to ``n`` of ``allowed`` closest to ``word`` (difflib.get_close_matches, cutoff 0.6;
    compared case-insensitively)."""
    allowed = list(allowed)
    lower = {a.lower(): a for a in allowed}
    return [lower[m] for m in difflib.get_close_matches(word.lower(), list(lower), n=n)]


def did_you_mean(word: str, allowed: Iterable[str], n: int = 1) -> str:
    """" (did you mean 'x'?)" for the closest allowed names, or "" if none is close."""
    near = closest(word, allowed, n)
    return f" (did you mean {' or '.join(repr(m) for m in near)}?)" if near else ""
