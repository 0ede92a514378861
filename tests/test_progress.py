"""The one progress protocol (gearlever._progress): the calls, the terminal renderer, silence elsewhere."""

import io
import time

from gearlever._progress import Progress, TerminalProgress, null_progress
from gearlever.trains.search import search_best


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_library_work_calls_progress_with_stage_done_total():
    calls = []
    search_best("191/23", 2, 24, 60, progress=lambda stage, done, total: calls.append((stage, done, total)))
    assert calls and all(isinstance(s, str) and 0 <= d <= t for s, d, t in calls)


def test_null_progress_and_a_renderer_are_progress_reporters():
    def takes(p: Progress) -> None:
        p("stage", 1, 2)

    takes(null_progress)
    takes(TerminalProgress("x", stream=io.StringIO()))


def test_terminal_renderer_writes_one_line_and_erases_it():
    out = _Tty()
    bar = TerminalProgress("gearlever train search", stream=out)
    bar("searching", 3, 10)
    bar.close()
    assert out.getvalue() == "\rgearlever train search: searching 3/10\x1b[K\r\x1b[K"


def test_context_manager_shows_elapsed_seconds_after_the_delay_only_at_a_terminal():
    out = _Tty()
    with TerminalProgress("drawing", stream=out, delay=0.0, interval=0.01):
        time.sleep(0.1)
    assert out.getvalue().startswith("\rdrawing ... 0 s") and out.getvalue().endswith("\r\x1b[K")
    quiet = _Tty()
    with TerminalProgress("drawing", stream=quiet, delay=60.0):
        pass
    assert quiet.getvalue() == ""
    pipe = io.StringIO()
    with TerminalProgress("drawing", stream=pipe, delay=0.0, interval=0.01) as bar:
        bar("stage", 1, 1)
        time.sleep(0.05)
    assert pipe.getvalue() == ""
