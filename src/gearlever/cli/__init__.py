"""The ``gearlever`` command line.

Each module in this package that defines ``register(subparsers)`` adds one
sub-command (found automatically, in alphabetical order of module name).  A
sub-command's handler is stored as ``func`` on its parser and returns an exit
status.  The CLI only parses arguments, calls the library and writes files.

Errors: bad arguments and any :class:`ValueError` from the library end the
program with exit status 2 and exactly one line on stderr, no traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import sys


class UsageError(Exception):
    """Raised instead of argparse's print-usage-and-exit, to keep errors to one line."""


class OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line, raised as :class:`UsageError`."""

    def error(self, message):  # noqa: D401 - argparse API
        raise UsageError(f"{self.prog}: {message}")


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level parser with every sub-command registered."""
    from gearlever import __version__

    parser = OneLineParser(
        prog="gearlever",
        description="Kinematic analysis of gear-lever differential mechanisms.",
    )
    parser.add_argument("--version", action="version", version=f"gearlever {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    sub.required = True
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        register = getattr(module, "register", None)
        if register is not None:
            register(sub)
    return parser


def main(argv=None) -> int:
    """Run the CLI; return the exit status (0 ok, 2 bad input)."""
    # The command line writes files and never opens windows: it, not the library,
    # chooses a non-interactive matplotlib backend (the user's MPLBACKEND wins).
    os.environ.setdefault("MPLBACKEND", "Agg")
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        status = args.func(args)
    except UsageError as exc:
        print(str(exc).replace("\n", " "), file=sys.stderr)
        return 2
    except ValueError as exc:
        print(
            f"gearlever: error: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}",
            file=sys.stderr,
        )
        return 2
    except BrokenPipeError:
        return 0
    return int(status or 0)
