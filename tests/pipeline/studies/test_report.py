"""The committed REPORT.md against the committed tables beside it: every study's section (its
claim verdicts, their measured text, its own words) regenerates from figures/*.csv, and every
figure has a caption."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pandas as pd
import pytest

from pipeline.studies.registry import STUDIES, studies, study
from pipeline.studies.report import claim_sections
from pipeline.tables.files import study_file, write_csv

FIGURES = Path(__file__).resolve().parents[3] / "figures"
REPORT = FIGURES / "REPORT.md"
PAPER = study("klages2004")
CLAIMS_HEADING = f"## {PAPER.section.heading}"

#: claims whose verdict needs more than the committed tables, by measure, and why: their rows
#: are not compared (test_the_claims_not_regenerable_from_the_tables_are_exactly_these)
NOT_REGENERABLE = PAPER.needs_stores


def sections(text: str) -> dict[str, list[str]]:
    """{'## heading': its non-empty lines} of a markdown document."""
    out: dict[str, list[str]] = {}
    heading = None
    for line in text.splitlines():
        if line.startswith("## "):
            heading = line
            out[heading] = []
        elif heading is not None and line.strip():
            out[heading].append(line)
    return out


def _cells(row: str) -> list[str]:
    return [c.strip() for c in re.split(r"(?<!\\)\|", row.strip())[1:-1]]


def _skipped_rows() -> set[str]:
    """The first cells ('15', ...) of this study's rows that are not regenerable."""
    return {c.id for c in PAPER.claims if c.quantity in NOT_REGENERABLE}


def _claim_rows(lines: list[str]) -> list[str]:
    """The rows of a claims table (not its header and rule)."""
    return [r for r in lines if r.startswith("| ") and _cells(r)[0] not in ("#", "---")]


def mismatches(report: str, regenerated: dict[str, list[str]]) -> list[str]:
    """What differs between the committed report and the regenerated claim sections: this
    study's claims table row by row (by its '#'), every other section line by line."""
    have = sections(report)
    out = []
    for heading, lines in regenerated.items():
        if heading not in have:
            out.append(f"{heading}: not in REPORT.md")
            continue
        if heading == CLAIMS_HEADING:
            rows = {_cells(r)[0]: r for r in _claim_rows(have[heading])}
            skip = _skipped_rows()
            for r in _claim_rows(lines):
                key = _cells(r)[0]
                if key in skip:
                    continue
                if rows.get(key) != r:
                    out.append(f"claim {key}:\n  REPORT.md:   {rows.get(key)}\n  regenerated: {r}")
            continue
        want = [line for line in lines if line.strip()]
        for i in range(max(len(want), len(have[heading]))):
            a = have[heading][i] if i < len(have[heading]) else None
            b = want[i] if i < len(want) else None
            if a != b:
                out.append(f"{heading}, line {i + 1}:\n  REPORT.md:   {a}\n  regenerated: {b}")
    return out


def test_every_claim_section_of_the_report_regenerates_from_the_committed_tables():
    """The paper's claims table (but the rows of NOT_REGENERABLE), its further sections and the
    whole section of every other study (mechanisms M rows, transport T rows, the contact table
    and its text, ...), regenerated from figures/*.csv, equal what REPORT.md says."""
    diff = mismatches(REPORT.read_text(encoding="utf-8"), claim_sections(FIGURES))
    assert not diff, "\n".join(diff)


def test_the_claims_not_regenerable_from_the_tables_are_exactly_these():
    """Regenerated without stores, exactly the claims of NOT_REGENERABLE come out 'not
    measured' where REPORT.md has a verdict: a claim that becomes regenerable must leave the
    list (and be compared), a claim that needs a store must say so here."""
    regenerated = claim_sections(FIGURES, studies=[PAPER])[CLAIMS_HEADING]
    have = {_cells(r)[0]: _cells(r) for r in _claim_rows(
        sections(REPORT.read_text(encoding="utf-8"))[CLAIMS_HEADING])}
    lost = {_cells(r)[0] for r in _claim_rows(regenerated)
            if _cells(r)[3] == "**not measured**"
            and have.get(_cells(r)[0], [""] * 4)[3] != "**not measured**"}
    assert lost == _skipped_rows(), NOT_REGENERABLE


def _copy(tmp_path: Path) -> Path:
    out = tmp_path / "figures"
    out.mkdir()
    for p in FIGURES.glob("*.csv"):
        shutil.copy(p, out)
    return out


def test_a_perturbed_number_that_a_claim_reads_changes_its_regenerated_verdict(tmp_path):
    """k_max of the rest family at 60 Hz set to 2.0 in locking.csv: claim 11 (k ≈ 1.47
    around 60 Hz) regenerates as 'disagrees', and the comparison says so."""
    out = _copy(tmp_path)
    lock = pd.read_csv(out / "locking.csv")
    at = (lock["family"] == "rest") & ((lock["f"] - 60.0).abs() < 1e-6)
    assert at.sum() == 1
    lock.loc[at, ["k_max", "k_max_lo", "k_max_hi"]] = 2.0
    lock.to_csv(out / "locking.csv", index=False)
    regenerated = claim_sections(out, studies=[PAPER])
    row = next(r for r in regenerated[CLAIMS_HEADING] if r.startswith("| 11 |"))
    assert _cells(row)[3] == "**disagrees**"
    assert any(d.startswith("claim 11:") for d in mismatches(REPORT.read_text(encoding="utf-8"),
                                                           regenerated))


def _files(s, out: Path) -> list[Path]:
    """The committed CSVs of study ``s`` in ``out``."""
    if s.files is not None:
        return [out / fn for fn in s.files.values() if (out / fn).is_file()]
    return [out / study_file(k, s.scenes) for k in s.read_tables(out)]


@pytest.mark.parametrize("name", STUDIES)
def test_a_studys_section_changes_when_its_tables_do(name, tmp_path):
    """Every number (but f and a map's grid coordinates) of every committed table of the
    study times 1.5: its regenerated section no longer matches REPORT.md (its claims read the
    committed tables)."""
    from pipeline.workflow.scenes import load_scene

    out = _copy(tmp_path)
    s = study(name)
    coords = {"f"} | {a for sc in s.scenes for a, _ in load_scene(sc).grid}
    files = _files(s, out)
    assert files
    for p in files:
        t = pd.read_csv(p)
        num = [c for c in t.select_dtypes("number").columns if c not in coords]
        t[num] = t[num] * 1.5
        t.to_csv(p, index=False)
    regenerated = claim_sections(out, studies=[s])
    assert mismatches(REPORT.read_text(encoding="utf-8"), regenerated)


def test_a_studys_tables_read_back_under_the_keys_make_figures_gives_them(tmp_path):
    """Tables named after their scene ('mechanisms', and 'mechanisms_fine' of a scene whose
    name the first prefixes), a scene's table and a table a draw hook added: written, read
    back under the same keys; a CSV of a scene's table that is no longer made is deleted, a
    CSV of no scene of the study kept."""
    scenes = ("contact_stick", "contact_proj_stick", "mechanisms", "mechanisms_fine")
    tables = {"mechanisms": pd.DataFrame({"f": [60.5]}),
              "mechanisms_fine": pd.DataFrame({"f": [60.25]}),
              "contact_stick_diffusion": pd.DataFrame({"f": [54.5], "D": [0.5]}),
              "contact_proj_stick_locking": pd.DataFrame({"f": [54.5], "k_peak": [1.5]})}
    from pipeline.tables.files import read_study_tables, write_study_tables

    write_csv(pd.DataFrame({"f": [1.5]}), tmp_path / "mechanisms_old.csv")
    write_csv(pd.DataFrame({"f": [1.5]}), tmp_path / "locking.csv")  # not a scene's
    write_study_tables(tmp_path, tables, scenes)
    assert not (tmp_path / "mechanisms_old.csv").exists() and (tmp_path / "locking.csv").exists()
    back = read_study_tables(tmp_path, scenes)
    assert set(back) == set(tables)
    for key, df in tables.items():
        pd.testing.assert_frame_equal(back[key], df)


def _figure_captions() -> dict[str, str]:
    """{figure stem: caption} of the '## Figures' list of REPORT.md."""
    lines = sections(REPORT.read_text(encoding="utf-8"))["## Figures"]
    return {m["stem"]: m["caption"].strip() for line in lines
            if (m := re.match(r"- \[`(?P<stem>[^`]+)\.png`\]\([^)]*\) \(and `\.pdf`\):(?P<caption>.*)",
                              line))}


def test_every_figure_listed_in_the_report_has_a_caption():
    figures = _figure_captions()
    assert len(figures) == len(sections(REPORT.read_text(encoding="utf-8"))["## Figures"])
    assert not [stem for stem, caption in figures.items() if not caption]


def test_every_figure_listed_in_the_report_has_a_caption_declared_in_code():
    """Each figure of REPORT.md has a non-empty caption among its study's captions (what
    make_figures writes beside it)."""
    declared = {k: v for s in studies() for k, v in s.captions.items()}
    assert not [stem for stem in _figure_captions() if not declared.get(stem, "").strip()]


# -- the committed D(f) tables: what their intervals promise ---------------------------------
def _diffusion_tables() -> dict[str, pd.DataFrame]:
    """{scene: its committed D(f) table} (figures/diffusion_<scene>.csv, <study>_diffusion.csv)."""
    out = {}
    for p in sorted(FIGURES.glob("*diffusion*.csv")):
        scene = p.stem.removeprefix("diffusion_").removesuffix("_diffusion")
        out[scene] = pd.read_csv(p)
    return out


def _intervals(t: pd.DataFrame) -> list[str]:
    """The D columns with an interval: D, D_<family>, D_drift (not dD, a difference)."""
    return [c[:-3] for c in t.columns if re.fullmatch(r"D(_[a-z]+)?_lo", c) and c[:-3] + "_hi" in t]


def test_no_committed_interval_of_d_has_zero_width():
    tables = _diffusion_tables()
    assert len(tables) >= 8  # the paper's four, mechanisms, and the maps transport(_sliding), contact
    for scene, t in tables.items():
        for c in _intervals(t):
            same = t[(t[c + "_lo"] == t[c + "_hi"])]
            assert same.empty, f"{scene}: {c} has a zero-width CI at f = {list(same['f'])}"


def _stops(text: str) -> dict[str, str]:
    """{column of D: stop reason} of a stop text ("target met" or "rest: cap; launched: ...")."""
    if ":" not in text:
        return {"D": text.strip()}
    return {f"D_{fam.strip()}": why.strip()
            for fam, why in (part.split(":", 1) for part in text.split(";"))}


def test_no_row_that_stopped_with_its_target_met_shows_a_wider_ci_than_the_target():
    from pipeline.workflow.load import parse_workflow
    from pipeline.workflow.scenes import scene_path

    checked = 0
    for scene, t in _diffusion_tables().items():
        if "stop" not in t:
            continue
        target = parse_workflow(scene_path(scene).read_text(), scene).accuracy.target_ci
        for _, row in t.iterrows():
            for col, why in _stops(row["stop"]).items():
                if why != "target met":
                    continue
                hw = 0.5 * (row[col + "_hi"] - row[col + "_lo"])
                assert hw <= target * row[col] * (1 + 1e-12), (scene, row["f"], col, hw)
                checked += 1
    assert checked >= 300


def test_the_level_floor_vibrated_vertically_carries_no_current_in_the_committed_table():
    from pipeline.studies.map_lines import line_table

    t = line_table(pd.read_csv(FIGURES / "transport_diffusion.csv"), {"tilt": 0.0, "throw": 90.0})
    assert len(t) >= 20 and (t["v_by"] == "mirror symmetry").all()
    assert t[["v", "v_lo", "v_hi"]].abs().max().max() <= 1e-9
