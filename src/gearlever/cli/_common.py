"""Helpers shared by the CLI sub-commands: number parsing, caps, output and progress.

How a sub-command stays safe (what :func:`gearlever.cli.main` already does
for every command, and what each command can add):

* Errors: raise :class:`gearlever.errors.GearleverError` (or let the library
  raise it, or an :class:`OSError`); ``main`` prints one line and exits 2.
  Never print a traceback or call ``sys.exit`` from a handler.
* Numbers: give every argument an argparse ``type`` from this module
  (:func:`finite_float`, :func:`positive_float`, :func:`positive_int`,
  :func:`nonnegative_int`); argparse then names the flag in the error.
* Sizes: every argument that sets how much is allocated or computed gets a
  cap, ``type=capped_int(CAP)`` or ``type=capped_float(CAP)``, with ``CAP``
  a named constant next to the code that allocates and a comment giving the
  memory/time reasoning.  Caps on a product of arguments (turns times steps
  per turn) are checked in the handler with :func:`check_cap`.
* Outputs: ``main`` runs every handler inside one
  :func:`gearlever._io.output_set`, so that a command writes all its files
  or none, and checks ``args.out`` with :func:`check_output` before the
  handler runs; a command with other output arguments declares them with
  :func:`check_output` (files, with the suffixes the flag takes) or
  :func:`check_output_folder` (folders) first thing, before any work: two
  flags naming one file are refused there.  Write with :func:`emit` or the
  atomic helpers of :mod:`gearlever._io` (they stage into the set), never
  with ``open(path, "w")``; call :func:`commit_outputs` before printing the
  paths written.
* JSON: :func:`to_json` only (strict: NaN and infinities become null).
* Long work: wrap it in ``with progress("what"):`` so that a user at a
  terminal sees it is alive (nothing is printed when stderr is not a
  terminal, or for work under :data:`PROGRESS_DELAY` seconds).
"""

from __future__ import annotations

import argparse
import math
import re
import sys

from gearlever import _io
from gearlever._progress import PROGRESS_DELAY, TerminalProgress
from gearlever.errors import GearleverError


def finite_float(text: str) -> float:
    """argparse type: a finite float (argparse reports the parameter name on failure)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return value


def positive_float(text: str) -> float:
    """argparse type: a finite float > 0."""
    value = finite_float(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text!r}")
    return value


def nonnegative_int(text: str) -> int:
    """argparse type: an integer >= 0."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a non-negative integer, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be a non-negative integer, got {text!r}")
    return value


def positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    return value


def _cap_text(cap) -> str:
    """``10**7`` as ``10^7`` (readable), other caps as written."""
    if isinstance(cap, int) and cap >= 1000 and str(cap).rstrip("0") == "1":
        return f"10^{len(str(cap)) - 1}"
    return f"{cap:g}" if isinstance(cap, float) else str(cap)


def _integer_text(text: str) -> int:
    """The integer written in ``text``: digits (``100000``) or a whole number in ``e`` notation (``1e5``).

    The help prints large caps as ``1e+07``; a user who types a size the same
    way means that integer.  ``1.5``, ``1e-3`` and ``nan`` raise ValueError.

    >>> _integer_text("1e5"), _integer_text("2.5E3"), _integer_text(" 42 ")
    (100000, 2500, 42)
    """
    try:
        return int(text)
    except ValueError:
        pass
    t = str(text).strip()
    if "e" not in t.lower() or len(t) > 40:
        raise ValueError(text)
    from decimal import Decimal, InvalidOperation

    try:
        d = Decimal(t)
    except InvalidOperation:
        raise ValueError(text) from None
    if not d.is_finite() or d != d.to_integral_value() or abs(d) > 10**18:
        raise ValueError(text)
    return int(d)


def capped_int(cap: int, low: int = 1):
    """argparse type factory: an integer ``low <= n <= cap`` (the cap is named in the refusal).

    A whole number in ``e`` notation is that integer (``1e5`` is 100000).

    >>> t = capped_int(10**6)
    >>> t("20"), t("1e5")
    (20, 100000)
    >>> t("2000000")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be at most 10^6 (the cap for this size), got '2000000'
    """

    def parse(text: str) -> int:
        try:
            value = _integer_text(text)
        except ValueError:
            what = "a positive integer" if low == 1 else f"an integer >= {low}"
            raise argparse.ArgumentTypeError(f"must be {what}, got {text!r}") from None
        if value < low:
            what = "a positive integer" if low == 1 else f"an integer >= {low}"
            raise argparse.ArgumentTypeError(f"must be {what}, got {text!r}")
        if value > cap:
            raise argparse.ArgumentTypeError(f"must be at most {_cap_text(cap)} (the cap for this size), got {text!r}")
        return value

    parse.__name__ = f"integer <= {_cap_text(cap)}"
    return parse


def capped_float(cap: float, *, positive: bool = True):
    """argparse type factory: a finite float ``<= cap`` (and ``> 0`` when ``positive``).

    >>> capped_float(1e7)("5")
    5.0
    >>> capped_float(1e7)("1e9")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be at most 1e+07 (the cap for this size), got '1e9'
    """

    def parse(text: str) -> float:
        value = positive_float(text) if positive else finite_float(text)
        if value > cap:
            raise argparse.ArgumentTypeError(f"must be at most {_cap_text(cap)} (the cap for this size), got {text!r}")
        return value

    parse.__name__ = f"number <= {_cap_text(cap)}"
    return parse


def check_cap(what: str, value: float, cap: float) -> None:
    """Refuse a size computed from several arguments when it exceeds ``cap``.

    ``what`` names the flags, e.g. ``"--turns 5e6 with --steps-per-turn 1000"``.

    >>> check_cap("--turns 10 with --steps-per-turn 1000", 10_000, 10**7)
    >>> check_cap("--turns 1e9 with --steps-per-turn 1000", 1e12, 10**7)
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --turns 1e9 with --steps-per-turn 1000 imply 1e+12, more than the cap 10^7
    """
    if not value <= cap:  # also refuses NaN
        raise GearleverError(f"{what} imply {value:.6g}, more than the cap {_cap_text(cap)}")


#: File name endings of a figure output (the formats :func:`gearlever.plotting._common.save` writes).
FIGURE_SUFFIXES = ("png", "svg", "pdf")


def _outputs():
    """The output set of the running command (:func:`gearlever.cli.main` opens one), or a throw-away one."""
    return _io.current_outputs() or _io.OutputSet()


def check_output(path, flag: str = "--out", suffixes=None) -> None:
    """Declare an output file of the command and refuse it now, before any work, if it cannot be written.

    Refused, with a :class:`GearleverError` naming ``flag``, the path and the
    reason: an empty name, a directory, a device, a folder that does not
    exist (it is not created), a path under a regular file, an unwritable
    folder (``/proc``), a suffix not in ``suffixes`` (e.g. ``("png",)``), a
    file that another output of the command already names (``--out x.toml
    --report ./x.toml``, a link to it, a hard link).  ``None`` (stdout) passes.
    See :class:`gearlever._io.OutputSet`.

    >>> check_output(None)
    >>> check_output("/proc/x.csv")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --out '/proc/x.csv': cannot write in this folder: No such file or directory
    >>> check_output("f.txt", "--figure", ("png",))
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --figure must end with .png, got 'f.txt'
    """
    if path is None:
        return
    _outputs().declare(path, flag, suffixes=suffixes)


def check_output_folder(path, flag: str, *, create: bool = False) -> None:
    """Refuse an output folder that is a file or cannot be created or written; with ``create``, make it.

    A folder made here is removed again if the command fails (it writes all
    or none, see :class:`gearlever._io.OutputSet`); files written into it are
    named by ``flag`` in errors.

    >>> check_output_folder("/proc/t", "--tables")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --tables '/proc/t': cannot write in this folder: ... (at '/proc')
    """
    outputs = _outputs()
    if create:
        outputs.declare_folder(path, flag)
    else:
        try:
            _io.check_folder(path)
        except OSError as exc:
            raise _io.named_error(flag, path, exc) from None


def commit_outputs() -> list:
    """Write the files the command has staged so far (all or none); return their paths.

    A command that prints the paths it wrote calls this first, so that it
    prints only what is there.
    """
    outputs = _io.current_outputs()
    return [] if outputs is None else outputs.commit()


class ReaderGone(Exception):
    """stdout's reader went away (``gearlever ... | head``): not an error, exit 0.

    Not an :class:`OSError`, so that a handler catching write errors of an
    output file does not report a closed pipe as an ``--out`` problem.
    """


def emit(text: str, out: str | None = None, flag: str = "--out") -> None:
    """Print ``text`` to stdout, or write it atomically to the file ``out`` (checked first, named ``flag``).

    Inside a command the file is renamed into place with the command's other
    outputs, when it ends (all or none).

    A closed pipe on stdout raises :class:`ReaderGone` (``main`` exits 0).
    """
    if out is not None:
        check_output(out, flag)
        _io.write_text_atomic(out, text if text.endswith("\n") else text + "\n", flag=flag)
    else:
        try:
            print(text)
            sys.stdout.flush()
        except BrokenPipeError:
            raise ReaderGone() from None


def to_json(obj) -> str:
    """Strict JSON (NaN and infinities as null), keys in the order given; see :func:`gearlever._io.to_json`."""
    return _io.to_json(obj, indent=2)


def progress(label: str, stream=None, delay: float = PROGRESS_DELAY, interval: float = 1.0) -> TerminalProgress:
    """Show ``label`` and the elapsed seconds on stderr while the body runs, if it is a terminal.

    The renderer is :class:`gearlever._progress.TerminalProgress`: nothing is
    printed when the stream is not a terminal (pipes, files, tests) or when the
    body takes less than ``delay`` seconds; the line is erased at the end.  The
    same object is the ``progress(stage, done, total)`` callback of library work.

    >>> with progress("simulating"):
    ...     pass
    """
    return TerminalProgress(label, stream, delay, interval)


def flagged(exc: Exception, flags: dict[str, str]) -> GearleverError:
    """The library's error with its parameter names replaced by the CLI flags (one line).

    The leading name (``"max_teeth must ..."``) and any ``snake_case`` name
    in the message are replaced; plain words such as "pairs" inside the
    sentence are left alone.
    """
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    lead = re.match(r"[a-z_]+", text)
    if lead and lead.group(0) in flags:
        text = flags[lead.group(0)] + text[lead.end() :]
    text = re.sub(r"\b[a-z]+(?:_[a-z]+)+\b", lambda m: flags.get(m.group(0), m.group(0)), text)
    return GearleverError(text)


def named_values(given, flag: str, names, *, parse=None, bare_ok: bool = True) -> dict:
    """Parse ``NAME=VALUE`` arguments given once per input (``--rpm crank=100 --rpm lever=-30``).

    ``names`` are the valid names (the model's inputs, in order).  A bare
    ``VALUE`` is accepted when there is exactly one name and ``bare_ok``.
    Values are parsed by ``parse`` (default: a finite float; ``-1e6`` is a
    number).  Refused, naming ``flag``: an unknown or repeated name, a bad
    number.  Returns ``{name: value}`` in the order given.

    >>> named_values(["gear9=100", "lever1=-3e1"], "--rpm", ["gear9", "lever1"])
    {'gear9': 100.0, 'lever1': -30.0}
    >>> named_values(["100"], "--rpm", ["crank"])
    {'crank': 100.0}
    >>> named_values(["crnak=1"], "--rpm", ["crank"])
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --rpm: unknown input 'crnak' (inputs: crank)
    """
    parse = finite_float if parse is None else parse
    names = list(names)
    out: dict = {}
    for text in given or ():
        text = str(text)
        if "=" in text:
            name, _, value = text.partition("=")
            name = name.strip()
            if name not in names:
                raise GearleverError(f"{flag}: unknown input {name!r} (inputs: {', '.join(names)})")
        else:
            if not (bare_ok and len(names) == 1):
                raise GearleverError(f"{flag} must be NAME=VALUE, once per input ({', '.join(names)}), got {text!r}")
            name, value = names[0], text
        if name in out:
            raise GearleverError(f"{flag}: input {name!r} given twice")
        try:
            out[name] = parse(value.strip())
        except (argparse.ArgumentTypeError, ValueError) as exc:
            raise GearleverError(f"{flag} {name}: {exc}") from None
    return out
