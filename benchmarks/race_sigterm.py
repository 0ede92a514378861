"""Loop script (not a benchmark, not a test): SIGTERM while ``gearlever ... --out`` is written, hundreds of times.

The scenario of ``tests/cli/test_hostile.py::test_sigterm_during_a_write_leaves_no_temporary_file``:
start ``gearlever zrdpm --contour 1 --step 0.00037 --format csv --out big.csv``,
poll the folder until a temporary file of the write appears, send SIGTERM,
and look at what is left.  Run it with ``--load 2`` to keep both cores of a
2-core machine busy (the failure was seen once under a loaded full run), and
with ``--src`` pointing at another checkout's ``src`` to count the same
scenario on older code.

Each run is classified:

* ``temporary file left``: a hidden file (``.big.csv.*``: the write's
  temporary file, a probe, a backup) is still in the folder (the defect);
* ``half-written output``: ``big.csv`` exists and differs from a complete
  run's bytes (the defect's other face);
* ``bad status``: an exit status other than 0, 143 or death by SIGTERM, or
  143 without the one line ``gearlever: terminated``;
* ``terminated, nothing written`` / ``terminated after the renames`` /
  ``finished before the signal`` / ``killed after the handlers were
  restored``: the correct outcomes (the last three: the signal landed once
  the output was complete; each file is then whole).

``old test fails`` counts the runs that the test's assertions before issue
33's fix would have failed (143 always with no output; otherwise exit 0):
it was right to keep no temporary file, wrong to require no output on 143.

The test's own command takes a minute a run on a loaded 2-core machine (it formats 95 MB), so by
default the child is ``gearlever.cli.main`` itself (the same signal handlers, output set, ``--out`` check and
``emit``) running a command that emits ready-made text: the same code from the handlers to the rename, without
the computation (``--megabytes 0`` runs the test's command).

Usage::

    python benchmarks/race_sigterm.py [--runs 300] [--load 2] [--src DIR]
"""

from __future__ import annotations

import argparse
import collections
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ARGV = ["zrdpm", "--contour", "1", "--step", "0.00037", "--format", "csv", "--out"]
BUSY = "while True:\n    pass\n"


#: The fast scenario's child: ``gearlever.cli.main`` (its signal handlers, its output set, ``--out`` checked and
#: written by ``emit``) running one command that emits ``MB`` megabytes of CSV made at once (no computation).
CHILD = """
import argparse, sys
from gearlever import cli
from gearlever.cli._common import emit

def build_parser():
    p = argparse.ArgumentParser(prog="gearlever")
    p.add_argument("--out")
    p.set_defaults(func=lambda a: emit("x,y\\n" + "0.123456789,0.987654321\\n" * (int(sys.argv[2]) * 41943), a.out))
    return p

cli.build_parser = build_parser
cli._chosen_parser = lambda parser, args: parser
sys.exit(cli.main(["--out", sys.argv[1]]))
"""


def _start(src: Path, out: Path, megabytes: int) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(src))
    argv = ["-c", CHILD, str(out), str(megabytes)] if megabytes else ["-m", "gearlever", *ARGV, str(out)]
    return subprocess.Popen([sys.executable, *argv], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def _hidden(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def one(src: Path, folder: Path, reference: bytes, megabytes: int, jitter: float, rng) -> tuple[str, bool]:
    """One run in the empty ``folder``: (its class, whether the old test's assertions fail)."""
    out = folder / "big.csv"
    proc = _start(src, out, megabytes)
    caught = False
    try:
        while proc.poll() is None:
            if any(p.name.startswith(".big.csv.") for p in folder.iterdir()):
                caught = True
                if jitter:
                    time.sleep(rng.uniform(0.0, jitter))
                proc.send_signal(signal.SIGTERM)
                break
            time.sleep(0.002)
        err = proc.communicate()[1].decode()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    rc = proc.returncode
    left = _hidden(folder)
    written = out.exists()
    old_fails = bool(left) or (
        (err != "gearlever: terminated\n" or written)
        if caught and rc == 143
        else not (rc == 0 and written and out.stat().st_size > 0)
    )
    if left:
        return "temporary file left: " + ", ".join(n.split(".")[-1] for n in left), old_fails
    if written and out.read_bytes() != reference:
        return "half-written output", old_fails
    if rc == 143:
        if err != "gearlever: terminated\n":
            return "bad status", old_fails
        return ("terminated after the renames" if written else "terminated, nothing written"), old_fails
    if rc == 0 and written:
        return "finished before the signal", old_fails
    if rc == -signal.SIGTERM and (written or not caught):
        return "killed after the handlers were restored", old_fails
    return f"bad status ({rc})", old_fails


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=300)
    p.add_argument("--load", type=int, default=0, help="busy Python loops kept running meanwhile")
    p.add_argument("--src", type=Path, default=ROOT / "src", help="the package's source folder to run")
    p.add_argument("--megabytes", type=int, default=20, help="size of the fast scenario's output; 0: the test's zrdpm")
    p.add_argument("--jitter", type=float, default=0.02, help="seconds: the signal waits a random time up to this")
    args = p.parse_args(argv)
    rng = random.Random(0)
    busy = [subprocess.Popen([sys.executable, "-c", BUSY]) for _ in range(args.load)]
    counts: collections.Counter = collections.Counter()
    old_fails = 0
    t0 = time.monotonic()
    try:
        with tempfile.TemporaryDirectory() as tmp:
            ref = Path(tmp) / "ref"
            ref.mkdir()
            proc = _start(args.src, ref / "big.csv", args.megabytes)
            if proc.wait() != 0:
                print(proc.stderr.read().decode(), file=sys.stderr)
                return 1
            reference = (ref / "big.csv").read_bytes()
            for i in range(args.runs):
                folder = Path(tmp) / f"run{i}"
                folder.mkdir()
                kind, fails = one(args.src, folder, reference, args.megabytes, args.jitter, rng)
                counts[kind] += 1
                old_fails += fails
                for f in folder.iterdir():
                    f.unlink()
                folder.rmdir()
    finally:
        for b in busy:
            b.kill()
            b.wait()
    what = f"emit of {args.megabytes} MB under cli.main" if args.megabytes else "the test's zrdpm command"
    print(f"source {args.src}; {what}; signal delayed 0 to {args.jitter * 1000:g} ms after the temporary file is seen")
    print(f"{args.runs} runs with {args.load} busy loops in {time.monotonic() - t0:.0f} s")
    print(f"load average at the end: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    for kind, n in sorted(counts.items()):
        print(f"{n:5d}  {kind}")
    print(f"{old_fails:5d}  old test fails")
    defects = sum(n for k, n in counts.items() if k.startswith(("temporary", "half", "bad")))
    print(f"{defects:5d}  defects (temporary file left, half-written output, bad status)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
