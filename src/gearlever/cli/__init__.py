"""The ``gearlever`` command line.

Each module in this package that defines ``register(subparsers)`` adds one
sub-command (found automatically, in alphabetical order of module name).  A
sub-command's handler is stored as ``func`` on its parser and returns an exit
status.  The CLI only parses arguments, calls the library and writes files:
it may import every other part of gearlever (the library lazily, inside the
handlers, so that ``gearlever --help`` stays fast), never the reverse.

Exit status and errors (handled here, once, for every sub-command):

* 0: done.
* 2: bad input, with exactly one line on stderr and no traceback: a bad
  argument (argparse names the flag), any :class:`ValueError` (so every
  :class:`~gearlever.errors.GearleverError`; a message that starts with a
  parameter name the parser knows is prefixed with the user's flag), any
  :class:`OSError` (the line names the path and the reason), an
  :class:`OverflowError`, or a :class:`MemoryError` (the caps on sizes should
  prevent it).
* 130: interrupted (Ctrl-C), one line; 143: terminated (SIGTERM), one line.
  Both unwind normally, so a file being written is removed, never left half
  written or as a temporary file (the handler removes the temporary files
  first: :func:`gearlever._io.raise_or_defer`); during the renames they wait
  until all files are in place.
* 1: an internal error (a bug), one line asking for a report; set
  ``GEARLEVER_TRACEBACK=1`` to see the traceback instead.

Before the handler runs, an ``--out`` file is checked
(:func:`gearlever.cli._common.check_output`): a directory, a device, a
missing folder or an unwritable place is refused before any work.  Every
file a command writes is staged beside its target and renamed into place
when the handler returns (:func:`gearlever._io.output_set`): a command
writes all its files or none, two of its outputs may not be one file, and a
symbolic link is replaced, not followed.  Numeric
:class:`RuntimeWarning` s (overflow) are not printed: they would break the
one-line rule; the affected values come out as inf/nan (null in JSON).
"""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import re
import signal
import sys
import threading
import warnings


class UsageError(Exception):
    """Raised instead of argparse's print-usage-and-exit, to keep errors to one line."""


class _StoreOnce(argparse._StoreAction):
    """``store`` for an option that takes one value: given twice, it is refused (the last would win silently)."""

    def __call__(self, parser, namespace, values, option_string=None):
        seen = namespace.__dict__.setdefault("_options_given", set())
        if option_string is not None and self.dest in seen:
            raise argparse.ArgumentError(self, "given twice (it takes one value)")
        seen.add(self.dest)
        super().__call__(parser, namespace, values, option_string)


class OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line, raised as :class:`UsageError`.

    Negative numbers in scientific notation (``--torque -1e6``) are taken as
    values, not as flags (argparse alone knows only ``-5`` and ``-0.5``).  An
    option that takes one value is refused when given twice.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$")
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def error(self, message):  # noqa: D401 - argparse API
        raise UsageError(f"{self.prog}: {message}")


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level parser with every sub-command registered."""
    from gearlever import __version__

    parser = OneLineParser(
        prog="gearlever",
        description="Kinematic, kinetostatic and dynamic analysis and synthesis of gear-lever differential "
        "mechanisms, gear trains and planar linkages.",
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


def _chosen_parser(parser: argparse.ArgumentParser, args) -> argparse.ArgumentParser:
    """The innermost sub-command parser that ``args`` came from."""
    while True:
        subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        name = getattr(args, subs[0].dest, None) if subs else None
        if name is None or name not in subs[0].choices:
            return parser
        parser = subs[0].choices[name]


#: Library parameter names that stand for a CLI flag of another name (a message
#: "qdot must be ..." from a command with ``--rpm`` reads "--rpm must be ...").
PARAMETER_FLAGS = {
    "qdot": "rpm",
    "qdot0": "rpm",
    "mean_speed_rpm": "rpm",
    "period": "period_deg",
    "applied": "torque",
}


def _with_flag(message: str, parser: argparse.ArgumentParser | None) -> str:
    """Name the user's flag in front of a ``message`` that starts with a parameter name the parser knows.

    ``"steps_per_turn must be ..."`` becomes ``"--steps-per-turn: steps_per_turn must be ..."``;
    ``"step: the way-points need ..."`` becomes ``"--step: the way-points need ..."``; a library
    name of :data:`PARAMETER_FLAGS` is replaced: ``"qdot must be ..."`` becomes ``"--rpm must be ..."``
    when the command has ``--rpm``.
    """
    if parser is None:
        return message
    m = re.match(r"([A-Za-z_][A-Za-z0-9_]*)\b", message)
    if not m:
        return message
    name = m.group(1)
    dests = {a.dest: a for a in parser._actions if a.option_strings}
    alias = PARAMETER_FLAGS.get(name)
    if name not in dests and alias in dests:
        flag = max(dests[alias].option_strings, key=len)
        return flag + message[m.end() :]
    if name in dests:
        flag = max(dests[name].option_strings, key=len)
        rest = message[m.end() :]
        return flag + rest if rest.startswith(":") else f"{flag}: {message}"
    return message


def _one_line(text: str) -> str:
    lines = [ln.strip() for ln in str(text).splitlines() if ln.strip()]
    return " ".join(lines)


def _huge_values(args, parser) -> list:
    """``--flag value`` of the numeric arguments whose size floating-point arithmetic cannot carry far."""
    if args is None:
        return []
    flags = {}
    if parser is not None:
        flags = {a.dest: max(a.option_strings, key=len) for a in parser._actions if a.option_strings}
    found = []
    for dest, value in vars(args).items():
        values = value if isinstance(value, (list, tuple)) else [value]
        for v in values:
            if isinstance(v, (list, tuple)):
                v = next(
                    (x for x in v if isinstance(x, (int, float)) and not isinstance(x, bool) and abs(x) > 1e100), None
                )
            if isinstance(v, (int, float)) and not isinstance(v, bool) and abs(v) > 1e100:
                found.append(f"{flags.get(dest, dest)} {v:g}")
                break
    return found


def _overflow_line(args, parser) -> str:
    """One line for an arithmetic overflow: the flags whose values are too large, never Python's wording."""
    huge = _huge_values(args, parser)
    if huge:
        return f"a value is out of range: {', '.join(huge)} too large for the arithmetic (give a smaller value)"
    return "a value is out of range: a number of the input is too large for the arithmetic (give smaller values)"


def _oserror_line(exc: OSError) -> str:
    reason = exc.strerror or _one_line(exc) or type(exc).__name__
    names = [repr(str(f)) for f in (exc.filename, exc.filename2) if f is not None]
    return f"gearlever: error: {' -> '.join(names) + ': ' if names else ''}{reason}"


class Terminated(KeyboardInterrupt):
    """Raised in the main thread by SIGTERM, so that clean-up (``finally``) runs as for Ctrl-C."""


def _on_sigterm(signum, frame):
    from gearlever._io import raise_or_defer

    raise_or_defer(Terminated)


def _on_sigint(signum, frame):
    from gearlever._io import raise_or_defer

    raise_or_defer(KeyboardInterrupt)


def _install_sigterm():
    """Install the SIGTERM and SIGINT handlers (main thread only); return the old ones, or None.

    Both raise (:class:`Terminated`, :class:`KeyboardInterrupt`) so that clean-up runs, but never inside a
    critical section of the output writers (:func:`gearlever._io.raise_or_defer`): there they raise at its end.
    """
    if threading.current_thread() is not threading.main_thread():
        return None
    try:
        old_int = signal.getsignal(signal.SIGINT)
        old = signal.signal(signal.SIGTERM, _on_sigterm)
        if old_int is signal.default_int_handler:
            signal.signal(signal.SIGINT, _on_sigint)
        return old, old_int
    except (ValueError, OSError):
        return None


def _print_error(line: str) -> None:
    try:
        print(line, file=sys.stderr)
        sys.stderr.flush()
    except (OSError, ValueError):
        pass


def main(argv=None) -> int:
    """Run the CLI; return the exit status (0 ok, 2 bad input, 130 interrupted, 1 internal error)."""
    # The command line writes files and never opens windows: it, not the library,
    # chooses a non-interactive matplotlib backend (the user's MPLBACKEND wins).
    os.environ.setdefault("MPLBACKEND", "Agg")
    old_sigterm = _install_sigterm()
    try:
        return _main(argv)
    finally:
        if old_sigterm is not None:
            signal.signal(signal.SIGTERM, old_sigterm[0])
            if old_sigterm[1] is not None:
                signal.signal(signal.SIGINT, old_sigterm[1])


def _main(argv) -> int:
    from gearlever._io import output_set
    from gearlever.cli._common import ReaderGone, check_output

    chosen = None
    args = None
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        chosen = _chosen_parser(parser, args)
        # every file the command writes is staged and renamed into place when it ends: all or none
        reader_gone = False
        with output_set():
            out = getattr(args, "out", None)
            if isinstance(out, str) and not getattr(args, "out_is_folder", False):  # a folder is checked by its command
                check_output(out, "--out")
            with warnings.catch_warnings():
                # numeric warnings (overflow, invalid value) would be extra lines on
                # stderr; the results show them as inf/nan (json null) or the library refuses
                warnings.simplefilter("ignore", RuntimeWarning)
                try:
                    status = args.func(args)
                except (BrokenPipeError, ReaderGone):
                    # stdout's reader left (``| head``): not an error, so the files are still written
                    reader_gone = True
        if reader_gone:
            raise ReaderGone()
    except UsageError as exc:
        _print_error(_one_line(exc))
        return 2
    except (BrokenPipeError, ReaderGone):
        # the reader went away (``gearlever ... | head``): not an error; keep
        # Python from complaining again when it flushes stdout at exit
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        except (OSError, ValueError, AttributeError):
            pass
        return 0
    except OSError as exc:
        _print_error(_oserror_line(exc))
        return 2
    except ValueError as exc:
        _print_error(f"gearlever: error: {_with_flag(_one_line(exc), chosen) or type(exc).__name__}")
        return 2
    except OverflowError:
        _print_error(f"gearlever: error: {_overflow_line(args, chosen)}")
        return 2
    except MemoryError:
        _print_error(
            "gearlever: error: out of memory: a size argument is too large for this machine (see the caps in --help)"
        )
        return 2
    except Terminated:
        _print_error("gearlever: terminated")
        return 143
    except KeyboardInterrupt:
        _print_error("gearlever: interrupted")
        return 130
    except Exception as exc:  # noqa: BLE001 - last resort: one line instead of a traceback
        if os.environ.get("GEARLEVER_TRACEBACK"):
            raise
        _print_error(f"gearlever: internal error (please report): {type(exc).__name__}: {_one_line(exc)}")
        return 1
    return int(status or 0)
