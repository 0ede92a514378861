"""Outputs: unwritable --out, --tables, --figures are refused with exit 2 and one line, before any work.

Read-only files cannot be made with chmod here (the tests run as root, for
whom permission bits do not refuse), so the unwritable places are ``/proc``,
a directory, a path under a regular file and a folder that does not exist.
"""

import subprocess
import sys
from pathlib import Path

import pytest

from gearlever.cli import main

TEETH = ["--n2", "30", "--n5", "24", "--n6", "18", "--n7", "36", "--n8", "20", "--n9", "25", "--n11", "40"]
NETWORK = "a,gear,20\nb,gear,40\nab,mesh,a,b\n"

COMMANDS = {
    "chariot-nuttall": ["chariot", "nuttall", *TEETH],
    "chariot-simulate": ["chariot", "simulate", *TEETH, "--turns", "1"],
    "differential": [
        "differential",
        "car",
        "--pinion-teeth",
        "11",
        "--ring-teeth",
        "41",
        "--pinion-speed",
        "1",
        "--pinion-torque",
        "1",
    ],
    "zrdpm": ["zrdpm", "--contour", "1"],
    "hooke": ["hooke", "--shaft-angle", "30"],
    "train-ratio": ["train", "ratio", "--drivers", "20", "--followers", "60"],
    "fourbar": ["fourbar", "--ground", "9", "--crank", "5", "--coupler", "8", "--rocker", "8"],
    "network": ["network", "{network}", "--inputs", "a"],
    "animate": ["animate", "--fourbar", "9", "5", "8", "8", "--frames", "4"],
}


def unwritable(work):
    """The unwritable --out targets by kind."""
    return {
        "proc": "/proc/x.csv",
        "directory": str(work),
        "under-a-file": "/etc/hostname/x.csv",
        "missing-folder": str(work / "missing" / "x.csv"),
        "device": "/dev/null",
        "empty": "",
    }


KINDS = ["proc", "directory", "under-a-file", "missing-folder", "device", "empty"]


def run(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def _argv(command, tmp_path):
    net = tmp_path / "net.csv"
    net.write_text(NETWORK)
    return [a.replace("{network}", str(net)) for a in COMMANDS[command]]


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_unwritable_out_exits_2_with_one_line_naming_the_path(capsys, tmp_path, command, kind):
    work = tmp_path / "work"
    work.mkdir()
    argv = _argv(command, tmp_path)
    target = unwritable(work)[kind]
    if command == "animate" and target.endswith(".csv"):
        target = target[:-4] + ".gif"
    before = sorted(p.name for p in work.rglob("*"))
    code, out, err = run(capsys, [*argv, "--out", target])
    assert code == 2, err
    assert out == ""
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "--out" in err and repr(target) in err
    # nothing written, no temporary left behind, no folder created
    assert sorted(p.name for p in work.rglob("*")) == before
    assert not (work / "missing").exists()


@pytest.mark.parametrize("command", ["chariot-nuttall", "differential", "hooke", "fourbar"])
def test_good_out_is_written_whole_and_alone(capsys, tmp_path, command):
    target = tmp_path / "o" / "result.txt"
    target.parent.mkdir()
    code, out, err = run(capsys, [*_argv(command, tmp_path), "--out", str(target)])
    assert (code, out, err) == (0, "", "")
    assert target.read_text().endswith("\n")
    assert [p.name for p in target.parent.iterdir()] == ["result.txt"]


def test_bad_input_leaves_an_existing_out_file_untouched(capsys, tmp_path):
    target = tmp_path / "keep.txt"
    target.write_text("old")
    code, _, err = run(capsys, ["chariot", "simulate", *TEETH, "--turns", "1e9", "--out", str(target)])
    assert code == 2 and len(err.splitlines()) == 1
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


@pytest.mark.parametrize(
    ("tables", "figures", "flag"),
    [
        ("/proc/t", "{tmp}/f", "--tables"),
        ("{tmp}/t", "/proc/f", "--figures"),
        ("/etc/hostname", "{tmp}/f", "--tables"),
        ("{tmp}/t", "/etc/hostname/f", "--figures"),
        ("{tmp}/t", "{tmp}/a-file", "--figures"),
        ("{tmp}/a-file/t", "{tmp}/f", "--tables"),
    ],
)
def test_reproduce_checks_both_folders_before_writing_anything(capsys, tmp_path, tables, figures, flag):
    (tmp_path / "a-file").write_text("not a folder")
    tables = tables.replace("{tmp}", str(tmp_path))
    figures = figures.replace("{tmp}", str(tmp_path))
    code, out, err = run(capsys, ["reproduce", "--tables", tables, "--figures", figures])
    assert code == 2 and out == ""
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert flag in err
    # neither folder was created, no file was written
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-file"]


def test_reproduce_library_refuses_a_bad_folder_before_writing(tmp_path):
    from gearlever.reproduce import run as reproduce

    with pytest.raises(NotADirectoryError) as exc:
        reproduce(tmp_path / "t", "/etc/hostname/f")
    assert exc.value.filename == "/etc/hostname"
    assert list(tmp_path.iterdir()) == []


def test_reproduce_end_to_end_refuses_proc_without_traceback(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "gearlever", "reproduce", "--tables", "/proc/t", "--figures", str(tmp_path / "f")],
        capture_output=True,
        text=True,
        check=False,
        timeout=120,
    )
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "/proc/t" in proc.stderr and "Traceback" not in proc.stderr
    assert list(tmp_path.iterdir()) == []


def test_out_into_a_missing_folder_does_not_create_it(capsys, tmp_path):
    target = tmp_path / "a" / "b" / "x.json"
    code, _, err = run(capsys, ["hooke", "--shaft-angle", "30", "--out", str(target)])
    assert code == 2 and "folder does not exist" in err
    assert not Path(tmp_path / "a").exists()
