"""``gearlever examples``: list the example model files shipped with the package, or copy them out.

Sub-commands::

    gearlever examples list [--format csv|json]
    gearlever examples copy NAME [NAME ...] [--to DIR] [--force]

``copy`` writes the files into ``DIR`` (default: the current folder,
created if missing) all or none, and prints the path of each copy, one a
line, so that ``gearlever mechanism analyze $(gearlever examples copy
fourbar)`` works.  Every name and every target is checked before anything is
written: an unknown name is refused with the list of valid ones, an existing
file is refused unless ``--force`` (a symbolic link in the way is replaced,
never written through).
"""

from __future__ import annotations

from pathlib import Path

from gearlever._io import table_text
from gearlever.cli._common import check_output_folder, commit_outputs, emit
from gearlever.errors import GearleverError

#: What a file of each suffix holds.
KINDS = {".toml": "mechanism model", ".csv": "gear network"}
#: CSV headers of synthesis targets (``gearlever synthesize``), and what they are.
TARGET_HEADERS = {
    "x,y,angle_deg": "motion poses (synthesize motion)",
    "x,y": "path points (synthesize path)",
    "x,y,input_deg": "timed path points (synthesize path)",
    "input_deg,output_deg": "function pairs (synthesize function)",
}


def _kind(name: str, text: str) -> str:
    """What an example holds: a mechanism model, a gear network or synthesis targets (by its CSV header)."""
    first = next((ln.strip() for ln in text.splitlines() if ln.strip() and not ln.startswith("#")), "")
    if name.endswith(".csv") and first.replace(" ", "") in TARGET_HEADERS:
        return TARGET_HEADERS[first.replace(" ", "")]
    if name.endswith(".toml") and any(ln.strip() == "[law]" for ln in text.splitlines()):
        return "motion law (cam design)"
    return KINDS.get(Path(name).suffix, "")


def register(sub) -> None:
    p = sub.add_parser(
        "examples",
        help="list the shipped example models (mechanism TOML, gear-network CSV) or copy them out",
        description="The example model files shipped with gearlever: list them, or copy some into a folder.",
    )
    es = p.add_subparsers(dest="examples_command", metavar="ACTION")
    es.required = True

    ls = es.add_parser("list", help="name, kind and first comment line of each example")
    ls.add_argument("--format", choices=("csv", "json"), default="csv")
    ls.set_defaults(func=_list)

    cp = es.add_parser("copy", help="copy examples into a folder (atomically; never overwrites without --force)")
    cp.add_argument("name", nargs="+", help="example name, with or without its suffix (see 'gearlever examples list')")
    cp.add_argument("--to", default=".", help="folder to copy into (created if missing; default: current folder)")
    cp.add_argument("--force", action="store_true", help="replace files that already exist")
    cp.set_defaults(func=_copy)


def _description(text: str) -> str:
    """The example's first comment line (its one-line description)."""
    for line in text.splitlines():
        if line.startswith("#"):
            return line.lstrip("#").strip()
        if line.strip():
            break
    return ""


def _list(args) -> int:
    from gearlever.data import example_path, list_examples

    names = list_examples()
    texts = [example_path(n).read_text(encoding="utf-8") for n in names]
    cols = {
        "name": names,
        "kind": [_kind(n, t) for n, t in zip(names, texts)],
        "description": [_description(t) for t in texts],
    }
    emit(table_text(cols, args.format))
    return 0


def _copy(args) -> int:
    from gearlever._io import write_text_atomic
    from gearlever.data import example_path

    sources = list({p.name: p for p in (example_path(n) for n in args.name)}.values())  # refuses unknown names first
    check_output_folder(args.to, "--to", create=True)
    folder = Path(args.to)
    targets = [folder / s.name for s in sources]
    dirs = [str(t) for t in targets if t.is_dir()]
    if dirs:
        raise GearleverError(f"--to: {', '.join(dirs)} is a directory, not replaced")
    existing = [str(t) for t in targets if t.exists() or t.is_symlink()]
    if existing and not args.force:
        raise GearleverError(f"--to: {', '.join(existing)} already exist(s); give --force to replace")
    for src, dst in zip(sources, targets):  # all or none: renamed into place together
        write_text_atomic(dst, src.read_text(encoding="utf-8"), flag="--to")
    emit("\n".join(str(t) for t in commit_outputs()))
    return 0
