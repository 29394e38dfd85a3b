"""A6c's line: the scene ``dissipation_own_seeds`` is the map's α = 0.7 line at the frequencies
Fig. 2 shares, with seeds of its own -- no chunk of it is a chunk of the map or of Fig. 2 --
and its committed cut against Fig. 2 is the cut of the committed tables."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pipeline.studies.dissipation.claims import MAP, OWN_SEEDS_CUT
from pipeline.studies.dissipation.cuts import compare_cut
from pipeline.studies.dissipation.report import OWN_SEEDS, SCENES
from pipeline.workflow.scenes import load_scene
from tests.pipeline.map_scenes import ROOT

FIGURES = ROOT / "figures"


def _chunk_states(study, frequencies) -> set[tuple[int, ...]]:
    """The first words of every chunk seed a run of ``study`` can draw at ``frequencies``
    (every chunk index up to its cap of particles)."""
    n = study.accuracy.max_particles // study.accuracy.chunk_size
    return {tuple(study.seed_sequence(f, fam, c).generate_state(4)) for f in frequencies
            for fam in study.families for c in range(n)}


def test_the_own_seed_scene_is_the_maps_alpha_07_line_at_the_frequencies_figure2_shares():
    own, fig2 = load_scene(OWN_SEEDS), load_scene("figure2")
    line = load_scene(MAP).line({"alpha": 0.7})
    shared = sorted({round(f, 3) for f in line.frequencies} & {round(f, 3) for f in fig2.frequencies})
    assert [round(f, 3) for f in own.frequencies] == shared
    a, b = own.data_identity(), line.with_frequencies(own.frequencies).data_identity()
    assert {k for k in a.keys() | b.keys() if a.get(k) != b.get(k)} == {"seed"}


def test_no_chunk_of_the_own_seed_scene_is_a_chunk_of_the_map_or_of_figure2():
    own = load_scene(OWN_SEEDS)
    mine = _chunk_states(own, own.frequencies)
    assert len(mine) == len(own.frequencies) * own.accuracy.max_particles // own.accuracy.chunk_size
    for other in (load_scene(MAP).line({"alpha": 0.7}), load_scene("figure2")):
        assert mine.isdisjoint(_chunk_states(other, own.frequencies))


def test_the_own_seed_scene_is_a_scene_of_the_dissipation_study():
    assert OWN_SEEDS in SCENES


def test_the_committed_own_seed_cut_is_the_cut_of_the_committed_tables():
    """figures/dissipation_cuts.csv's rows of the own-seed cut are compare_cut of the committed
    own-seed D(f) and Fig. 2's, at every frequency the scene lists."""
    cuts = pd.read_csv(FIGURES / f"{MAP}_cuts.csv")
    got = cuts[cuts["cut"] == OWN_SEEDS_CUT].drop(columns="cut").reset_index(drop=True)
    line = pd.read_csv(FIGURES / f"{OWN_SEEDS}_diffusion.csv")
    ref = pd.read_csv(FIGURES / "diffusion_figure2.csv")
    want = compare_cut(line, ref, load_scene(OWN_SEEDS).accuracy.d_resolved,
                       load_scene("figure2").accuracy.d_resolved)
    listed = [round(f, 3) for f in load_scene(OWN_SEEDS).frequencies]
    assert line["f"].round(3).tolist() == got["f"].round(3).tolist() == listed
    pd.testing.assert_frame_equal(got, want, check_dtype=False, rtol=1e-5)


def test_the_own_seed_line_is_other_particles_than_figure2s():
    """Where D is above the resolution, no own-seed D equals Fig. 2's to every digit (the map's
    α = 0.7 line, sharing Fig. 2's chunks, equals it at every frequency)."""
    cuts = pd.read_csv(FIGURES / f"{MAP}_cuts.csv")
    own = cuts[(cuts["cut"] == OWN_SEEDS_CUT) & (cuts["D"] > cuts["d_resolved"])]
    assert len(own) > 0
    assert not np.any(own["D"].to_numpy() == own["D_ref"].to_numpy())


def test_a6cs_note_gives_the_chance_of_as_many_disagreements_between_equal_curves():
    """2 of 25 disagreeing: P(X ≥ 2), X ~ Binomial(25, 0.05) = 1 − 0.95²⁵ − 25 · 0.05 · 0.95²⁴
    (about 0.36); with none disagreeing, no note."""
    from pipeline.claims.claim import evaluate_claim
    from pipeline.studies.dissipation.claims import CLAIMS

    a6c = next(c for c in CLAIMS if c.id == "A6c")
    agree = [0.0, 0.0] + [1.0] * 23
    t = pd.DataFrame({"f": np.arange(50.0, 100.0, 2.0), "agree": agree, "cut": OWN_SEEDS_CUT})
    row = evaluate_claim(a6c, {"tables": {f"{MAP}_cuts": t}})
    p = 1 - 0.95 ** 25 - 25 * 0.05 * 0.95 ** 24
    assert row.verdict == "disagrees"
    assert f"2 or more of 25 with probability {p:.2f}" in row.note and "allows 1" in row.note
    assert "Were both" not in evaluate_claim(
        a6c, {"tables": {f"{MAP}_cuts": t.assign(agree=1.0)}}).note
