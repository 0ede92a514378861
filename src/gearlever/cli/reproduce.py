"""``gearlever reproduce``: write every table and figure of the project."""

from __future__ import annotations

from pathlib import Path


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="regenerate tables/ and figures/")
    p.add_argument("--tables", default="tables", help="folder for CSV tables (default: tables)")
    p.add_argument("--figures", default="figures", help="folder for figures (default: figures)")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from gearlever.reproduce import run

    for line in run(Path(args.tables), Path(args.figures)):
        print(line)
    return 0
