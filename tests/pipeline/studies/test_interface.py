"""The Study record: its tables go to the files it names (a table without a name is refused,
not dropped), read back equal, and its claims are judged once or on each of its lines."""

from __future__ import annotations

import pandas as pd
import pytest

from pipeline.claims.claim import Band, Claim, Quantity
from pipeline.claims.section import Section
from pipeline.studies.interface import Study


def _value(claim, ctx):
    from pipeline.claims.claim import Measured, Part

    t = ctx["tables"].get("t")
    if t is None:
        return Measured(missing="no table t")
    q = Quantity(float(t["x"].iloc[0]))
    return Measured([Part("x", q, q.text("g"), band=claim.band)])


CLAIM = Claim("x is about 1", _value, "t", Band.around(1.0, 0.1, "test"))


def test_a_table_without_a_file_name_is_refused_and_the_named_ones_read_back(tmp_path):
    s = Study("s", ("sc",), Section("S"), files={"t": "t.csv"})
    with pytest.raises(KeyError, match="u have no file name"):
        s.write_tables(tmp_path, {"t": pd.DataFrame({"x": [1.0]}), "u": pd.DataFrame()})
    s.write_tables(tmp_path, {"t": pd.DataFrame({"x": [1.5]})})
    pd.testing.assert_frame_equal(s.read_tables(tmp_path)["t"], pd.DataFrame({"x": [1.5]}))


def test_claims_are_judged_once_or_on_each_line():
    once = Study("s", ("sc",), Section("S"), claims=(CLAIM,))
    assert [r.verdict for r in once.judge({"t": pd.DataFrame({"x": [1.0]})})[None]] == ["agrees"]
    per_line = Study("s", ("sc",), Section("S", layout="by claim"), claims=(CLAIM,),
                     lines=lambda tables: {"a": {"t": tables["a"]}, "b": {"t": tables["b"]}})
    v = per_line.judge({"a": pd.DataFrame({"x": [1.0]}), "b": pd.DataFrame({"x": [3.0]})})
    assert {k: [r.verdict for r in rows] for k, rows in v.items()} == {
        "a": ["agrees"], "b": ["disagrees"]}
