"""A shipped scene as a template: ``bbb scenes --show NAME`` prints it as it ships (its
comments say what each line is for), ``bbb new NAME --from SCENE`` writes it as ``NAME.toml``
in the current directory with ``[study] name = "NAME"``, to edit and run.

``--show`` is an option of the ``bbb scenes`` parser that :mod:`pipeline.commands.plan_scenes`
builds (its listing stays there); :func:`add_parsers` adds it to that parser after the fact
and runs the listing when it is not given.  An unknown scene name is one line, exit 2, listing
the shipped names.
"""

from __future__ import annotations

import re
from pathlib import Path

from .common import UsageError

__all__ = ["add_parsers", "cmd_new", "show_text", "template_text"]

#: a study name, as ``[study] name`` allows it (pipeline.workflow.keys.StudyTable.name)
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]*")


def add_parsers(sub) -> None:
    """``bbb new``, and ``--show NAME`` on the ``bbb scenes`` parser already in ``sub``."""
    scenes = sub.choices["scenes"]
    scenes.add_argument("--show", metavar="NAME",
                        help="print the shipped scene NAME as TOML (to read or copy; "
                             "`bbb new` writes it as a file)")
    listing = scenes.get_default("handler")
    scenes.set_defaults(handler=lambda args: cmd_show(args) if args.show else listing(args))

    n = sub.add_parser("new", help="write a shipped scene as NAME.toml to edit: "
                                   "bbb new NAME --from SCENE",
                       description="Copy the shipped scene SCENE (`bbb scenes` lists them) to "
                                   "NAME.toml in the current directory (or --out), its [study] "
                                   "name set to NAME, so that `bbb run NAME.toml` writes "
                                   "runs/NAME.zarr.  An existing file is never overwritten.")
    n.add_argument("name", metavar="NAME", help="the new study's name: letters, digits, "
                                                "'_', '-', '.' (it names the file and the store)")
    n.add_argument("--from", dest="scene", metavar="SCENE", required=True,
                   help="the shipped scene to start from")
    n.add_argument("--out", metavar="FILE", help="where to write (default: NAME.toml)")
    n.set_defaults(handler=cmd_new)


def _scene_text(name: str) -> str:
    """The text of the shipped scene ``name``; UsageError listing the shipped names if none."""
    from ..workflow.scenes import scene_names, scene_path
    from ..workflow.suggest import did_you_mean

    names = scene_names()
    if name not in names:
        raise UsageError(f"{name}: no such shipped scene{did_you_mean(name, names, n=3)}; "
                         f"allowed: {', '.join(names)}")
    return scene_path(name).read_text(encoding="utf-8")


def show_text(name: str) -> str:
    """The shipped scene ``name`` as it ships, headed by where it lives in the source tree."""
    from ..workflow.scenes import scene_label

    text = _scene_text(name)
    return f"# {scene_label(name)}\n{text}"


def template_text(scene: str, name: str) -> str:
    """The shipped scene ``scene`` with ``[study] name = "name"`` (its comments kept), headed
    by the scene it came from; refused (UsageError) if the result is not a valid scene."""
    from ..workflow.load import parse_workflow
    from ..workflow.scenes import scene_label
    from ..workflow.study import WorkflowError

    if not _NAME.fullmatch(name):
        raise UsageError(f"{name!r}: not a study name; allowed: letters, digits, '_', '-', '.', "
                         "starting with a letter or digit")
    lines = _scene_text(scene).splitlines()
    headers = [i for i, line in enumerate(lines) if re.match(r"^\s*\[", line)]
    study = next((i for i in headers if re.match(r"^\s*\[\s*study\s*\]", lines[i])), None)
    if study is None:  # no [study] table: one, first
        lines = ["[study]", f'name = "{name}"', "", *lines]
    else:
        end = next((i for i in headers if i > study), len(lines))
        at = next((i for i in range(study + 1, end) if re.match(r"^\s*name\s*=", lines[i])), None)
        if at is None:
            lines.insert(study + 1, f'name = "{name}"')
        else:  # its comment kept
            comment = re.search(r"#.*$", lines[at].split("=", 1)[1])
            lines[at] = f'name = "{name}"' + (f"  {comment.group(0)}" if comment else "")
    text = (f"# {name}: from the shipped scene {scene} ({scene_label(scene)}); edit it, then "
            "`bbb plan` and `bbb run` it\n" + "\n".join(lines) + "\n")
    try:
        loaded = parse_workflow(text, source=f"{name}.toml")
    except WorkflowError as e:  # a shipped scene that no longer loads: say so, write nothing
        raise UsageError(f"{scene}: the shipped scene does not load as a template ({e})") from None
    if loaded.name != name:
        raise UsageError(f"{scene}: could not set its [study] name to {name!r}")
    return text


def cmd_show(args) -> int:
    print(show_text(args.show), end="")
    return 0


def cmd_new(args) -> int:
    text = template_text(args.scene, args.name)
    out = Path(args.out or f"{args.name}.toml")
    if out.exists():
        raise UsageError(f"{out}: exists; allowed: a new file (--out FILE), or remove it first")
    try:
        out.write_text(text, encoding="utf-8")
    except OSError as e:
        raise UsageError(f"{out}: cannot write ({e.strerror}); allowed: a writable path") from None
    print(f"wrote {out} from the shipped scene {args.scene}: edit it, then "
          f"`bbb plan {out}` and `bbb run {out}` (-> runs/{args.name}.zarr)")
    return 0
