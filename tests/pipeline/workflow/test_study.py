"""The validated workflow (pipeline.workflow.study.Study): seeds keyed by values, the fingerprint of
what determines the stored numbers, and the dict a store keeps."""

from __future__ import annotations

import numpy as np

from pipeline.workflow.load import parse_workflow

from ..helpers import TINY


def parse(text: str):
    return parse_workflow(text, source="wf.toml")


def test_seed_is_keyed_by_values_not_positions():
    a = parse(TINY)
    b = parse(TINY.replace("[54.0, 60.0]", "[60.0, 33.0, 54.0]")
              .replace("[families.rest]", "[families.extra]\ninitial = \"dropped\"\n"
                       "[families.rest]"))
    fam_a = next(f for f in a.families if f.name == "rest")
    fam_b = next(f for f in b.families if f.name == "rest")
    sa = a.seed_sequence(60.0, fam_a, 1).generate_state(4)
    sb = b.seed_sequence(60.0, fam_b, 1).generate_state(4)
    assert np.array_equal(sa, sb)
    assert not np.array_equal(sa, a.seed_sequence(54.0, fam_a, 1).generate_state(4))


def test_reduce_settings_do_not_change_the_fingerprint():
    a = parse(TINY)
    b = parse(TINY.replace("n_resamples = 100", "n_resamples = 500") + "[analysis]\nci = 0.9\n")
    c = parse(TINY.replace("t_max = 10.0", "t_max = 20.0"))
    assert a.fingerprint() == b.fingerprint() != c.fingerprint()


def test_study_round_trips_through_its_dict():
    s = parse(TINY)
    assert type(s).from_dict(s.to_dict()) == s


def test_family_description_is_kept_but_not_part_of_the_fingerprint():
    s = parse(TINY)
    d = parse(TINY.replace('initial = "rest"', 'initial = "rest"\ndescription = "from rest"'))
    assert d.families[0].description == "from rest" and s.fingerprint() == d.fingerprint()


def test_a_scenes_description_is_not_part_of_its_fingerprint():
    from pipeline.workflow.scenes import scene_path

    text = scene_path("smoke").read_text(encoding="utf-8")
    line = next(ln for ln in text.splitlines() if ln.startswith("description = "))
    without = text.replace(line + "\n", "")
    other = text.replace(line, 'description = "another text"')
    assert parse(text).fingerprint() == parse(without).fingerprint() == parse(other).fingerprint()
