"""The house style of every figure (pipeline.plot.style)."""

from __future__ import annotations

from pipeline.plot.style import FAMILY_COLORS, family_color


def test_families_without_a_colour_of_their_own_get_distinct_colours_not_taken_by_named_ones():
    others = [family_color(f"fam{i}", i) for i in range(4)]
    assert len(set(others)) == 4 and not set(others) & set(FAMILY_COLORS.values())
    assert family_color("rest", 3) == FAMILY_COLORS["rest"]
