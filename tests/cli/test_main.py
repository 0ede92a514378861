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
