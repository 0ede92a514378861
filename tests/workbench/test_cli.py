"""``gearlever workbench`` as a user starts it: a subprocess on a free port, its one line, the page, SIGTERM."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request

import pytest

from tests.workbench._client import example_text

PYTHON = sys.executable


def _start(args, cwd):
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen(
        [PYTHON, "-m", "gearlever", "workbench", *args],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )


def _line(proc, timeout=60.0) -> str:
    import selectors

    sel = selectors.DefaultSelector()
    sel.register(proc.stdout, selectors.EVENT_READ)
    if not sel.select(timeout):
        proc.kill()
        raise AssertionError(f"no line in {timeout} s: {proc.stderr.read()}")
    return proc.stdout.readline()


def _get(url, token=None, timeout=30):
    req = urllib.request.Request(url, headers={"Authorization": f"Bearer {token}"} if token else {})
    with urllib.request.urlopen(req, timeout=timeout) as r:
        return r.status, r.headers, r.read()


def _stop(proc, sig=signal.SIGTERM, timeout=30):
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        raise
    return proc.returncode, out, err


def test_workbench_prints_one_line_serves_the_page_and_stops_on_sigterm(tmp_path):
    (tmp_path / "fourbar.toml").write_text(example_text("fourbar"))
    proc = _start([str(tmp_path / "fourbar.toml"), "--port", "0", "--no-browser"], tmp_path)
    try:
        line = _line(proc)
        assert line.startswith("workbench: http://127.0.0.1:") and line.endswith("\n")
        url = line.split(" ", 1)[1].strip()
        assert "&open=fourbar.toml" in url
        token = url.split("token=")[1].split("&")[0]
        assert len(token) == 22
        status, headers, body = _get(url)
        assert status == 200 and b"<html" in body.lower()
        base = url.split("/?")[0]
        status, headers, body = _get(f"{base}/api/files/fourbar.toml", token)
        assert json.loads(body)["model"] == example_text("fourbar")
        with pytest.raises(urllib.error.HTTPError) as exc:
            _get(f"{base}/api/files")
        assert exc.value.code == 401
    finally:
        code, out, err = _stop(proc)
    assert code == 143, err
    assert out == ""  # the one line was read above; nothing else on stdout
    assert "Traceback" not in err
    assert err.strip().splitlines()[-1] == "gearlever: terminated"
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_workbench_stops_on_ctrl_c(tmp_path):
    proc = _start([str(tmp_path), "--no-browser"], tmp_path)
    try:
        assert _line(proc).startswith("workbench: http://127.0.0.1:")
    finally:
        code, _, err = _stop(proc, signal.SIGINT)
    assert code == 130, err
    assert "Traceback" not in err


def test_workbench_off_loopback_warns_that_the_token_is_the_only_guard(tmp_path):
    proc = _start([str(tmp_path), "--no-browser", "--host", "0.0.0.0"], tmp_path)
    try:
        assert _line(proc).startswith("workbench: http://")
        time.sleep(0.5)
    finally:
        code, _, err = _stop(proc)
    assert "token is then the only guard" in err


@pytest.mark.parametrize(
    ("args", "word"),
    [(["missing.toml"], "no such file"), (["notes.txt"], ".toml"), (["--port", "70000"], "--port")],
)
def test_workbench_bad_arguments_exit_2_with_one_line(tmp_path, args, word):
    (tmp_path / "notes.txt").write_text("x")
    r = subprocess.run(
        [PYTHON, "-m", "gearlever", "workbench", "--no-browser", *args],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert r.returncode == 2
    assert r.stdout == "" and len(r.stderr.strip().splitlines()) == 1 and word in r.stderr


def test_workbench_port_in_use_exits_2_naming_it(tmp_path):
    import socket

    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(1)
    port = s.getsockname()[1]
    try:
        r = subprocess.run(
            [PYTHON, "-m", "gearlever", "workbench", "--no-browser", "--port", str(port), str(tmp_path)],
            capture_output=True,
            text=True,
            timeout=60,
        )
    finally:
        s.close()
    assert r.returncode == 2 and str(port) in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_workbench_is_a_registered_command():
    r = subprocess.run([PYTHON, "-m", "gearlever", "workbench", "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "--no-browser" in r.stdout and "--scheduler" in r.stdout


# The driver of the test below: Ctrl-C ignored as a background job of a non-interactive shell inherits it (CI's
# ``make test``), and SIGINT sent to itself the moment the URL line is written, before anything else runs.
_SIGINT_ON_THE_LINE = """
import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_IGN)
class Out:
    def __init__(self, f):
        self.f = f
    def write(self, text):
        n = self.f.write(text)
        if text.startswith("workbench: http"):
            self.f.flush()
            os.kill(os.getpid(), signal.SIGINT)
        return n
    def __getattr__(self, name):
        return getattr(self.f, name)
sys.stdout = Out(sys.stdout)
from gearlever.cli import main
sys.exit(main(["workbench", sys.argv[1], "--no-browser"]))
"""


def test_workbench_stops_on_ctrl_c_sent_as_soon_as_its_line_is_printed_even_when_ctrl_c_was_ignored(tmp_path):
    """The line is printed once the server's own signal handlers are in place, so a Ctrl-C right after it stops it.

    Before: the line came before uvicorn installed its handlers; in a process started with SIGINT ignored (a
    background job of a non-interactive shell, as in a full test run), a Ctrl-C in that window was lost and
    the bench ran on; after the handlers, it ended with exit 0 and nothing on stderr (uvicorn raised the
    signal again through the restored "ignore").  Now: 130 and one line.
    """
    r = subprocess.run(
        [PYTHON, "-c", _SIGINT_ON_THE_LINE, str(tmp_path)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
        env=dict(os.environ, PYTHONUNBUFFERED="1"),
    )
    assert r.stdout.startswith("workbench: http://127.0.0.1:"), r.stderr
    assert r.returncode == 130, r.stderr
    assert r.stderr.strip().splitlines() == ["gearlever: interrupted"], r.stderr
