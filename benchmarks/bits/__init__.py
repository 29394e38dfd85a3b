"""Bit-for-bit comparisons: this checkout's kernel against another revision's, a map's line against
the scene it replaces, the committed tables against a revision's."""
