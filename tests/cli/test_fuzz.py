"""CLI fuzzing: every sub-command, random and hostile argument vectors, never a traceback or a hang.

Sub-commands are discovered from :func:`gearlever.cli.build_parser` (a command
registered later is fuzzed without a change here); each gets a strategy built
from its argparse actions.  Known commands also get hand-written hostile
cases.  Each case runs in-process through :func:`gearlever.cli.main` with
stdout and stderr captured, under two guards: a wall-clock alarm (a hang
check, not a speed test) and an address-space limit (a missing size cap shows
up as a MemoryError, which is reported as a failure rather than swapping the
machine).  A case passes when the exit status is 0 or 2, stderr holds no
traceback, an error is exactly one line, and no memory guard was hit.

Every output argument (``--out``, ``--tables``, ``--figures``) is forced into
the case's temporary folder or a known-unwritable place, and the case runs
with that folder as its working directory: the fuzzer never writes elsewhere.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from gearlever.cli import build_parser, main

#: Wall-clock guard per case (a hang check; normal cases take well under a second).
CASE_SECONDS = 8.0
#: Extra address space a case may take before the memory guard fires.
CASE_MEMORY = 1536 * 2**20
#: Examples per discovered sub-command (keeps the file within ~60 s on 2 cores).
EXAMPLES = 30

NETWORK = "a,gear,20\nb,gear,40\nab,mesh,a,b\n"
WAYPOINTS = "x,y\n0,0\n2,0\n2,1\n"

#: Hostile and ordinary values for any argument.
VALUES = [
    "0",
    "1",
    "2",
    "3",
    "20",
    "30",
    "45",
    "-1",
    "-30",
    "0.5",
    "1e-9",
    "1e-300",
    "1e9",
    "1e308",
    "-1e308",
    "100000000",
    "99999999999999999999",
    "nan",
    "inf",
    "-inf",
    "abc",
    "",
    " ",
    "1/6.931",
    "n2=30",
    "a,b",
    "-",
]
#: Ordinary values (most arguments accept them).
ORDINARY = ["1", "2", "3", "5", "8", "9", "12", "20", "24", "30", "40", "0.5", "1.5", "10"]
#: Destinations that name an output file / an output folder / an input file.
OUT_DESTS = {"out"}
FOLDER_DESTS = {"tables", "figures"}
FILE_DESTS = {"file", "waypoints"}


class CaseTimeout(BaseException):
    """Raised by the wall-clock guard (a BaseException: the CLI must not swallow it)."""


def _vm_bytes() -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmSize:"):
            return int(line.split()[1]) * 1024
    return 0


@contextlib.contextmanager
def guards(seconds: float = CASE_SECONDS):
    """Wall-clock alarm and address-space limit around one in-process case."""

    def alarm(signum, frame):
        raise CaseTimeout(f"case ran longer than {seconds} s")

    old_handler = signal.signal(signal.SIGALRM, alarm)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = _vm_bytes() + CASE_MEMORY
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old_handler)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


class Sandbox:
    """A temporary working folder with the files the cases point at."""

    def __init__(self, root: Path, garbage: bytes = b"\x00\xffgarbage,,\n1 two\n"):
        self.root = root
        (root / "dir").mkdir()
        (root / "empty.csv").write_text("")
        (root / "garbage.bin").write_bytes(garbage)
        (root / "network.csv").write_text(NETWORK)
        (root / "waypoints.csv").write_text(WAYPOINTS)

    def outs(self) -> list[str]:
        r = self.root
        return [
            str(r / "o.txt"),
            str(r / "o.gif"),
            "/proc/x.csv",
            str(r / "dir"),
            "/etc/hostname/x.csv",
            str(r / "missing" / "x.csv"),
            "",
        ]

    def bad_folders(self) -> list[str]:
        r = self.root
        return ["/proc/t", "/etc/hostname", "/etc/hostname/f", str(r / "empty.csv"), str(r / "empty.csv" / "t")]

    def inputs(self) -> list[str]:
        r = self.root
        return [
            str(r / "network.csv"),
            str(r / "waypoints.csv"),
            str(r / "empty.csv"),
            str(r / "garbage.bin"),
            str(r / "dir"),
            "/nonexistent/x.csv",
            "/etc/hostname/x",
            "",
        ]

    def substitute(self, argv: list[str]) -> list[str]:
        return [a.replace("{tmp}", str(self.root)) for a in argv]


def run_case(argv: list[str], root: Path, seconds: float = CASE_SECONDS):
    """Run ``gearlever argv`` in-process in ``root``; return (status, stdout, stderr, seconds)."""
    out, err = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    os.chdir(root)
    start = time.monotonic()
    try:
        with guards(seconds), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(argv)
            except SystemExit as exc:  # --help, --version
                status = exc.code if isinstance(exc.code, int) else 0
    finally:
        os.chdir(cwd)
    return status, out.getvalue(), err.getvalue(), time.monotonic() - start


def check_case(argv, status, out, err) -> None:
    """The contract every case must keep."""
    shown = " ".join(repr(a) if (not a or " " in a) else a for a in ["gearlever", *argv])
    assert "Traceback" not in err, f"{shown}\n{err}"
    assert status in (0, 2), f"{shown}: exit {status}\n{err}"
    assert "out of memory" not in err, f"{shown}: hit the memory guard (no cap)\n{err}"
    if status == 2:
        assert err.count("\n") == 1 and err.strip(), f"{shown}: error is not one line\n{err!r}"


def assert_nothing_outside(root: Path, before: set[str]) -> None:
    """No temporary file left in the sandbox (a finished output may stay)."""
    stray = [p.name for p in root.rglob(".*") if p.name.endswith((".tmp", ".probe", ".gif")) and p.name.startswith(".")]
    assert stray == [], stray


# ---------------------------------------------------------------------------
# discovery
# ---------------------------------------------------------------------------


def _leaves(parser: argparse.ArgumentParser, prefix=()):
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield prefix, parser
        return
    seen = set()
    for name, child in subs[0].choices.items():
        if id(child) in seen:  # an alias
            continue
        seen.add(id(child))
        yield from _leaves(child, (*prefix, name))


LEAVES = dict(_leaves(build_parser()))


def test_discovery_finds_every_registered_command():
    top = build_parser()
    (subs,) = [a for a in top._actions if isinstance(a, argparse._SubParsersAction)]
    assert {path[0] for path in LEAVES} == set(subs.choices)
    assert {"reproduce", "chariot", "differential"} <= set(subs.choices)


def _nargs_count(action):
    n = action.nargs
    if n is None:
        return st.just(1)
    if isinstance(n, int):
        return st.just(n)
    return {"?": st.integers(0, 1), "*": st.integers(0, 3), "+": st.integers(1, 3)}.get(n, st.just(1))


def _value(action, box: Sandbox, calm: bool):
    """A value for ``action``: ordinary when ``calm``, else anything (hostile or not)."""
    dest = action.dest
    if dest in OUT_DESTS:
        return st.sampled_from(box.outs()[:2] if calm else box.outs())
    if dest in FOLDER_DESTS:
        return st.sampled_from(box.bad_folders())
    if dest in FILE_DESTS or "FILE" in str(action.metavar or ""):
        return st.sampled_from(box.inputs()[:2] if calm else box.inputs())
    good = st.sampled_from([str(c) for c in action.choices] if action.choices else ORDINARY)
    if calm:
        return good
    return st.one_of(good, st.sampled_from(VALUES), st.text(max_size=6), st.integers(-(10**3), 10**4).map(str))


@st.composite
def argv_for(draw, path, parser, box: Sandbox):
    """A random argument vector for the leaf command ``path`` built from its argparse actions."""
    argv = list(path)
    actions = [a for a in parser._actions if not isinstance(a, (argparse._HelpAction, argparse._VersionAction))]
    draw(st.randoms(use_true_random=False)).shuffle(actions)
    # calm: ordinary values everywhere; one: one argument hostile; wild: any value anywhere
    mode = draw(st.sampled_from(["calm", "one", "one", "wild"]))
    hostile_at = draw(st.integers(0, max(0, len(actions) - 1)))
    positionals = []
    for k, action in enumerate(actions):
        calm = mode == "calm" or (mode == "one" and k != hostile_at)
        # folders are always given (a default folder would be the working tree), and always refused
        forced = action.dest in FOLDER_DESTS
        if action.option_strings:
            if not (action.required or forced or draw(st.booleans())):
                continue
            flag = draw(st.sampled_from(action.option_strings))
            if action.nargs == 0:
                argv.append(flag)
                continue
            count = draw(_nargs_count(action))
            argv += [flag, *(draw(_value(action, box, calm)) for _ in range(count))]
        else:
            count = draw(_nargs_count(action))
            positionals += [draw(_value(action, box, calm)) for _ in range(count)]
    if positionals:
        at = draw(st.integers(len(path), len(argv)))
        argv[at:at] = positionals
    if mode == "wild" and draw(st.booleans()):  # a garbage word anywhere
        argv.insert(draw(st.integers(1, len(argv))), draw(st.sampled_from(VALUES + ["--", "--bogus"])))
    return argv


# ---------------------------------------------------------------------------
# generic fuzz of every discovered command
# ---------------------------------------------------------------------------

#: Commands whose generic fuzz fails today in a file outside this branch's area:
#: leaf path -> reason (with a failing argv); strict, so that a fix flips it.
KNOWN_GENERIC = {}
#: Commands that serve until Ctrl-C or SIGTERM (an in-process case would serve until its alarm): fuzzed
#: where they run as servers, leaf path -> where.
SERVING = {("workbench",): "tests/workbench/test_cli.py (the command), tests/workbench/test_fuzz.py (its API)"}


def _leaf_params():
    out = []
    for path in sorted(LEAVES):
        marks = []
        if path in KNOWN_GENERIC:
            marks.append(pytest.mark.xfail(strict=True, reason=KNOWN_GENERIC[path]))
        if path in SERVING:
            marks.append(pytest.mark.skip(reason=f"serves until signalled; fuzzed in {SERVING[path]}"))
        out.append(pytest.param(path, id=" ".join(path), marks=marks))
    return out


@pytest.mark.parametrize("path", _leaf_params())
def test_generic_fuzz_of_each_command_keeps_the_contract(path):
    parser = LEAVES[path]
    with tempfile.TemporaryDirectory(prefix="gearlever-fuzz-") as tmp:
        root = Path(tmp)
        box = Sandbox(root)

        @settings(
            max_examples=EXAMPLES,
            deadline=None,
            derandomize=True,
            database=None,
            phases=[Phase.explicit, Phase.generate],  # no shrinking: a failing case is shown as found
            suppress_health_check=list(HealthCheck),
        )
        @given(data=st.data())
        def fuzz(data):
            argv = data.draw(argv_for(path, parser, box), label="argv")
            (root / "garbage.bin").write_bytes(data.draw(st.binary(max_size=64), label="garbage file"))
            before = {p.name for p in root.iterdir()}
            status, out, err, _ = run_case(argv, root)
            check_case(argv, status, out, err)
            assert_nothing_outside(root, before)

        fuzz()


# ---------------------------------------------------------------------------
# hand-written hostile cases for the known commands
# ---------------------------------------------------------------------------

TEETH = ["--n2", "30", "--n5", "24", "--n6", "18", "--n7", "36", "--n8", "20", "--n9", "25", "--n11", "40"]
CAR = ["differential", "car", "--pinion-teeth", "11", "--ring-teeth", "41"]
FOURBAR = ["--ground", "9", "--crank", "5", "--coupler", "8", "--rocker", "8"]

HOSTILE = {
    "chariot-turns-huge": ["chariot", "simulate", *TEETH, "--turns", "1e9"],
    "chariot-turns-inf": ["chariot", "simulate", *TEETH, "--turns", "inf"],
    "chariot-steps-huge": ["chariot", "simulate", *TEETH, "--steps-per-turn", "99999999999999999999"],
    "chariot-product-over-cap": ["chariot", "simulate", *TEETH, "--turns", "1e4", "--steps-per-turn", "10000"],
    "chariot-step-tiny": ["chariot", "simulate", *TEETH, "--waypoints", "{tmp}/waypoints.csv", "--step", "1e-300"],
    "chariot-turns-with-waypoints": [
        "chariot",
        "simulate",
        *TEETH,
        "--waypoints",
        "{tmp}/waypoints.csv",
        "--turns",
        "2",
    ],
    "chariot-waypoints-empty": ["chariot", "simulate", *TEETH, "--waypoints", "{tmp}/empty.csv"],
    "chariot-waypoints-garbage": ["chariot", "simulate", *TEETH, "--waypoints", "{tmp}/garbage.bin"],
    "chariot-waypoints-dir": ["chariot", "simulate", *TEETH, "--waypoints", "{tmp}/dir"],
    "chariot-waypoints-zero": ["chariot", "simulate", *TEETH, "--waypoints", "/dev/zero"],
    "chariot-teeth-huge": ["chariot", "nuttall", *TEETH[:-1], "99999999999999999999"],
    "chariot-track-huge": ["chariot", "nuttall", *TEETH, "--track", "1e308", "--format", "json"],
    "chariot-track-tiny": ["chariot", "simulate", *TEETH, "--track", "1e-308", "--turns", "1"],
    "chariot-d1-tiny": ["chariot", "simulate", *TEETH, "--d1", "1e-308", "--turns", "1", "--format", "json"],
    "chariot-out-proc": ["chariot", "nuttall", *TEETH, "--out", "/proc/x.csv"],
    "differential-huge-speed": [*CAR, "--pinion-speed", "1e308", "--pinion-torque", "1e308", "--format", "json"],
    "differential-teeth-huge": [
        *CAR[:3],
        "99999999999999999999",
        *CAR[4:],
        "--pinion-speed",
        "1",
        "--pinion-torque",
        "1",
    ],
    "differential-tiny-turn": [
        *CAR,
        "--pinion-speed",
        "1",
        "--pinion-torque",
        "1",
        "--turn-radius",
        "1e-308",
        "--track",
        "1e308",
    ],
    "differential-out-dir": [*CAR, "--pinion-speed", "1", "--pinion-torque", "1", "--out", "{tmp}/dir"],
    "reproduce-proc": ["reproduce", "--tables", "/proc/t", "--figures", "{tmp}/f"],
    "reproduce-file": ["reproduce", "--tables", "{tmp}/t", "--figures", "{tmp}/empty.csv"],
    "mobility-huge": ["mobility", "--n", "99999999999999999999", "--p5", "0", "--p4", "0", "--q", "0"],
    "zrdpm-range-infinite": ["zrdpm", "--contour", "1", "--start", "-1e308", "--stop", "1e308"],
    "zrdpm-step-tiny": ["zrdpm", "--contour", "1", "--step", "1e-300"],
    "zrdpm-many-angles": ["zrdpm", "--contour", "1", "--step", "0.0001", "--stop", "999", "--format", "json"],
    "zrdpm-teeth-huge": ["zrdpm", "--contour", "2", "--teeth", "1", "99999999999999999999"],
    "network-empty": ["network", "{tmp}/empty.csv"],
    "network-garbage": ["network", "{tmp}/garbage.bin", "--inputs", "a"],
    "network-dir": ["network", "{tmp}/dir"],
    "network-missing": ["network", "/nonexistent/net.csv"],
    "network-zero-device": ["network", "/dev/zero"],
    "network-teeth-huge": ["network", "{tmp}/network.csv", "--teeth", "n2=99999999999999999999"],
    "network-inputs-garbage": ["network", "{tmp}/network.csv", "--inputs", ",,,zz"],
    "train-ratio-huge": ["train", "ratio", "--drivers", "99999999999999999999", "--followers", "1"],
    "train-ratio-zero": ["train", "ratio", "--drivers", "0", "--followers", "0"],
    "train-design-nan": ["train", "design", "--ratio", "nan"],
    "train-design-zero-denominator": ["train", "design", "--ratio", "1/0"],
    "train-design-huge": ["train", "design", "--ratio", "1e308"],
    "train-search-huge-range": [
        "train",
        "search",
        "--ratio",
        "1/6.931",
        "--pairs",
        "99",
        "--min-teeth",
        "1",
        "--max-teeth",
        "99999999999999999999",
    ],
    "hooke-near-90": ["hooke", "--shaft-angle", "89.99999999999"],
    "hooke-input-huge": ["hooke", "--shaft-angle", "30", "--input-angle", "1e308", "-1e308"],
    "hooke-many-angles": ["hooke", "--shaft-angle", "30", "--input-angle", *["1"] * 5000],
    "fourbar-many-points": ["fourbar", *FOURBAR, "--points", "100000000"],
    "fourbar-huge-links": [
        "fourbar",
        "--ground",
        "1e308",
        "--crank",
        "1e308",
        "--coupler",
        "1e308",
        "--rocker",
        "1e-308",
    ],
    "fourbar-out-missing-folder": ["fourbar", *FOURBAR, "--out", "{tmp}/missing/x.csv"],
    "animate-many-frames": [
        "animate",
        "--fourbar",
        "9",
        "5",
        "8",
        "8",
        "--out",
        "{tmp}/a.gif",
        "--frames",
        "100000000",
    ],
    "animate-not-gif": ["animate", "--fourbar", "9", "5", "8", "8", "--out", "{tmp}/a.png"],
    "animate-out-proc": ["animate", "--fourbar", "9", "5", "8", "8", "--out", "/proc/a.gif"],
}

#: Hand-written cases that fail today in files outside this branch's area (strict: a fix flips them).
KNOWN_HOSTILE: dict[str, str] = {}


def _hostile_params():
    out = []
    for name, argv in HOSTILE.items():
        marks = [pytest.mark.xfail(strict=True, reason=KNOWN_HOSTILE[name])] if name in KNOWN_HOSTILE else []
        out.append(pytest.param(argv, id=name, marks=marks))
    return out


@pytest.mark.parametrize("argv", _hostile_params())
def test_hostile_case_keeps_the_contract(tmp_path, argv):
    box = Sandbox(tmp_path)
    argv = box.substitute(argv)
    before = {p.name for p in tmp_path.iterdir()}
    status, out, err, _ = run_case(argv, tmp_path)
    check_case(argv, status, out, err)
    assert_nothing_outside(tmp_path, before)
    if status == 2:  # a refused case writes nothing at all
        assert {p.name for p in tmp_path.iterdir()} == before


def test_hostile_cases_name_registered_commands_only():
    covered = {argv[0] for argv in HOSTILE.values()}
    assert covered <= {path[0] for path in LEAVES}


# ---------------------------------------------------------------------------
# a few end-to-end runs in a separate process
# ---------------------------------------------------------------------------


def _limited():
    resource.setrlimit(resource.RLIMIT_AS, (4 * 2**30, resource.RLIM_INFINITY))


@pytest.mark.parametrize(
    "argv",
    [
        ["chariot", "simulate", *TEETH, "--turns", "1e9"],
        ["chariot", "nuttall", *TEETH, "--out", "/proc/x.csv"],
        ["reproduce", "--tables", "/proc/t", "--figures", "/proc/f"],
    ],
    ids=["chariot-turns-huge", "out-proc", "reproduce-proc"],
)
def test_end_to_end_in_a_subprocess_is_one_line_and_exit_2(tmp_path, argv):
    proc = subprocess.run(
        [sys.executable, "-m", "gearlever", *argv],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=tmp_path,
        preexec_fn=_limited,
        check=False,
    )
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert list(tmp_path.iterdir()) == []
