"""The one progress protocol: ``progress(stage, done, total)``, and its terminal renderer.

Long library work (a tooth search, a synthesis, a library of topologies)
takes an optional ``progress`` callable and calls it between steps with the
stage's name, the steps done and the steps in all; it never prints.  Each
front end renders the calls its own way: the command line with
:class:`TerminalProgress` (one line on stderr, only at a terminal), the
workbench by forwarding them to its page.  :func:`null_progress` is the
reporter that does nothing.

A :class:`TerminalProgress` is also a context manager: around work that
reports nothing (drawing frames, integrating), ``with TerminalProgress("what"):``
shows the elapsed seconds after :data:`PROGRESS_DELAY` seconds, from a
daemon thread.  Nothing is printed when the stream is not a terminal
(pipes, files, tests); the line is erased at the end.

Imports only the standard library.

>>> def work(progress=null_progress):
...     for i in range(3):
...         progress("steps", i + 1, 3)
>>> seen = []
>>> work(lambda stage, done, total: seen.append(f"{stage} {done}/{total}"))
>>> seen
['steps 1/3', 'steps 2/3', 'steps 3/3']
"""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from typing import Protocol

__all__ = ["PROGRESS_DELAY", "Progress", "TerminalProgress", "null_progress"]

#: Seconds of work before a :class:`TerminalProgress` used as a context manager starts printing.
PROGRESS_DELAY = 2.0


class Progress(Protocol):
    """What long work calls between its steps: ``progress(stage, done, total)``."""

    def __call__(self, stage: str, done: int, total: int) -> None: ...


def null_progress(stage: str, done: int, total: int) -> None:
    """The reporter that reports nothing.

    >>> null_progress("search", 1, 10) is None
    True
    """


class TerminalProgress:
    """Progress on one line of a terminal (stderr by default), and nothing anywhere else.

    Parameters
    ----------
    label : str
        What is running (``"gearlever synthesize path"``).
    stream : file, optional
        Where to write (default :data:`sys.stderr` when created).
    delay, interval : float
        As a context manager: seconds before the elapsed time first shows, and
        between its updates.

    Calls ``(stage, done, total)`` write ``label: stage done/total``; inside
    ``with``, the elapsed seconds are shown until the end.  :meth:`close`
    (or leaving the ``with``) erases the line if anything was shown.

    Examples
    --------
    >>> import io
    >>> out = io.StringIO()  # not a terminal: nothing is written
    >>> with TerminalProgress("search", stream=out) as bar:
    ...     bar("pairs", 1, 2)
    >>> out.getvalue()
    ''
    """

    def __init__(self, label: str, stream=None, delay: float = PROGRESS_DELAY, interval: float = 1.0):
        self.label = label
        self.stream = sys.stderr if stream is None else stream
        self.delay = delay
        self.interval = interval
        try:
            self.active = bool(self.stream.isatty())
        except (AttributeError, ValueError):
            self.active = False
        self.shown = False
        self._lock = threading.Lock()
        self._done: threading.Event | None = None
        self._thread: threading.Thread | None = None

    def _write(self, text: str) -> None:
        with self._lock, contextlib.suppress(OSError, ValueError):
            self.stream.write(text)
            self.stream.flush()
            self.shown = True

    def __call__(self, stage: str, done: int, total: int) -> None:
        if self.active:
            self._write(f"\r{self.label}: {stage} {done}/{total}\033[K")

    def __enter__(self) -> TerminalProgress:
        if self.active:
            self._done = threading.Event()
            start = time.monotonic()

            def tick(done=self._done):
                if done.wait(self.delay):
                    return
                while not done.is_set():
                    self._write(f"\r{self.label} ... {time.monotonic() - start:.0f} s")
                    done.wait(self.interval)

            self._thread = threading.Thread(target=tick, name="gearlever-progress", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Stop the elapsed-time line (if running) and erase what was shown."""
        if self._done is not None:
            self._done.set()
            self._thread.join()
            self._done = self._thread = None
        if self.shown:
            with contextlib.suppress(OSError, ValueError):
                self.stream.write("\r\033[K")
                self.stream.flush()
            self.shown = False
