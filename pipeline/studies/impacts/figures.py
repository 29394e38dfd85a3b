"""Placeholder until the figures are drawn (replaced in the next commit)."""

CAPTIONS: dict = {}


def draw(tables, stores, out_dir):
    return []
