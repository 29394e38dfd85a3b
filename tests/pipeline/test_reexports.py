"""The old module paths kept for one release (docs/design.md, "Moved modules"): each still
gives the names code imported from it before the move, as the very objects of the new module.
The one file allowed to import them (tests/test_layout.py, REEXPORT_TEST)."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

#: old path -> (new modules, space-separated; the names imported from the old path before the
#: move)
MOVED = {
    "pipeline.workflow": ("pipeline.workflow.load",
                          ["Study", "WorkflowError", "load_workflow", "parse_workflow"]),
    "pipeline.store": ("pipeline.store.study_store",
                       ["COUNTERS", "JSON_ATTRS", "KERNEL_ATTRS", "LAYOUT_VERSION", "SEEDING",
                        "StoreError", "StudyStore", "fingerprint_difference", "is_local",
                        "normalize_path", "package_version", "read_attrs", "store_fingerprint"]),
    "pipeline.claims": ("pipeline.claims.record",
                        ["Band", "Claim", "Measured", "Part", "Quantity", "Row", "combine",
                         "evaluate", "evaluate_claim", "judge", "measure"]),
    "pipeline.reduce": ("pipeline.tables.reduce pipeline.tables.diffusion pipeline.tables.counters",
                        ["counters_table", "default_out_dir", "diffusion_table", "reduce_store",
                         "table_metadata", "column_unit", "write_table"]),
    "pipeline.run": ("pipeline.execute.run",
                     ["FAIL_ENV", "RunFailed", "RunReport", "connect", "run_study", "warm_numba"]),
    "pipeline.cluster": ("pipeline.execute.cluster",
                         ["ClusterConfigError", "check_slurm", "job_script", "slurm_cluster",
                          "slurm_settings", "work_left"]),
    "pipeline.identity": ("pipeline.workflow.identity",
                          ["PILOT_CHUNK", "SEEDING", "child_seed", "chunk_seed", "f_key", "f_keys",
                           "family_key", "mechanisms_seed", "pilot_seed", "reduce_seed",
                           "stop_seed", "table_seed"]),
}


@pytest.mark.parametrize("old", MOVED)
def test_an_old_path_gives_the_new_modules_objects(old):
    new, names = MOVED[old]
    was, now = importlib.import_module(old), [importlib.import_module(m) for m in new.split()]
    home = {n: next(m for m in now if hasattr(m, n)) for n in names}
    assert {n: getattr(was, n) is getattr(home[n], n) for n in names} == dict.fromkeys(names, True)
    assert "kept for one release" in " ".join((was.__doc__ or "").split())


def test_the_claims_markdown_is_still_importable_from_pipeline_claims():
    from pipeline.claims import markdown_table, md_cell
    from pipeline.claims.markdown import markdown_table as table
    from pipeline.claims.markdown import md_cell as cell

    assert (markdown_table, md_cell) == (table, cell)


@pytest.mark.parametrize("cmd", [["pipeline.workflow", "--reference"], ["pipeline.cluster", "x"]])
def test_the_old_python_dash_m_commands_still_run(cmd):
    out = subprocess.run([sys.executable, "-m", *cmd], capture_output=True, text=True, timeout=120)
    if cmd[0] == "pipeline.workflow":
        assert out.returncode == 0 and "| `name` |" in out.stdout, out.stderr
    else:  # an unknown cluster: its usage line, from the moved module
        assert out.returncode == 2 and "usage: python -m pipeline" in out.stderr, out.stderr
