"""The CLI dispatcher: sub-commands are found, errors are one line with exit 2."""

import subprocess
import sys

import pytest

from gearlever.cli import main


def test_unknown_command_exits_2_with_one_line(capsys):
    assert main(["no-such-command"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    assert "invalid choice" in err


def test_missing_command_exits_2(capsys):
    assert main([]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_version_prints_and_exits_0(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.startswith("gearlever ")


def test_reproduce_is_registered(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["reproduce", "--help"])
    assert exc.value.code == 0
    assert "--tables" in capsys.readouterr().out


def test_python_dash_m_runs_without_traceback():
    proc = subprocess.run(
        [sys.executable, "-m", "gearlever", "no-such-command"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def _patch_mobility(monkeypatch, exc):
    """Make ``gearlever mobility`` raise ``exc`` from its handler."""
    import gearlever.cli.mobility as mobility

    def boom(args):
        raise exc

    monkeypatch.setattr(mobility, "_run", boom)
    return ["mobility", "--n", "1", "--p5", "1", "--p4", "0", "--q", "0"]


@pytest.mark.parametrize(
    ("exc", "status", "words"),
    [
        (PermissionError(13, "Permission denied", "/root/x.csv"), 2, ["/root/x.csv", "Permission denied"]),
        (IsADirectoryError(21, "Is a directory", "/tmp"), 2, ["/tmp", "Is a directory"]),
        (FileNotFoundError(2, "No such file or directory", "/no/such"), 2, ["/no/such", "No such file"]),
        (NotADirectoryError(20, "Not a directory", "/etc/hostname/x"), 2, ["/etc/hostname/x", "Not a directory"]),
        (OSError(5, "Input/output error", "/proc/1/mem"), 2, ["/proc/1/mem", "Input/output error"]),
        (ValueError("bad\nsecond line"), 2, ["gearlever: error: bad second line"]),
        (OverflowError("int too large to convert to float"), 2, ["out of range"]),
        (MemoryError(), 2, ["out of memory"]),
        (KeyboardInterrupt(), 130, ["interrupted"]),
        (ZeroDivisionError("division by zero"), 1, ["internal error", "ZeroDivisionError"]),
    ],
    ids=lambda v: type(v).__name__ if isinstance(v, BaseException) else None,
)
def test_every_error_is_one_line_with_its_status(capsys, monkeypatch, exc, status, words):
    monkeypatch.delenv("GEARLEVER_TRACEBACK", raising=False)
    argv = _patch_mobility(monkeypatch, exc)
    assert main(argv) == status
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err
    assert all(w in err for w in words), err


def test_broken_pipe_is_a_quiet_success(capsys, monkeypatch):
    argv = _patch_mobility(monkeypatch, BrokenPipeError(32, "Broken pipe"))
    monkeypatch.setattr(sys, "stdout", open(__import__("os").devnull, "w"))  # noqa: SIM115 - dup2 target
    assert main(argv) == 0
    assert capsys.readouterr().err == ""


def test_traceback_is_shown_for_internal_errors_only_when_asked(monkeypatch):
    monkeypatch.setenv("GEARLEVER_TRACEBACK", "1")
    argv = _patch_mobility(monkeypatch, ZeroDivisionError("x"))
    with pytest.raises(ZeroDivisionError):
        main(argv)


def test_a_library_message_is_given_the_users_flag(capsys):
    teeth = ["--n2", "30", "--n5", "24", "--n6", "18", "--n7", "36", "--n8", "20", "--n9", "25", "--n11", "40"]
    wp = ["chariot", "simulate", *teeth, "--step", "0.5"]
    assert main(wp) == 2
    assert capsys.readouterr().err.startswith("gearlever: error: --step ")


def test_mplbackend_defaults_to_agg(monkeypatch, capsys):
    monkeypatch.delenv("MPLBACKEND", raising=False)
    main(["mobility", "--n", "1", "--p5", "1", "--p4", "0", "--q", "0"])
    assert __import__("os").environ["MPLBACKEND"] == "Agg"
    assert capsys.readouterr().out.startswith("W = ")


class _Tty:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_progress_prints_on_a_terminal_only_and_erases_its_line():
    import time

    from gearlever.cli._common import progress

    term, pipe = _Tty(True), _Tty(False)
    for stream in (term, pipe):
        with progress("working", stream=stream, delay=0.0, interval=0.01):
            time.sleep(0.1)
    assert "working ... " in term.text and term.text.endswith("\r\x1b[K")
    assert pipe.text == ""


def test_capped_types_name_the_cap():
    import argparse

    from gearlever.cli._common import capped_float, capped_int

    assert capped_int(10**6)("1000000") == 10**6
    with pytest.raises(argparse.ArgumentTypeError, match="at most 10\\^6"):
        capped_int(10**6)("1000001")
    with pytest.raises(argparse.ArgumentTypeError, match="positive integer"):
        capped_int(10**6)("0")
    with pytest.raises(argparse.ArgumentTypeError, match="at most 2.5"):
        capped_float(2.5)("3")
    with pytest.raises(argparse.ArgumentTypeError, match="finite"):
        capped_float(2.5)("nan")
