"""Hostile outputs (issue 25, part 4): a command writes all its files or none, never one twice, never through a link.

Each class of the issue has its tests: two flags naming one file (the same
path, ``./x`` and ``x``, a symbolic link, a hard link), a figure suffix that
cannot be written, a full disk part way through the files (ENOSPC, simulated
in-process: the tests cannot fill a real disk), a rename failing part way
through the commit, ``examples copy`` all or none and onto a link, LAPACK's
``DLASCL`` line on the C stdout (captured at file descriptor 1 with
``capfd``), and ``reproduce`` naming the files it wrote.  Every test runs
:func:`gearlever.cli.main` in-process and checks the exit status, the one
line on stderr naming the flag, and the folder afterwards, byte for byte.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

import numpy as np
import pytest

import gearlever._io as gio
from gearlever.cli import main
from gearlever.data import example_path

FUNCTION = [
    "synthesize",
    "function",
    "--expr",
    "log10(x)",
    "--x-range",
    "1",
    "2",
    "--input-range",
    "30",
    "120",
    "--output-range",
    "60",
    "150",
]
ENOSPC = "No space left on device"


def run(capsys, argv, cwd=None):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def snapshot(folder: Path) -> dict:
    """Every entry under ``folder`` (hidden ones too): a link as its target, a file as its bytes."""
    out = {}
    for p in sorted(folder.rglob("*")):
        rel = str(p.relative_to(folder))
        if p.is_symlink():
            out[rel] = ("link", os.readlink(p))
        elif p.is_file():
            out[rel] = p.read_bytes()
        else:
            out[rel] = "dir"
    return out


def one_line(err: str) -> str:
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err


# ---------------------------------------------------------------------------
# two outputs that are one file
# ---------------------------------------------------------------------------


def _same_by_path(d):
    return "x.toml", "x.toml"


def _same_by_dot(d):
    return "x.toml", "./x.toml"


def _same_by_folder(d):
    (d / "sub").mkdir()
    return "x.toml", "sub/../x.toml"


def _same_by_link_to_new(d):
    (d / "r.json").symlink_to("x.toml")  # the model does not exist yet: the link names it
    return "x.toml", "r.json"


def _same_by_link_to_old(d):
    (d / "x.toml").write_text("old model\n")
    (d / "r.json").symlink_to(d / "x.toml")
    return "x.toml", "r.json"


def _same_by_hard_link(d):
    (d / "x.toml").write_text("old model\n")
    os.link(d / "x.toml", d / "r.json")
    return "x.toml", "r.json"


@pytest.mark.parametrize(
    "make",
    [_same_by_path, _same_by_dot, _same_by_folder, _same_by_link_to_new, _same_by_link_to_old, _same_by_hard_link],
    ids=["same-path", "dot-slash", "through-a-folder", "link-to-new", "link-to-old", "hard-link"],
)
def test_two_flags_naming_one_file_are_refused_naming_both(capsys, tmp_path, monkeypatch, make):
    # before: exit 0 and the model overwritten by the report
    monkeypatch.chdir(tmp_path)
    out, report = make(tmp_path)
    before = snapshot(tmp_path)
    code, stdout, err = run(capsys, [*FUNCTION, "--out", out, "--report", report])
    assert code == 2 and stdout == ""
    one_line(err)
    assert f"--report {report!r}" in err and f"--out {out!r}" in err and "same file" in err
    assert snapshot(tmp_path) == before


def test_same_file_is_refused_before_any_work(capsys, tmp_path, monkeypatch):
    import gearlever.synthesis.function as fn

    def boom(*a, **k):
        raise AssertionError("the synthesis ran before the outputs were checked")

    monkeypatch.setattr(fn, "synthesize_function", boom)
    code, _, err = run(capsys, [*FUNCTION, "--out", tmp_path / "x.png", "--figure", tmp_path / "x.png"])
    assert code == 2 and "--figure" in err and "--out" in err and "same file" in err
    assert list(tmp_path.iterdir()) == []


def test_motion_all_folder_file_and_out_are_one_file(capsys, tmp_path):
    poses = example_path("motion_poses.csv")
    (tmp_path / "sols").mkdir()
    out = tmp_path / "sols" / "solution_01.toml"
    code, _, err = run(capsys, ["synthesize", "motion", poses, "--out", out, "--all", tmp_path / "sols"])
    assert code == 2 and "--all" in one_line(err) and "--out" in err and "same file" in err
    assert snapshot(tmp_path) == {"sols": "dir"}


def test_distinct_outputs_beside_each_other_are_written(capsys, tmp_path):
    argv = [*FUNCTION, "--out", tmp_path / "m.toml", "--report", tmp_path / "r.json", "--figure", tmp_path / "f.png"]
    code, stdout, err = run(capsys, argv)
    assert (code, err) == (0, "")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "m.toml", "r.json"]
    assert (tmp_path / "m.toml").read_text().startswith("#") and (tmp_path / "r.json").read_text().startswith("{")


# ---------------------------------------------------------------------------
# a figure that cannot be written in that format
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["f.txt", "f", "f.gif"])
def test_bad_figure_suffix_is_refused_first_and_leaves_nothing(capsys, tmp_path, name):
    # before: exit 2 from matplotlib ("Format 'txt' is not supported") with the model already written
    code, stdout, err = run(capsys, [*FUNCTION, "--out", tmp_path / "m.toml", "--figure", tmp_path / name])
    assert code == 2 and stdout == ""
    assert one_line(err).startswith("gearlever: error: --figure must end with .png, .svg or .pdf")
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------
# a full disk part way through the files
# ---------------------------------------------------------------------------


class _FullDisk:
    """``open`` of :mod:`gearlever._io` whose ``n``-th file for writing fails with ENOSPC on write."""

    def __init__(self, n: int):
        self.n, self.calls = n, 0

    def __call__(self, file, mode="r", *args, **kwargs):
        fh = open(file, mode, *args, **kwargs)  # noqa: SIM115 - handed back to the caller
        if "w" not in mode:
            return fh
        self.calls += 1
        if self.calls < self.n:
            return fh

        class Full:
            def __enter__(self):
                return self

            def __exit__(self, *exc):
                fh.close()

            def write(self, text):
                fh.write(text[: len(text) // 2])  # half of it went to the disk
                raise OSError(errno.ENOSPC, ENOSPC)

        return Full()


def test_full_disk_at_the_figure_leaves_nothing_and_names_the_flag(capsys, tmp_path, monkeypatch):
    # before: "gearlever: error: No space left on device" and the model and report left behind
    import matplotlib.figure

    def full(self, fname, *a, **k):
        Path(fname).write_bytes(b"\x89PNG half")
        raise OSError(errno.ENOSPC, ENOSPC)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", full)
    (tmp_path / "m.toml").write_text("the old model\n")
    before = snapshot(tmp_path)
    argv = [*FUNCTION, "--out", tmp_path / "m.toml", "--report", tmp_path / "r.json", "--figure", tmp_path / "f.png"]
    code, stdout, err = run(capsys, argv)
    assert code == 2 and stdout == ""
    assert one_line(err) == f"gearlever: error: --figure {str(tmp_path / 'f.png')!r}: cannot write: {ENOSPC}\n"
    assert snapshot(tmp_path) == before  # the old model untouched, no report, no temporary file


@pytest.mark.parametrize(("n", "flag", "name"), [(1, "--out", "m.toml"), (2, "--report", "r.json")])
def test_full_disk_at_a_text_output_leaves_nothing_and_names_it(capsys, tmp_path, monkeypatch, n, flag, name):
    monkeypatch.setattr(gio, "open", _FullDisk(n), raising=False)
    argv = [*FUNCTION, "--out", tmp_path / "m.toml", "--report", tmp_path / "r.json", "--figure", tmp_path / "f.png"]
    code, stdout, err = run(capsys, argv)
    assert code == 2 and stdout == ""
    assert one_line(err) == f"gearlever: error: {flag} {str(tmp_path / name)!r}: cannot write: {ENOSPC}\n"
    assert list(tmp_path.iterdir()) == []


def test_full_disk_in_the_middle_of_examples_copy_copies_none(capsys, tmp_path, monkeypatch):
    # before: 15 of 18 examples copied, and "No space left on device" without the folder
    monkeypatch.setattr(gio, "open", _FullDisk(3), raising=False)
    dest = tmp_path / "new" / "models"
    code, stdout, err = run(capsys, ["examples", "copy", "fourbar", "engine", "watt_sixbar", "whitworth", "--to", dest])
    assert code == 2 and stdout == ""
    assert one_line(err) == f"gearlever: error: --to {str(dest / 'watt_sixbar.toml')!r}: cannot write: {ENOSPC}\n"
    assert list(tmp_path.iterdir()) == []  # the folders it made are gone too


def test_full_disk_with_force_leaves_the_old_copies(capsys, tmp_path, monkeypatch):
    for name in ("fourbar.toml", "engine.toml"):
        (tmp_path / name).write_text(f"my own {name}\n")
    before = snapshot(tmp_path)
    monkeypatch.setattr(gio, "open", _FullDisk(2), raising=False)
    code, _, err = run(capsys, ["examples", "copy", "fourbar", "engine", "--to", tmp_path, "--force"])
    assert code == 2 and "--to" in one_line(err) and ENOSPC in err
    assert snapshot(tmp_path) == before


def test_interrupt_in_the_middle_leaves_nothing(capsys, tmp_path, monkeypatch):
    import matplotlib.figure

    def interrupted(self, fname, *a, **k):
        Path(fname).write_bytes(b"half")
        raise KeyboardInterrupt

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", interrupted)
    argv = [*FUNCTION, "--out", tmp_path / "m.toml", "--report", tmp_path / "r.json", "--figure", tmp_path / "f.png"]
    code, _, err = run(capsys, argv)
    assert (code, err) == (130, "gearlever: interrupted\n")
    assert list(tmp_path.iterdir()) == []


def test_a_rename_failing_part_way_puts_the_old_files_back(capsys, tmp_path, monkeypatch):
    """POSIX renames one file at a time: the commit undoes the renames done when a later one fails."""
    for name in ("fourbar.toml", "engine.toml", "whitworth.toml"):
        (tmp_path / name).write_text(f"my own {name}\n")
    before = snapshot(tmp_path)
    real = os.replace
    calls = []

    def replace(src, dst):
        calls.append(Path(dst).name)
        if len(calls) == 2:
            raise OSError(errno.EIO, "Input/output error")
        return real(src, dst)

    monkeypatch.setattr(gio.os, "replace", replace)
    code, _, err = run(capsys, ["examples", "copy", "fourbar", "engine", "whitworth", "--to", tmp_path, "--force"])
    assert code == 2 and one_line(err).startswith(f"gearlever: error: --to {str(tmp_path / 'engine.toml')!r}")
    assert snapshot(tmp_path) == before  # fourbar.toml, already replaced, got its old bytes back


# ---------------------------------------------------------------------------
# symbolic links are replaced, not followed
# ---------------------------------------------------------------------------


def test_examples_copy_force_replaces_a_link_not_its_target(capsys, tmp_path):
    # before: the copy went through the link into the file it names
    precious = tmp_path / "precious.txt"
    precious.write_text("keep me\n")
    dest = tmp_path / "models"
    dest.mkdir()
    (dest / "fourbar.toml").symlink_to(precious)
    code, stdout, err = run(capsys, ["examples", "copy", "fourbar", "--to", dest, "--force"])
    assert (code, err) == (0, "")
    assert stdout.split() == [str(dest / "fourbar.toml")]
    assert not (dest / "fourbar.toml").is_symlink()
    assert (dest / "fourbar.toml").read_bytes() == example_path("fourbar.toml").read_bytes()
    assert precious.read_text() == "keep me\n"


def test_examples_copy_without_force_refuses_a_link(capsys, tmp_path):
    (tmp_path / "fourbar.toml").symlink_to(tmp_path / "nowhere")
    code, _, err = run(capsys, ["examples", "copy", "fourbar", "--to", tmp_path])
    assert code == 2 and "--force" in one_line(err)
    assert (tmp_path / "fourbar.toml").is_symlink() and not (tmp_path / "nowhere").exists()


def test_out_onto_a_link_replaces_the_link(capsys, tmp_path):
    elsewhere = tmp_path / "elsewhere.json"
    elsewhere.write_text("not mine\n")
    (tmp_path / "out.json").symlink_to(elsewhere)
    code, _, err = run(capsys, ["hooke", "--shaft-angle", "30", "--format", "json", "--out", tmp_path / "out.json"])
    assert (code, err) == (0, "")
    assert not (tmp_path / "out.json").is_symlink() and (tmp_path / "out.json").read_text().startswith("[")
    assert elsewhere.read_text() == "not mine\n"


# ---------------------------------------------------------------------------
# output folders: created if missing (folder flags), refused if missing (file flags)
# ---------------------------------------------------------------------------


def test_all_creates_its_folder_and_out_refuses_a_missing_one(capsys, tmp_path):
    poses = example_path("motion_poses.csv")
    code, _, err = run(capsys, ["synthesize", "motion", poses, "--out", tmp_path / "no" / "m.toml"])
    assert code == 2 and "--out" in one_line(err) and "folder does not exist" in err
    code, _, err = run(capsys, ["synthesize", "motion", poses, "--out", tmp_path / "m.toml", "--all", tmp_path / "a/b"])
    assert (code, err) == (0, "")
    assert (tmp_path / "a" / "b" / "solution_01.toml").is_file()


def test_a_failed_command_removes_the_folder_it_created(capsys, tmp_path):
    poses = example_path("motion_poses.csv")
    argv = ["synthesize", "motion", poses, "--out", tmp_path / "m.toml", "--all", tmp_path / "a" / "b"]
    code, _, err = run(capsys, [*argv, "--figure", tmp_path / "f.txt"])
    assert code == 2 and "--figure" in one_line(err)
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------------------
# LAPACK writes on the C stdout: it is never handed an infinity
# ---------------------------------------------------------------------------

HUGE = """
[points]
O2 = [0, 0]
O4 = [40, 0]
A = [11, 1]
B = [44, 31]
[links]
ground = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B"]
[[inputs]]
link = "crank"
[lengths]
"""


@pytest.mark.parametrize(
    "lengths",
    ["crank = 1e308\ncoupler = 45\nrocker = 30", "crank = 1e308\ncoupler = 1e308\nrocker = 1e308"],
    ids=["one", "all"],
)
def test_assemble_at_1e308_keeps_stdout_clean(capfd, tmp_path, lengths):
    # before: " ** On entry to DLASCL parameter number  4 had an illegal value" twice on stdout (fd 1)
    model = tmp_path / "huge.toml"
    model.write_text(HUGE + lengths + "\n")
    code = main(["mechanism", "assemble", str(model), "--out", str(tmp_path / "o.toml")])
    out, err = capfd.readouterr()
    assert code == 2 and out == ""
    assert "lengths.crank" in one_line(err) and "1e+308" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["huge.toml"]


def test_the_assembly_newton_step_never_hands_lapack_an_infinity(capfd):
    from gearlever.mechanism.assemble import _newton_step

    J = np.array([[1.0, np.inf], [0.0, 1.0]])
    assert _newton_step(J, np.ones(2)) is None
    assert _newton_step(np.eye(2), np.array([np.nan, 1.0])) is None
    assert np.allclose(_newton_step(np.eye(2), np.array([1.0, 2.0])), [1.0, 2.0])
    assert capfd.readouterr().out == ""


# ---------------------------------------------------------------------------
# reproduce names the files it wrote
# ---------------------------------------------------------------------------


@pytest.fixture
def few_steps(monkeypatch):
    """Only the quick reproduction steps (a table-only, a table-and-figure and a per-file one)."""
    import pkgutil

    import gearlever.reproduce as rep

    keep = {"epicyclic", "networks", "textbook"}
    real = pkgutil.iter_modules

    def some(path=None, prefix=""):
        found = list(real(path, prefix))
        return [m for m in found if m.name in keep] if path == rep.__path__ else found

    monkeypatch.setattr(pkgutil, "iter_modules", some)


def test_reproduce_prints_the_paths_it_wrote(capsys, tmp_path, monkeypatch, few_steps):
    # before: "tables/nuttall.csv: ..." although the file went to t/nuttall.csv
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, ["reproduce", "--tables", "t", "--figures", "f"])
    assert (code, err) == (0, "")
    named = [w.rstrip(":,") for line in out.splitlines() for w in line.split() if w.endswith((".csv:", ".png:"))]
    assert len(named) == len(out.splitlines()) == 10  # each line names the file it is about
    assert all(w.startswith(("t/", "f/")) for w in named), named
    assert all((tmp_path / w).is_file() for w in named)
    assert "tables/" not in out and "figures/" not in out
    written = {str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file()}
    assert written == set(named)


def test_reproduce_failing_part_way_writes_nothing_and_removes_its_folders(capsys, tmp_path, few_steps, monkeypatch):
    import gearlever.reproduce.textbook as textbook

    def broken(tables_dir, figures_dir):
        raise OSError(errno.ENOSPC, ENOSPC)

    monkeypatch.setattr(textbook, "run", broken)
    code, out, err = run(capsys, ["reproduce", "--tables", tmp_path / "t", "--figures", tmp_path / "f"])
    assert code == 2 and out == "" and ENOSPC in one_line(err)
    assert list(tmp_path.iterdir()) == []
