"""The registry's rules on toy claims: the hash holds the rule and scope, the frozen list
catches a changed rule, and the case check catches a claim that cannot be turned."""

from __future__ import annotations

from dataclasses import replace

from pipeline.claims.claim import Band, Case, Claim, Measured, Part, Quantity, measure
from pipeline.claims.registry import case_problems, frozen_mismatches, id_problems, rule_hash


@measure("toy")
def _toy(claim, ctx) -> Measured:
    if "x" not in ctx:
        return Measured(missing="no x")
    return Measured([Part("x", Quantity(ctx["x"], ctx["x"] - 0.1, ctx["x"] + 0.1))])


def _cases():
    return [Case("x = 1", {"x": 1.0}, "agrees"),
            Case("x = 5", {"x": 5.0}, "disagrees", perturbs="x = 1")]


TOY = Claim("x is about 1", _toy, "s", Band(0.5, 1.5, "toy"), id="X1", registered="today",
            scope={"scenes": ["s"]}, cases=_cases)


def test_the_hash_changes_with_the_rule_and_the_scope_not_with_the_note():
    h = rule_hash(TOY)
    assert rule_hash(replace(TOY, band=Band(0.5, 2.0, "toy"))) != h
    assert rule_hash(replace(TOY, scope={"scenes": ["s", "t"]})) != h
    assert rule_hash(replace(TOY, note="a note")) == h


def test_a_frozen_claim_whose_rule_changed_is_named():
    frozen = {"X1": rule_hash(TOY)}
    assert frozen_mismatches([TOY], frozen) == []
    wider = replace(TOY, scope={"scenes": ["s", "t"]})
    assert frozen_mismatches([wider], frozen)[0].startswith("X1: its rule or scope changed")
    assert "no claim has this id" in frozen_mismatches([], frozen)[0]


def test_a_claim_with_cases_that_turn_it_each_way_passes():
    assert case_problems(TOY) == []


def test_a_claim_without_cases_fails():
    assert case_problems(replace(TOY, cases=None)) == ["X1: no synthetic-case provider"]


def test_cases_that_do_not_turn_it_or_flip_it_fail():
    one_way = replace(TOY, cases=lambda: [Case("x = 1", {"x": 1.0}, "agrees")])
    problems = case_problems(one_way)
    assert any("each way" in p for p in problems) and any("flips" in p for p in problems)


def test_a_case_whose_expected_verdict_is_wrong_fails():
    wrong = replace(TOY, cases=lambda: [Case("x = 1", {"x": 1.0}, "disagrees"),
                                        Case("x = 5", {"x": 5.0}, "agrees", perturbs="x = 1")])
    assert len([p for p in case_problems(wrong) if "expected" in p]) == 2


def test_repeated_ids_and_unknown_supersedes_are_registration_errors():
    twin = replace(TOY, supersedes="X0")
    problems = id_problems([TOY, twin])
    assert any("used 2 times" in p for p in problems) and any("supersedes X0" in p
                                                              for p in problems)


def test_a_consistency_claim_never_agrees():
    from pipeline.claims.claim import evaluate_claim

    c = replace(TOY, kind="consistency")
    assert evaluate_claim(c, {"x": 1.0}).verdict == "consistent"
    assert evaluate_claim(c, {"x": 5.0}).verdict == "inconsistent"


def test_a_rule_over_all_parts_is_not_measured_when_a_part_is_missing():
    from pipeline.claims.claim import evaluate_claim

    @measure("toy2")
    def two(claim, ctx):
        return Measured([Part("a", Quantity(1.0, 0.9, 1.1)), Part("b", Quantity(float("nan")))])

    c = Claim("both about 1", two, "s", Band(0.5, 1.5, "toy"))
    assert evaluate_claim(c, {}).verdict == "agrees"  # a one-sided rule reads 'a' alone
    assert evaluate_claim(replace(c, all_parts=True), {}).verdict == "not measured"
