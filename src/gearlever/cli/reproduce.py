"""``gearlever reproduce``: write every table and figure of the project.

Both folders are checked first (each must be a writable directory, or
creatable); a refused one ends with exit 2 naming the flag and the path, and
nothing is written.  Then they are created and every file is written
atomically.
"""

from __future__ import annotations

from pathlib import Path

from gearlever.cli._common import check_output_folder


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="regenerate tables/ and figures/")
    p.add_argument("--tables", default="tables", help="folder for CSV tables (default: tables)")
    p.add_argument("--figures", default="figures", help="folder for figures (default: figures)")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from gearlever.reproduce import run

    check_output_folder(args.tables, "--tables")
    check_output_folder(args.figures, "--figures")
    for line in run(Path(args.tables), Path(args.figures)):
        print(line)
    return 0
