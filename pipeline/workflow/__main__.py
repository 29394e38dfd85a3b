"""``python -m pipeline.workflow --reference [--write]``: the workflow reference (printed, or
written into pipeline/README.md between its markers); ``--schema``: the scene format as a JSON
Schema (:mod:`pipeline.workflow.json_schema`)."""

from __future__ import annotations

import sys

from .keys import README, readme_with_reference, reference_markdown


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.workflow --reference [--write]``: print the reference table, or
    write it into pipeline/README.md between the markers; ``--schema``: print the scene
    format as a JSON Schema (:mod:`pipeline.workflow.json_schema`)."""
    argv = sys.argv[1:] if argv is None else argv
    if argv == ["--schema"]:
        import json

        from .json_schema import scene_schema

        print(json.dumps(scene_schema(), indent=1, ensure_ascii=False))
        return 0
    if "--reference" not in argv or set(argv) - {"--reference", "--write"}:
        print("usage: python -m pipeline.workflow --reference [--write] | --schema",
              file=sys.stderr)
        return 2
    if "--write" in argv:
        README.write_text(readme_with_reference(README.read_text(encoding="utf-8")),
                          encoding="utf-8")
        print(f"wrote the workflow reference into {README.name}")
    else:
        print(reference_markdown(), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
