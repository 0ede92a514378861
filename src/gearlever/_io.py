"""Atomic file output: write to a temporary file beside the target, then rename.

No caller of gearlever is ever left with a half-written file: either the old
file (or none) is there, or the complete new one.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import json
import math
import numbers
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
    # leave it behind, between its creation and its removal).  The mask holds this thread only:
    # a signal the kernel hands to another thread (OpenBLAS's workers) still runs Python's
    # handler here, so the removal is also in a finally.
    with _signals_held():
        probe = None
        try:
            fd, probe = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".probe", dir=parent)
            os.close(fd)
        except OSError as exc:
            raise _refuse(exc.errno or errno.EACCES, f"cannot write in this folder: {exc.strerror}", target) from None
        finally:
            if probe is not None:
                with contextlib.suppress(OSError):
                    os.unlink(probe)
    return target


def _hold_signals():
    """Hold SIGTERM and SIGINT (main thread, where the platform allows); return what :func:`_release_signals` takes."""
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, (signal.SIGTERM, signal.SIGINT))


def _release_signals(old) -> None:
    """Restore the signal mask saved by :func:`_hold_signals` (a held signal is delivered now); idempotent."""
    if old is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


#: Depth of the critical sections open now, and the interruptions they hold back (see :func:`raise_or_defer`).
_CRITICAL = {"depth": 0, "pending": []}


def raise_or_defer(exc_type) -> None:
    """Raise ``exc_type()`` now, or at the end of the enclosing critical section (:func:`_signals_held`).

    The signal handlers of gearlever (SIGTERM, Ctrl-C) call this instead of
    raising.  The signal mask of :func:`_hold_signals` holds the main thread
    only: a signal the kernel hands to another thread (OpenBLAS's workers)
    still runs Python's handler in the main thread, between any two
    bytecodes, for instance between a temporary file's creation and the line
    that records it for removal.  Deferred to the end of the section, the
    exception is raised where the file is known and cleaned up.
    """
    if _CRITICAL["depth"] > 0:
        _CRITICAL["pending"].append(exc_type)
        return
    _CRITICAL["pending"].clear()  # raised now: nothing held back is left to raise later
    _interrupt_outputs()
    raise exc_type()


def _interrupt_outputs() -> None:
    """Abort the active :class:`OutputSet` before an interruption is raised, and mark it interrupted.

    The exception may land anywhere, even in a ``finally`` before its first
    line or in a finalizer that swallows it: the temporary files and new
    folders are removed here, by the handler, not by the code it unwinds.
    An interrupted set is never joined again (:func:`output_set`).
    """
    outputs = _ACTIVE.get()
    if outputs is not None:
        outputs.interrupted = True
        outputs.abort()


@contextlib.contextmanager
def _signals_held():
    """Hold SIGTERM and SIGINT for a short critical section: masked, and deferred by :func:`raise_or_defer`.

    The section is open (deferral on) before the mask is set and until after
    it is restored, so there is no bytecode between the two where a handler
    could raise (a held signal is delivered when the mask is restored, and
    deferred too); the interruption held back is raised last.
    """
    _CRITICAL["depth"] += 1
    old = None
    try:
        old = _hold_signals()
        yield
    finally:
        try:
            _release_signals(old)
        finally:
            _CRITICAL["depth"] -= 1
            if _CRITICAL["depth"] == 0 and _CRITICAL["pending"]:
                pending = _CRITICAL["pending"][0]
                _CRITICAL["pending"].clear()
                _interrupt_outputs()
                raise pending()


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
    # the probe is made and removed with SIGTERM and Ctrl-C held (as in check_target)
    with _signals_held():
        probe = None
        try:
            fd, probe = tempfile.mkstemp(prefix=".gearlever.", suffix=".probe", dir=existing)
            os.close(fd)
        except OSError as exc:
            raise _refuse(exc.errno or errno.EACCES, f"cannot write in this folder: {exc.strerror}", existing) from None
        finally:
            if probe is not None:
                with contextlib.suppress(OSError):
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
        raise_or_defer(_Terminated)

    old = signal.SIG_DFL
    try:
        old = signal.signal(signal.SIGTERM, handler)
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
    as it was.  A symbolic link is replaced by the new file, not followed
    (the file it points to is left alone).  A write error (a full disk) is
    an :class:`OSError` naming ``target``, not the temporary file.

    Inside :func:`output_set` the rename waits for the set's commit, so that
    several files are written all or none (see :class:`OutputSet`); alone,
    the write is a set of one.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "x.txt") as tmp:
    ...     _ = tmp.write_text("hi")
    >>> (d / "x.txt").read_text()
    'hi'
    """
    with output_set() as outputs:
        with outputs.stage(target, suffix=suffix, mkdir=mkdir) as tmp:
            yield tmp


#: The :class:`OutputSet` that :func:`atomic_path` stages into (None: each write is its own set).
_ACTIVE: contextvars.ContextVar = contextvars.ContextVar("gearlever_output_set", default=None)


def current_outputs() -> OutputSet | None:
    """The :class:`OutputSet` of the enclosing :func:`output_set`, or None (also when it was interrupted)."""
    outputs = _ACTIVE.get()
    return None if outputs is None or outputs.interrupted else outputs


@contextlib.contextmanager
def output_set():
    """Write every file of the body all or none: yield the :class:`OutputSet` the writes are staged in.

    Every :func:`atomic_path` (so :func:`write_text_atomic`, the figure and
    table writers) inside the body writes a temporary file beside its target;
    when the body ends normally all of them are renamed onto their targets
    (:meth:`OutputSet.commit`); when it raises, or the process gets SIGTERM or
    Ctrl-C, every temporary file and every folder the set created is removed
    and no target is touched.  Nested sets join the outermost one.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> try:
    ...     with output_set():
    ...         _ = write_text_atomic(d / "a.txt", "a")
    ...         raise RuntimeError("the second file failed")
    ... except RuntimeError:
    ...     pass
    >>> sorted(p.name for p in d.iterdir())
    []
    """
    outer = _ACTIVE.get()
    if outer is not None and not outer.interrupted:
        yield outer
        return
    outputs = OutputSet()
    try:
        _ACTIVE.set(outputs)
        with _sigterm_unwinds():
            try:
                yield outputs
                outputs.commit()
            except BaseException:
                outputs.abort()
                raise
    finally:
        # never left active (an interruption right after the set would otherwise leave later writes staged in it)
        if _ACTIVE.get() is outputs:
            _ACTIVE.set(None)


def _identity(path: Path) -> frozenset:
    """What makes two outputs one file: the directory entry (folders resolved), the file a link names, the inode."""
    keys = {("entry", os.path.realpath(path.parent), path.name)}
    if path.is_symlink():
        keys.add(("entry", *os.path.split(os.path.realpath(path))))
    try:
        st = os.stat(path)
    except OSError:
        pass
    else:
        keys.add(("inode", st.st_dev, st.st_ino))
    return frozenset(keys)


def named_error(flag: str | None, path, exc: OSError, what: str = ""):
    """One line for a refused output: ``--report 'r.json': cannot write: No space left on device``.

    A :class:`~gearlever.errors.GearleverError` naming ``flag`` and ``path``
    (with ``exc.filename`` when it is another path, e.g. the folder); with no
    flag, an :class:`OSError` of the same errno (so the same subclass) naming
    the path (the target, never a temporary file).

    >>> import errno
    >>> named_error("--report", "r.json", OSError(errno.ENOSPC, "No space left on device"), "cannot write")
    GearleverError("--report 'r.json': cannot write: No space left on device")
    """
    from gearlever.errors import GearleverError

    reason = exc.strerror or str(exc) or type(exc).__name__
    reason = f"{what}: {reason}" if what and not reason.startswith(what) else reason
    where = str(path)
    if flag is None:
        return OSError(exc.errno, reason, exc.filename if exc.filename and not what else where)
    culprit = f" (at {exc.filename!r})" if exc.filename and str(exc.filename) != where else ""
    return GearleverError(f"{flag} {where!r}: {reason}{culprit}")


def _over_input(entry, what: str, text: str):
    """The refusal of an output that would replace an input file of the same command (names both)."""
    from gearlever.errors import GearleverError

    out = f"{entry.flag} {entry.text!r}" if entry.flag else repr(entry.text)
    return GearleverError(
        f"{out} is the input {what} {text!r}: an output may not replace an input; give it another name"
    )


class _Output:
    """One declared output: its flag, path, identity keys and, once written, its temporary file."""

    __slots__ = ("flag", "path", "text", "keys", "tmp")

    def __init__(self, flag, path, text, keys):
        self.flag, self.path, self.text, self.keys, self.tmp = flag, path, text, keys, None


class OutputSet:
    """Several output files written all or none: the one transaction of gearlever's writers.

    Declare every output first (:meth:`declare`, :meth:`declare_folder`):
    each is checked at once, before any work (:func:`check_target`, the
    suffixes its flag takes), and two outputs that are one file are refused
    naming both flags: the same path spelt twice (``./x`` and ``x``), a
    symbolic link and the file it names, two hard links.  Then write them
    (:meth:`stage`, or any :func:`atomic_path` inside :func:`output_set`):
    each goes to a temporary file beside its target.  :meth:`commit` renames
    them all; :meth:`abort` removes every temporary file and every folder the
    set created.  A symbolic link is replaced, never followed.  Errors name
    the output's flag (or its folder's flag), the path and the reason, in one
    line (:class:`~gearlever.errors.GearleverError`; without a flag, an
    :class:`OSError` naming the path).

    Notes
    -----
    POSIX renames one file atomically, not several: :meth:`commit` renames
    them one after the other with SIGTERM and Ctrl-C held, and if a rename
    fails, the targets already replaced get their old file back (kept as a
    hard link until the end, where the file system has hard links) and the
    new ones are removed.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> outs = OutputSet()
    >>> _ = outs.declare(d / "m.toml", "--out")
    >>> outs.declare(d / "." / "m.toml", "--report")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: --report '...m.toml' and --out '...m.toml' are the same file: give each its own
    """

    def __init__(self):
        self._outputs: list[_Output] = []
        self._folders: list[tuple] = []  # (flag, resolved folder)
        self._made: list[Path] = []  # folders created by this set, outermost first
        self._inputs: list[tuple] = []  # (what, text, identity keys) of every input file read
        self.written: list[Path] = []
        self.interrupted = False  # aborted by SIGTERM or Ctrl-C (see raise_or_defer): never joined again

    # -- inputs ----------------------------------------------------------------
    def note_input(self, path, what: str) -> None:
        """Record that the command read the input file ``path`` (its role ``what``): no output may replace it.

        Refused at once if a declared output already names the same file, and
        again at :meth:`commit` for outputs declared later (the same path
        spelt another way, a symbolic link to it, a hard link).
        """
        text = os.fspath(path)
        keys = _identity(Path(path))
        self._inputs.append((what, text, keys))
        for e in self._outputs:
            if e.keys & keys:
                raise _over_input(e, what, text)

    def _check_inputs(self, entry: _Output) -> None:
        keys = entry.keys | _identity(entry.path)
        for what, text, ikeys in self._inputs:
            if keys & ikeys:
                raise _over_input(entry, what, text)

    # -- declaring -------------------------------------------------------------
    def _label(self, flag, path) -> str | None:
        """``flag``, else the flag of a declared folder holding ``path``."""
        if flag is not None:
            return flag
        parent = os.path.realpath(Path(path).parent)
        for f, folder in self._folders:  # a loop, not a generator left to be closed by the collector, where an
            if folder == parent and f is not None:  # interruption would be "ignored" (lost)
                return f
        return None

    def declare(self, path, flag: str | None = None, *, suffixes=None, mkdir: bool = False) -> Path:
        """Check the output ``path`` of ``flag`` now, before any work; return it as a :class:`~pathlib.Path`.

        ``suffixes`` (e.g. ``("png", "svg")``) are the file name endings the
        flag takes.  Refused: a path :func:`check_target` refuses, another
        suffix, a file another output of the set already names.  Declaring
        the same path for the same flag again is allowed.
        """
        text, path = os.fspath(path), Path(path)
        if suffixes is not None and path.suffix.lower().lstrip(".") not in suffixes:
            from gearlever.errors import GearleverError

            ends = ", ".join("." + s for s in suffixes)
            ends = " or ".join(ends.rsplit(", ", 1))
            raise GearleverError(f"{flag or 'output'} must end with {ends}, got {text!r}")
        if mkdir and not path.parent.exists():
            self._make_folder(path.parent, self._label(flag, path))
        try:
            check_target(path)
        except OSError as exc:
            raise named_error(self._label(flag, path), text, exc) from None
        return self._entry(path, flag, text).path

    def _entry(self, path: Path, flag, text: str) -> _Output:
        keys = _identity(path)
        for e in self._outputs:
            if e.keys & keys:
                if flag in (e.flag, None) and os.path.abspath(e.path) == os.path.abspath(path):
                    return e  # declared again, or written by a writer that does not know the flag
                from gearlever.errors import GearleverError

                flag = self._label(flag, path)
                if e.flag == flag:
                    raise GearleverError(f"{flag or 'output'}: {text!r} and {e.text!r} are the same file")
                a = f"{flag} {text!r}" if flag else repr(text)
                b = f"{e.flag} {e.text!r}" if e.flag else repr(e.text)
                raise GearleverError(f"{a} and {b} are the same file: give each its own")
        e = _Output(self._label(flag, path), path, text, keys)
        self._outputs.append(e)
        return e

    def declare_folder(self, folder, flag: str | None = None, *, create: bool = True) -> Path:
        """Check the output folder ``folder`` of ``flag`` (and create it, with its parents, when ``create``).

        A folder this set creates is removed again if the set is aborted.
        Files written into it later are named by ``flag`` in errors.
        """
        folder = Path(folder)
        try:
            check_folder(folder)
            if not folder.exists():
                if not create:
                    raise _refuse(errno.ENOENT, "folder does not exist", folder)
                self._make_folder(folder, flag)
        except OSError as exc:
            raise named_error(flag, folder, exc) from None
        resolved = os.path.realpath(folder)
        if resolved not in [f for _, f in self._folders]:
            self._folders.append((flag, resolved))
        return folder

    def _make_folder(self, folder: Path, flag) -> None:
        missing = []
        up = folder
        while not up.exists() and up.parent != up:
            missing.append(up)
            up = up.parent
        try:
            check_folder(folder)
            for m in reversed(missing):
                with _signals_held():  # a folder is recorded (so removed by abort) as soon as it is made
                    m.mkdir()
                    self._made.append(m)
        except OSError as exc:
            raise named_error(flag, folder, exc) from None

    # -- writing ---------------------------------------------------------------
    @contextlib.contextmanager
    def stage(self, target, flag: str | None = None, *, suffix: str | None = None, mkdir: bool = False):
        """Yield a temporary path beside ``target`` to write; it replaces ``target`` at :meth:`commit`.

        ``target`` is declared first if it was not (see :meth:`declare`); a
        target written twice in one set is refused.  If the body raises the
        temporary file is removed; an :class:`OSError` of the body (a full
        disk) becomes an error naming the flag and ``target``.
        """
        text, target = os.fspath(target), Path(target)
        if mkdir and not target.parent.exists():
            self._make_folder(target.parent, self._label(flag, target))
        try:
            check_target(target)
        except OSError as exc:
            raise named_error(self._label(flag, target), text, exc) from None
        entry = self._entry(target, flag, text)
        if entry.tmp is not None:
            from gearlever.errors import GearleverError

            raise GearleverError(f"{entry.flag or 'output'} {entry.text!r}: written twice by one command")
        try:
            # SIGTERM and Ctrl-C wait until the temporary file is known (they are raised at the end of the
            # section, inside this try), so that it is removed
            with _signals_held():
                try:
                    fd, name = tempfile.mkstemp(
                        prefix=f".{target.name}.",
                        suffix=suffix if suffix is not None else ".tmp" + target.suffix,
                        dir=target.parent,
                    )
                except OSError as exc:
                    raise named_error(entry.flag, entry.text, exc, "cannot write") from None
                os.close(fd)
                entry.tmp = Path(name)
            yield entry.tmp
        except OSError as exc:
            self._drop(entry)
            raise named_error(entry.flag, entry.text, exc, "cannot write") from None
        except BaseException:
            self._drop(entry)
            raise

    def _drop(self, entry: _Output) -> None:
        if entry.tmp is not None:
            with contextlib.suppress(OSError):
                entry.tmp.unlink()
            entry.tmp = None

    # -- ending ----------------------------------------------------------------
    def commit(self) -> list[Path]:
        """Rename every staged file onto its target; return the targets written (in the order declared).

        On failure the targets already replaced are restored, every
        temporary file is removed and the error names the flag.
        """
        staged = [e for e in self._outputs if e.tmp is not None]
        try:
            for e in staged:
                self._check_inputs(e)
        except BaseException:
            self.abort()
            raise
        done: list[tuple] = []  # (entry, backup or None, existed)
        mode = 0o666 & ~_umask()  # mkstemp makes 0600; give the mode a plain open() would
        with _signals_held():
            try:
                for i, e in enumerate(staged):
                    os.chmod(e.tmp, mode)
                    existed = os.path.lexists(e.path)
                    # the last rename needs no way back: if it fails its target is untouched
                    backup = _backup(e.path) if existed and i < len(staged) - 1 else None
                    try:
                        os.replace(e.tmp, e.path)
                    except BaseException:
                        if backup is not None:
                            with contextlib.suppress(OSError):
                                backup.unlink()
                        raise
                    e.tmp = None
                    done.append((e, backup, existed))
            except BaseException as exc:
                for e, backup, existed in reversed(done):
                    with contextlib.suppress(OSError):
                        if backup is not None:
                            os.replace(backup, e.path)
                        elif not existed:
                            e.path.unlink()
                self.abort()
                if isinstance(exc, OSError):
                    e = staged[len(done)]
                    raise named_error(e.flag, e.text, exc, "cannot write") from None
                raise
            # still held: a signal that came during the renames is raised once the backups are gone too
            for _, backup, _ in done:
                if backup is not None:
                    with contextlib.suppress(OSError):
                        backup.unlink()
        written = [e.path for e, _, _ in done]
        self.written.extend(written)
        self._outputs.clear()
        self._made.clear()
        return written

    def abort(self) -> None:
        """Remove every temporary file and every (empty) folder this set created; forget the staged files.

        SIGTERM and Ctrl-C wait until all of them are gone (an interruption
        halfway through would leave the rest).
        """
        with _signals_held():
            for e in self._outputs:
                self._drop(e)
            for folder in reversed(self._made):
                with contextlib.suppress(OSError):
                    folder.rmdir()
            self._outputs.clear()
            self._made.clear()


def _backup(path: Path) -> Path | None:
    """A hard link to ``path`` (a link itself, not followed) under a hidden name beside it, or None."""
    for _ in range(100):
        name = path.parent / f".{path.name}.{os.urandom(4).hex()}.old"
        try:
            os.link(path, name, follow_symlinks=False)
        except FileExistsError:
            continue
        except OSError:
            return None
        return name
    return None


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text_atomic(target, text: str, *, mkdir: bool = False, flag: str | None = None) -> Path:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``target`` atomically and return the path.

    The folder must exist (it is created only when ``mkdir`` is true); see
    :func:`atomic_path` for what is refused.  ``flag`` names the output in
    errors (see :class:`OutputSet`).
    """
    target = Path(target)
    with output_set() as outputs, outputs.stage(target, flag, mkdir=mkdir) as tmp:
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
    outputs = _ACTIVE.get()
    if outputs is not None:
        outputs.note_input(p, what)
    try:
        return data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError:
        raise GearleverError(f"{what} {str(path)!r}: not UTF-8 text") from None


def read_json_capped(path, what: str, where: str | None = None):
    """The JSON value of the input file ``path``, read by :func:`read_text_capped` (``what``, the cap).

    Text that is not JSON, or JSON nested too deeply for Python's parser, is
    refused with a :class:`~gearlever.errors.GearleverError` whose message
    starts with ``where`` (default: ``what`` and the path, as the refusals of
    :func:`read_text_capped`).

    >>> import pathlib, tempfile
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "d.json"
    >>> _ = p.write_text('{"x0": [[0, 0]],')
    >>> read_json_capped(p, "DESIGN", where="d.json")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: d.json: not JSON (Expecting property name enclosed in double quotes, line 1)
    """
    from gearlever.errors import GearleverError

    if where is None:
        where = f"{what} {str(path)!r}"
    text = read_text_capped(path, what)
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise GearleverError(f"{where}: not JSON ({exc.msg}, line {exc.lineno})") from None
    except RecursionError:
        raise GearleverError(f"{where}: JSON nested too deeply") from None


def did_you_mean(word, names) -> str:
    """`` (did you mean 'x'?)`` for the name of ``names`` closest to ``word``, or ``""``.

    >>> did_you_mean("segments", ("output", "segment"))
    " (did you mean 'segment'?)"
    """
    import difflib

    close = difflib.get_close_matches(str(word), list(names), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def read_toml_table(path, what: str, table: str, keys, missing: str = "") -> dict:
    """The table ``[table]`` of the TOML file ``path`` (read by :func:`read_text_capped` as ``what``).

    Refused with a :class:`~gearlever.errors.GearleverError` whose message
    starts with the path: text that is not TOML, no ``[table]`` table (the
    message ends with ``missing``, a hint), a key of the table not in ``keys``
    (with the closest known key).

    >>> import pathlib, tempfile
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "law.toml"
    >>> _ = p.write_text('[law]\\nsegments = []\\n')
    >>> read_toml_table(p, "LAW", "law", ("output", "segment"))
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: ...law.toml: [law] has unknown key 'segments' (did you mean 'segment'?)
    """
    import tomllib

    from gearlever.errors import GearleverError

    source = str(path)
    text = read_text_capped(Path(path), what)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise GearleverError(f"{source}: not valid TOML: {exc}") from None
    except RecursionError:
        # tomllib parses nested arrays and inline tables recursively
        raise GearleverError(f"{source}: arrays or tables nested too deeply") from None
    found = data.get(table)
    if not isinstance(found, dict):
        raise GearleverError(f"{source}: a [{table}] table is missing{missing}")
    for key in found:
        if key not in keys:
            raise GearleverError(f"{source}: [{table}] has unknown key {key!r}{did_you_mean(key, keys)}")
    return found


class CsvTable:
    """The rows of a CSV file read by :func:`read_csv_table`, each with its line in the file.

    Attributes
    ----------
    where : str
        The file as errors name it (``PAIRS 'p.csv'``).
    header : list of str
        The column names (stripped), empty when the file has no header row.
    rows : list of list of str
        The cells of each data row, as written.
    lines : list of int
        The line of each data row in the file (1-based), for error messages.
    """

    def __init__(self, where: str, header: list, rows: list, lines: list):
        self.where, self.header, self.rows, self.lines = where, header, rows, lines

    def __len__(self) -> int:
        return len(self.rows)

    def number(self, k: int, column: int, name: str | None = None, finite: bool = True) -> float:
        """The cell of row ``k`` in ``column`` as a (finite) float, or the one refusal naming the line and column.

        With ``finite=False``, ``nan`` and ``inf`` are returned for the caller to refuse
        (a law's samples, refused with their row among the samples).

        >>> t = CsvTable("PAIRS 'p.csv'", ["x"], [["1.5"], ["abc"]], [2, 3])
        >>> t.number(0, 0)
        1.5
        >>> t.number(1, 0)
        Traceback (most recent call last):
        ...
        gearlever.errors.GearleverError: PAIRS 'p.csv' row 3 column x: not a number ('abc')
        """
        from gearlever.errors import GearleverError

        row = self.rows[k]
        name = name if name is not None else (self.header[column] if column < len(self.header) else str(column + 1))
        cell = row[column].strip() if column < len(row) else ""
        at = f"{self.where} row {self.lines[k]} column {name}"
        try:
            v = float(cell)
        except ValueError:
            raise GearleverError(f"{at}: not a number ({cell!r})") from None
        if finite and not math.isfinite(v):
            raise GearleverError(f"{at}: must be finite, got {cell!r}")
        return v

    def columns(self, names, finite: bool = True) -> dict[str, list[float]]:
        """The named columns as lists of (finite) floats (:meth:`number` refuses a bad cell)."""
        index = {n: self.header.index(n) for n in names}
        return {n: [self.number(k, j, n, finite) for k in range(len(self.rows))] for n, j in index.items()}

    def only(self, accepted, least: int) -> CsvTable:
        """This table held to the package's one rule for the columns of a user's CSV file.

        The rule, the same for every CSV a user gives (path targets, curve
        targets, a law's samples): a header row is optional; with one, it
        names only ``accepted`` columns (any order, case ignored) and at least
        the first ``least`` of them; without one, the values are the
        ``accepted`` columns in order, at least ``least`` of them.  A row with
        more values than the columns is refused with its line (a silently
        dropped column is a silently wrong result); trailing empty cells (a
        spreadsheet's extra commas) are not values.

        Returns the table with its header set (positional names when the file
        had none) and the trailing empty cells removed.

        >>> t = CsvTable("T", [], [["1", "2", ""], ["3", "4"]], [1, 2]).only(("x", "y", "input_deg"), 2)
        >>> t.header, t.rows
        (['x', 'y'], [['1', '2'], ['3', '4']])
        >>> CsvTable("T", ["x", "y", "z"], [["1", "2", "3"]], [2]).only(("x", "y"), 2)
        Traceback (most recent call last):
        ...
        gearlever.errors.GearleverError: T: unknown column 'z' in the header (the columns are x, y)
        >>> CsvTable("T", ["x", "y"], [["1", "2", "3"]], [2]).only(("x", "y"), 2)
        Traceback (most recent call last):
        ...
        gearlever.errors.GearleverError: T line 2: 3 values, but the columns are x, y
        """
        from gearlever.errors import GearleverError

        accepted = list(accepted)
        described = ", ".join(accepted[:least])
        if len(accepted) > least:
            described += " and optionally " + ", ".join(accepted[least:])
        rows = []
        for r in self.rows:
            r = list(r)
            while r and not r[-1].strip():
                r.pop()
            rows.append(r)
        if self.header:
            header = [c.strip().lower() for c in self.header]
            for name in header:
                if name not in accepted:
                    raise GearleverError(
                        f"{self.where}: unknown column {name!r} in the header (the columns are {described})"
                    )
            seen = set()
            for name in header:
                if name in seen:
                    raise GearleverError(f"{self.where}: column {name!r} appears twice in the header")
                seen.add(name)
            missing = [n for n in accepted[:least] if n not in header]
            if missing:
                raise GearleverError(
                    f"{self.where}: the header must name columns {described}, got {','.join(self.header)}"
                )
        else:
            width = min(len(rows[0]), len(accepted)) if rows else least
            if width < least:
                raise GearleverError(
                    f"{self.where} line {self.lines[0]}: {len(rows[0])} value(s), but the columns are {described}"
                )
            header = accepted[:width]
        for r, line in zip(rows, self.lines):
            if len(r) > len(header):
                columns = ", ".join(header)
                raise GearleverError(f"{self.where} line {line}: {len(r)} values, but the columns are {columns}")
        return CsvTable(self.where, header, rows, self.lines)


def read_csv_table(
    path,
    what: str,
    *,
    columns=(),
    header: bool | None = True,
    comments: bool = False,
    max_rows: int | None = None,
    cap: int = MAX_INPUT_BYTES,
    where: str | None = None,
) -> CsvTable:
    """The one CSV reader of the package: a capped read, the :mod:`csv` module's quoting, one wording of refusals.

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        What the file is to the user (``"PAIRS"``, ``"--torque-file"``): named in
        every refusal, with the path, as ``where`` (default ``f"{what} {path!r}"``).
    columns : sequence of str
        Columns the header must name (refused otherwise, with the header found).
    header : bool or None
        True: the first row names the columns; False: there is no header row;
        None: the first row is a header when its first cell is not a number.
    comments : bool
        Skip rows whose first cell starts with ``#``.  Blank rows are always skipped.
    max_rows : int, optional
        Most data rows (refused beyond, without reading on).
    cap : int
        Most bytes read (:func:`read_text_capped`).

    Returns
    -------
    CsvTable

    Raises
    ------
    GearleverError
        The file missing, unreadable, too large, not UTF-8; a column missing;
        more than ``max_rows`` rows.  Cells are checked by the caller
        (:meth:`CsvTable.number` for numbers), every refusal naming ``where``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "pairs.csv"
    >>> _ = p.write_text("input_deg,output_deg\\n10,20\\n\\n30,40\\n")
    >>> t = read_csv_table(p, "PAIRS", columns=("input_deg", "output_deg"), where="PAIRS")
    >>> t.header, t.lines, t.columns(["output_deg"])
    (['input_deg', 'output_deg'], [2, 4], {'output_deg': [20.0, 40.0]})
    >>> read_csv_table(p, "PAIRS", columns=("input_deg", "out"), where="PAIRS")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: PAIRS: missing column(s) out (header: input_deg,output_deg)
    """
    where = f"{what} {str(path)!r}" if where is None else where
    text = read_text_capped(path, what, cap)
    return csv_table(text, where, columns=columns, header=header, comments=comments, max_rows=max_rows)


def csv_table(
    text: str, where: str, *, columns=(), header: bool | None = True, comments: bool = False, max_rows=None
) -> CsvTable:
    """The :class:`CsvTable` of CSV ``text`` already read (package data); see :func:`read_csv_table`.

    >>> csv_table("# source\\nx,y\\n1,2\\n", "data", comments=True).rows
    [['1', '2']]
    """
    import csv
    import io

    from gearlever.errors import GearleverError

    reader = csv.reader(io.StringIO(text))
    rows, lines = [], []
    head: list | None = None if header is not False else []
    for record in reader:
        if not any(c.strip() for c in record):
            continue
        if comments and record[0].lstrip().startswith("#"):
            continue
        if head is None:
            is_header = True
            if header is None:
                try:
                    float(record[0])
                    is_header = False
                except ValueError:
                    pass
            if is_header:
                head = [c.strip() for c in record]
                continue
            head = []
        if max_rows is not None and len(rows) >= max_rows:
            raise GearleverError(f"{where}: more than {max_rows} rows")
        rows.append(record)
        lines.append(reader.line_num)
    head = head or []
    missing = [c for c in columns if c not in head]
    if missing:
        hint = did_you_mean(missing[0], head) if len(missing) == 1 else ""
        raise GearleverError(f"{where}: missing column(s) {', '.join(missing)} (header: {','.join(head)}){hint}")
    return CsvTable(where, head, rows, lines)


def _error(message: str):
    from gearlever.errors import GearleverError

    return GearleverError(message)


def _settled_column(col: list, digits: int) -> list:
    """The floats of one column quantized to ``digits`` of its largest finite magnitude."""
    from gearlever._format import quantize_in_column

    vals = [abs(float(v)) for v in col if isinstance(v, numbers.Real) and not isinstance(v, bool)]
    vals = [v for v in vals if math.isfinite(v)]
    scale = max(vals) if vals else 0.0

    def q(v):
        if isinstance(v, bool) or not isinstance(v, numbers.Real) or isinstance(v, numbers.Integral):
            return v
        return quantize_in_column(v, scale, digits)

    return [q(v) for v in col]


def table_text(cols: dict, fmt: str = "csv", meta: dict | None = None, digits: int = 12) -> str:
    """Columns of equal length as CSV (the :mod:`csv` module: fields quoted as needed) or strict JSON.

    ``cols`` maps a column name to a sequence: numbers, bools (1/0 in CSV)
    or strings (quoted in CSV when they hold a comma, quote or newline).
    The numbers are written to ``digits`` significant digits, never finer
    than ``digits + 2`` digits of their column's largest magnitude
    (:func:`gearlever._format.quantize_in_column`: a value that is zero up to
    rounding is written 0, the same text on every machine).  JSON
    is ``{**meta, "rows": [{name: value, ...}, ...]}`` with NaN and
    infinities as null, the numbers as in the CSV.  The one writer of tabular
    output for every sub-command.

    >>> print(table_text({"x": [0.5, 2.0], "reason": ["", "dead point: a, b"]}))
    x,reason
    0.5,
    2,"dead point: a, b"
    """
    import csv
    import io

    from gearlever._format import format_number

    names = list(cols)
    columns = [list(cols[k].tolist() if hasattr(cols[k], "tolist") else cols[k]) for k in names]
    lengths = {len(c) for c in columns}
    if len(lengths) > 1:
        raise _error(f"table columns differ in length: {dict(zip(names, map(len, columns)))}")
    columns = [_settled_column(c, digits) for c in columns]
    rows = list(zip(*columns)) if columns else []
    if fmt == "json":
        recs = [dict(zip(names, row)) for row in rows]
        return to_json({**(meta or {}), "rows": recs})
    if fmt != "csv":
        raise _error(f"format must be 'csv' or 'json', got {fmt!r}")

    def cell(v):
        if isinstance(v, bool):
            return str(int(v))
        if isinstance(v, numbers.Real):
            return format_number(v, digits)
        return "" if v is None else str(v)

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(names)
    for row in rows:
        w.writerow([cell(v) for v in row])
    return buf.getvalue().rstrip("\n")
