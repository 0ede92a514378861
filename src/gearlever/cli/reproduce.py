"""``gearlever reproduce``: write every table and figure of the project.

Both folders are checked first (each must be a writable directory, or
creatable); a refused one ends with exit 2 naming the flag and the path, and
nothing is written.  Then they are created and every file is written, all or
none (a failure removes the folders created).  The summary lines name the
files by the paths written (``--tables t`` prints ``t/...``).
"""

from __future__ import annotations

from pathlib import Path

from gearlever.cli._common import check_output_folder, commit_outputs, emit


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="regenerate tables/ and figures/")
    p.add_argument("--tables", default="tables", help="folder for CSV tables (default: tables)")
    p.add_argument("--figures", default="figures", help="folder for figures (default: figures)")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from gearlever.reproduce import run

    check_output_folder(args.tables, "--tables")  # both checked before either is created
    check_output_folder(args.figures, "--figures")
    check_output_folder(args.tables, "--tables", create=True)
    check_output_folder(args.figures, "--figures", create=True)
    lines = run(Path(args.tables), Path(args.figures))
    commit_outputs()  # the lines name the files written: they are printed once the files are there
    emit("\n".join(lines))
    return 0
