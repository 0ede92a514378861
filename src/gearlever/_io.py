"""Atomic file output: write to a temporary file beside the target, then rename.

No caller of gearlever is ever left with a half-written file: either the old
file (or none) is there, or the complete new one.
"""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import signal
import tempfile
import threading
from fractions import Fraction
from pathlib import Path

import numpy as np


def _refuse(errno_code: int, reason: str, path) -> OSError:
    """An :class:`OSError` of the right subclass naming ``path`` and ``reason``."""
    return OSError(errno_code, reason, str(path))


def check_target(target, *, mkdir: bool = False) -> Path:
    """Check that a file can be written at ``target``; return it as a :class:`~pathlib.Path`.

    Refuses (with an :class:`OSError` whose ``filename`` is the offending
    path and whose ``strerror`` says why) a target that is a directory or
    another non-regular file (a device, a pipe), a target whose folder does
    not exist (unless ``mkdir``), is not a folder, or cannot hold a new file
    (read-only, ``/proc``...).  The last check creates and removes an empty
    temporary file in the folder, the only reliable test (``os.access`` says
    yes to root everywhere).

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> check_target(d / "x.csv") == d / "x.csv"
    True
    >>> check_target(d / "missing" / "x.csv")
    Traceback (most recent call last):
    ...
    FileNotFoundError: [Errno 2] folder does not exist: '...missing'
    """
    target = Path(target)
    if str(target) in ("", "."):
        raise _refuse(errno.ENOENT, "empty file name", target)
    if target.is_dir():
        raise _refuse(errno.EISDIR, "is a directory", target)
    if target.exists() and not target.is_file():
        raise _refuse(errno.EINVAL, "is not a regular file (a device or pipe is not replaced)", target)
    parent = target.parent
    if not parent.exists():
        if mkdir:
            parent.mkdir(parents=True, exist_ok=True)
        else:
            # the nearest existing ancestor may be a regular file: say so
            for up in parent.parents:
                if up.exists():
                    if not up.is_dir():
                        raise _refuse(errno.ENOTDIR, "is not a directory", up)
                    break
            raise _refuse(errno.ENOENT, "folder does not exist", parent)
    if not parent.is_dir():
        raise _refuse(errno.ENOTDIR, "is not a directory", parent)
    # SIGTERM and Ctrl-C wait until the probe is gone (a handler that raises could otherwise
    # leave it behind, between its creation and its removal)
    with _signals_held():
        try:
            fd, probe = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".probe", dir=parent)
        except OSError as exc:
            raise _refuse(exc.errno or errno.EACCES, f"cannot write in this folder: {exc.strerror}", target) from None
        os.close(fd)
        with contextlib.suppress(OSError):
            os.unlink(probe)
    return target


def _hold_signals():
    """Hold SIGTERM and SIGINT (main thread, where the platform allows); return what :func:`_release_signals` takes."""
    import signal
    import threading

    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, (signal.SIGTERM, signal.SIGINT))


def _release_signals(old) -> None:
    """Restore the signal mask saved by :func:`_hold_signals` (a held signal is delivered now); idempotent."""
    if old is not None:
        import signal

        signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def _signals_held():
    """Hold SIGTERM and SIGINT for a short critical section."""
    old = _hold_signals()
    try:
        yield
    finally:
        _release_signals(old)


def check_folder(folder, *, create: bool = False) -> Path:
    """Check that files can be written in ``folder`` (existing, or creatable); return it.

    An existing ``folder`` must be a directory that can hold a new file; a
    missing one must have a nearest existing ancestor that is a writable
    directory.  Nothing is created unless ``create`` is true (then the folder
    and its missing parents are made after the checks pass).  Refusals are
    :class:`OSError` naming the path and the reason.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> check_folder(d / "new").exists()
    False
    >>> check_folder(d / "new", create=True).is_dir()
    True
    """
    folder = Path(folder)
    if str(folder) == "":
        raise _refuse(errno.ENOENT, "empty folder name", folder)
    existing = folder
    while not existing.exists():
        if existing.parent == existing:
            break
        existing = existing.parent
    if not existing.is_dir():
        raise _refuse(errno.ENOTDIR, "is not a directory", existing)
    try:
        fd, probe = tempfile.mkstemp(prefix=".gearlever.", suffix=".probe", dir=existing)
    except OSError as exc:
        raise _refuse(exc.errno or errno.EACCES, f"cannot write in this folder: {exc.strerror}", existing) from None
    os.close(fd)
    os.unlink(probe)
    if create and existing != folder:
        folder.mkdir(parents=True, exist_ok=True)
    return folder


class _Terminated(BaseException):
    """SIGTERM arrived while an atomic write was under way (raised to run the clean-up)."""


@contextlib.contextmanager
def _sigterm_unwinds():
    """While the body runs, a SIGTERM with the default action first unwinds, then kills.

    The default action ends the process at once, leaving the temporary file of
    a write in progress.  When SIGTERM still has its default action (and this
    is the main thread), a handler raises :class:`_Terminated` instead; once
    the clean-up has run the default action is restored and the signal sent
    again, so the process ends as it would have.  A program with its own
    handler (the ``gearlever`` command) is left alone.
    """
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGTERM) not in (
        signal.SIG_DFL,
        None,
    ):
        yield
        return

    def handler(signum, frame):
        raise _Terminated()

    old = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    except _Terminated:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)
        raise
    finally:
        signal.signal(signal.SIGTERM, old)


@contextlib.contextmanager
def atomic_path(target, suffix: str | None = None, *, mkdir: bool = False):
    """Yield a temporary path in ``target``'s folder; rename it onto ``target`` on success.

    The target is checked first with :func:`check_target`: a directory, a
    device, a folder that does not exist (it is created only when ``mkdir``
    is true) or an unwritable folder raise :class:`OSError` naming the path,
    before anything is written.  If the body raises, or the process gets
    SIGTERM or Ctrl-C, the temporary file is removed and ``target`` is left
    as it was.  A symbolic link is written
    through (its target is replaced), as a plain ``open`` would.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "x.txt") as tmp:
    ...     _ = tmp.write_text("hi")
    >>> (d / "x.txt").read_text()
    'hi'
    """
    with _sigterm_unwinds():
        with _atomic_path(target, suffix, mkdir) as tmp:
            yield tmp


@contextlib.contextmanager
def _atomic_path(target, suffix, mkdir):
    target = Path(target)
    if target.is_symlink():
        target = Path(os.path.realpath(target))
    target = check_target(target, mkdir=mkdir)
    held = _hold_signals()  # a SIGTERM or Ctrl-C waits until the temporary is known, so it is removed
    tmp = None
    try:
        try:
            fd, tmp_name = tempfile.mkstemp(
                prefix=f".{target.name}.",
                suffix=suffix if suffix is not None else ".tmp" + target.suffix,
                dir=target.parent,
            )
        except OSError as exc:
            raise _refuse(exc.errno or errno.EACCES, exc.strerror or "cannot write", target) from None
        os.close(fd)
        tmp = Path(tmp_name)
        _release_signals(held)
        yield tmp
        # mkstemp makes the file 0600; give it the mode a plain open() would.
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException:
        _release_signals(held)
        if tmp is not None:
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text_atomic(target, text: str, *, mkdir: bool = False) -> Path:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``target`` atomically and return the path.

    The folder must exist (it is created only when ``mkdir`` is true); see
    :func:`atomic_path` for what is refused.
    """
    target = Path(target)
    with atomic_path(target, mkdir=mkdir) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
    return target


def _strict(obj):
    """``obj`` with NaN and infinities as None, numpy values as Python ones, Fractions as "p/q"."""
    if isinstance(obj, dict):
        return {str(k): _strict(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_strict(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _strict(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        value = float(obj)
        return value if math.isfinite(value) else None
    if isinstance(obj, Fraction):
        return str(obj)
    return obj


def to_json(obj, indent: int | None = 2) -> str:
    """Strict JSON text of ``obj``: the one JSON writer of gearlever.

    Keys keep the order of the dicts given (insertion order); NaN and
    infinities become ``null`` (bare ``NaN`` is not JSON); numpy scalars and
    arrays become numbers and lists; a :class:`~fractions.Fraction` becomes
    the string ``"p/q"``.

    >>> to_json({"b": float("nan"), "a": [1.5, float("inf")]}, indent=None)
    '{"b": null, "a": [1.5, null]}'
    """
    return json.dumps(_strict(obj), indent=indent, allow_nan=False)


#: Largest input file read (model, network, way-point, torque files): 64 MiB
#: of text is far beyond any real model and still parses in seconds.
MAX_INPUT_BYTES = 64 * 2**20


def read_text_capped(path, what: str, cap: int = MAX_INPUT_BYTES) -> str:
    """The UTF-8 text of the input file ``path``: the one reader of user files.

    A leading UTF-8 byte-order mark (spreadsheets write one before CSV, some
    editors before TOML) is dropped, so every CSV and TOML reader of
    gearlever, all fed by this one, takes such a file as written.

    Refused with a :class:`~gearlever.errors.GearleverError` whose message
    starts with ``what`` (the user's flag or the file's role) and the path: a
    missing or unreadable file, anything but a regular file (a device such as
    ``/dev/zero`` or a pipe would never end), a file larger than ``cap``
    bytes, text that is not UTF-8.

    >>> read_text_capped("/dev/zero", "FILE")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: FILE '/dev/zero': must be a regular file (not a device, pipe or folder)
    """
    from gearlever.errors import GearleverError

    p = Path(path)
    try:
        if not p.is_file():
            if p.exists():
                raise GearleverError(f"{what} {str(path)!r}: must be a regular file (not a device, pipe or folder)")
            raise GearleverError(f"{what} {str(path)!r}: cannot be read: no such file")
        with open(p, "rb") as fh:
            data = fh.read(cap + 1)
    except OSError as exc:
        raise GearleverError(f"{what} {str(path)!r}: cannot be read: {exc.strerror or exc}") from None
    if len(data) > cap:
        raise GearleverError(f"{what} {str(path)!r}: larger than the cap of {cap:,} bytes")
    try:
        return data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError:
        raise GearleverError(f"{what} {str(path)!r}: not UTF-8 text") from None
