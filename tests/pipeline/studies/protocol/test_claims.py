"""The protocol claims on synthetic tables with known answers: the paper-like protocol is
found, a falling one is not; claim 16 on the families; claim 2's note in the paper's
section reads the protocol verdicts."""

from __future__ import annotations

import math

import pandas as pd

from bbb.params import Params
from pipeline.claims.claim import evaluate
from pipeline.studies.klages2004.claims import CLAIMS, context
from pipeline.studies.protocol.claims import reproducing, verdicts_table
from pipeline.studies.protocol.tables import protocol_name

from .synthetic import F, curves, falling

GOOD = protocol_name("launched", 10.0, "displaced")


def test_the_paper_like_protocol_and_only_it_reproduces():
    v = verdicts_table(curves())
    ok, missing = reproducing(v)
    assert ok == [GOOD]
    bad = missing[protocol_name("rest", 5.0, "all")]
    assert "2" in bad and "4" in bad  # falling: no maximum near 54, no minimum near 58


def test_no_protocol_reproduces_when_none_is_paper_like():
    ok, missing = reproducing(verdicts_table(curves(good=None)))
    assert ok == [] and all("2" in m for m in missing.values())


def test_claim_16_is_judged_on_the_families():
    """Families equal everywhere but at 55 Hz (one family far off): agrees for that (T,
    definition); off also at 47 Hz: partly."""
    out = {("rest", 5.0, "all", 55.0): 2 * falling(F)[F == 55.0][0]}
    v = verdicts_table(curves(outlier=out))
    c16 = v[v["claim"].astype(str) == "16"].set_index("protocol")["verdict"]
    assert c16[protocol_name("families", 5.0, "all")] == "agrees"
    assert c16[protocol_name("families", 10.0, "all")] == "disagrees"  # families agree
    out[("rest", 5.0, "all", 47.0)] = 2 * falling(F)[F == 47.0][0]
    v = verdicts_table(curves(outlier=out))
    c16 = v[v["claim"].astype(str) == "16"].set_index("protocol")["verdict"]
    assert c16[protocol_name("families", 5.0, "all")] == "partly"


def _claim2(tables):
    p = Params.preset("klages2004", f=60.0)
    rows = evaluate([c for c in CLAIMS if c.id == "2"],
                    context(tables, {}, math.sqrt(p.g / p.A) / (2 * math.pi), p.as_dict()))
    return rows[0]


def test_claim_2_of_the_paper_states_the_protocol_result():
    fig2 = pd.DataFrame({"f": F, "D": falling(F), "D_lo": 0.95 * falling(F),
                         "D_hi": 1.05 * falling(F)})
    plain = _claim2({"figure2": fig2})
    assert plain.verdict == "disagrees" and "Protocol study" not in plain.note
    v = verdicts_table(curves())
    row = _claim2({"figure2": fig2, "protocol_verdicts": v})
    assert "Protocol study" in row.note and GOOD in row.note
    n = v[v["claim"].astype(str) != "16"]["protocol"].nunique()
    assert f"together under 1 ({GOOD})" in row.note and f"{n} protocols" in row.note
