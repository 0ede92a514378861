"""Load on a real workbench: 16 concurrent clients, 25 solves each of a ten-link model; memory over 1,000 solves.

The server is ``gearlever workbench`` started as a subprocess on a free
loopback port (its own process and worker processes, as a user runs it).
Every request is a different model (one point moved, as a drag does), so no
cache answers.  Checked: no error, p95 latency under 1 s (times the
machine's contention when other work shares its two cores, measured by
:func:`contention` and printed), and the resident memory of the
server and its workers (psutil) roughly flat over 1,000 solves (a generous
bound: 150 MB).  The figures are printed (``pytest -s``).
"""

from __future__ import annotations

import itertools
import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

#: A Watt six-bar driving two more four-bar loops in series: ten links, one input.
TEN_LINKS = """\
[mechanism]
name = "ten-link chain"
units = "mm"

[points]
O2 = [0.0, 0.0]
O4 = [40.0, 0.0]
O6 = [80.0, 10.0]
O8 = [110.0, 0.0]
O10 = [140.0, 20.0]
A = [10.0, 0.0]
B = [45.1, 28.3]
C = [55.0, 20.0]
D = [85.0, 40.0]
E = [84.0, 30.0]
F = [112.0, 35.0]
G = [118.0, 20.0]
H = [138.0, 45.0]

[links]
ground = ["O2", "O4", "O6", "O8", "O10"]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B", "C"]
link5 = ["C", "D"]
output = ["O6", "D", "E"]
link7 = ["E", "F"]
link8 = ["O8", "F", "G"]
link9 = ["G", "H"]
link10 = ["O10", "H"]

[[inputs]]
link = "crank"
"""
_SERIAL = itertools.count()
CLIENTS = 16
SOLVES = 25
TOTAL = 1000


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    ws = tmp_path_factory.mktemp("load")
    proc = subprocess.Popen(
        [sys.executable, "-m", "gearlever", "workbench", str(ws), "--port", "0", "--no-browser"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=dict(os.environ, PYTHONUNBUFFERED="1"),
    )
    try:
        line = proc.stdout.readline()
        assert line.startswith("workbench: "), proc.stderr.read()
        url = line.split(" ", 1)[1].strip()
        base, token = url.split("/?token=")
        yield proc, base, token
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()


def _rss(pid: int) -> float:
    """Resident memory of a process and its children (MB)."""
    import psutil

    p = psutil.Process(pid)
    procs = [p, *p.children(recursive=True)]
    total = 0
    for q in procs:
        try:
            total += q.memory_info().rss
        except psutil.NoSuchProcess:
            pass
    return total / 2**20


def _solver(base, token):
    import httpx

    client = httpx.Client(base_url=base, headers={"Authorization": f"Bearer {token}"}, timeout=60)

    count = [0]

    def solve() -> float:
        # every request a different model, as when a joint is dragged: nothing is answered from a cache
        y = 45.0 + 1e-3 * next(_SERIAL)
        model = TEN_LINKS.replace("H = [138.0, 45.0]", f"H = [138.0, {y!r}]")
        t0 = time.perf_counter()
        r = client.post("/api/solve", json={"model": model, "frames": 360})
        dt = time.perf_counter() - t0
        assert r.status_code == 200, r.text[:300]
        if count[0] % SOLVES == 0:  # the clients share the two cores with the server: read one answer in 25
            d = r.json()
            assert d["message"] == "" and len(d["point"]["H"]) == 360
        count[0] += 1
        return dt

    return client, solve


def contention() -> float:
    """How much slower than its CPU time a fixed single-threaded workload runs now (>= 1): the machine's load.

    The load bound of 1 s is for this machine unshared; when other work shares its two cores, the bound
    is scaled by this factor (printed with the figures).
    """
    data = [i * 0.001 for i in range(200_000)]
    best = float("inf")
    for _ in range(3):
        w0, c0 = time.perf_counter(), time.process_time()
        json.loads(json.dumps(data))
        best = min(best, (time.perf_counter() - w0) / max(time.process_time() - c0, 1e-9))
    return max(1.0, best)


def _wait_ready(base, token, timeout=60):
    client, solve = _solver(base, token)
    deadline = time.monotonic() + timeout
    with client:
        while True:
            try:
                solve()
                solve()
                return
            except Exception:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.5)


def test_sixteen_clients_twenty_five_solves_each_p95_under_a_second_and_memory_flat(server):
    proc, base, token = server
    _wait_ready(base, token)
    # warm-up, then the memory before
    client, solve = _solver(base, token)
    with client:
        for _ in range(20):
            solve()
    rss_before = _rss(proc.pid)
    factor = contention()

    times: list[float] = []
    errors: list[BaseException] = []
    lock = threading.Lock()

    def run(n):
        c, s = _solver(base, token)
        with c:
            for _ in range(n):
                try:
                    dt = s()
                except BaseException as exc:  # collected and failed below
                    with lock:
                        errors.append(exc)
                    return
                with lock:
                    times.append(dt)

    t0 = time.perf_counter()
    threads = [threading.Thread(target=run, args=(SOLVES,)) for _ in range(CLIENTS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    wall = time.perf_counter() - t0
    assert not errors, errors[:3]
    lat = np.array(times)
    p50, p95 = np.percentile(lat, 50) * 1000, np.percentile(lat, 95) * 1000
    print(
        f"\nload: {CLIENTS} clients x {SOLVES} solves of a ten-link model (360 frames): "
        f"p50 {p50:.0f} ms, p95 {p95:.0f} ms, max {lat.max() * 1000:.0f} ms, {len(lat) / wall:.1f} solves/s; "
        f"machine contention x{factor:.2f} before (load average {os.getloadavg()[0]:.1f})"
    )
    assert len(lat) == CLIENTS * SOLVES
    factor = max(factor, contention())  # the other work on the machine may have grown during the run
    assert p95 < 1000.0 * factor

    # the rest of 1,000 solves, 16 at a time, then the memory after
    rest = TOTAL - CLIENTS * SOLVES
    shares = [rest // CLIENTS + (1 if i < rest % CLIENTS else 0) for i in range(CLIENTS)]
    threads = [threading.Thread(target=run, args=(n,)) for n in shares]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors[:3]
    rss_after = _rss(proc.pid)
    print(f"memory (server + workers, RSS): {rss_before:.0f} MB before, {rss_after:.0f} MB after {len(times)} solves")
    assert len(times) == TOTAL
    assert rss_after - rss_before < 150.0
