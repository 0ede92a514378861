"""Benchmark: edit to redrawn cycle through the workbench's HTTP API, beside ``gearlever mechanism analyze``.

A real ``gearlever workbench`` (subprocess, loopback, its worker processes)
answers ``POST /api/solve`` for a whole cycle of 360 frames; each request is
an edit (one point moved by a small step, as a drag does, so no cache
answers), and the time is from sending the model to holding the parsed
answer (what the page then draws); the page's own edit sends the model as a
JSON object and the server writes its TOML and solves it in one round trip
(``page p50``, ``page p95``).  Beside them, ``server CPU``: the CPU time the
server's worker spends on one such edit (solve and JSON encoding, measured in
this process with :func:`time.process_time`, so the machine's other work does
not count).  Models: the four-bar example, the ZRDPM
gear contour example (two inputs, gears) and a 20-joint chain of six four-bar
loops.  Beside it, ``gearlever mechanism analyze MODEL --points 360`` run in
this process for the same frames (its CSV written to a temporary file), and
the ratio.  Targets: p50 at most 30 ms for the four-bar and 100 ms
for the 20-joint linkage; 30 redraws a second while dragging means p50 at
most 33 ms.

    python benchmarks/bench_workbench.py [--edits N]

Prints the CPU, the machine's load average and its contention (wall over CPU
time of a fixed single-threaded workload, 1 on an idle machine): on a shared
machine the times grow with it, and ``p50/contention`` estimates the
unshared figure.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _machine import machine_line

FRAMES = 360
TARGETS_MS = {"fourbar": 30.0, "chain20": 100.0}


def chain20() -> str:
    """A crank and six rockers in series (coupler to ternary rocker): 20 joints, 14 links."""
    pts = {"O2": (0.0, 0.0), "A": (10.0, 0.0)}
    links = {"crank": ["O2", "A"]}
    ground = ["O2"]
    prev = "A"
    for k in range(1, 7):
        x = 40.0 * k
        o, p, q = f"O{2 * k + 2}", f"P{k}", f"Q{k}"
        pts[o], pts[p], pts[q] = (x, 0.0), (x + 5.1, 28.3), (x + 8.0, 20.0)
        ground.append(o)
        links[f"coupler{k}"] = [prev, p]
        links[f"rocker{k}"] = [o, p, q]
        prev = q
    lines = ['[mechanism]\nname = "20-joint chain"\nunits = "mm"\n\n[points]']
    lines += [f"{k} = [{x!r}, {y!r}]" for k, (x, y) in pts.items()]
    lines += ["", "[links]", f"ground = {ground!r}".replace("'", '"')]
    lines += [f"{k} = {v!r}".replace("'", '"') for k, v in links.items()]
    lines += ["", "[[inputs]]", 'link = "crank"', ""]
    return "\n".join(lines)


def models() -> dict:
    from gearlever.data import example_path

    return {
        "fourbar": (Path(example_path("fourbar.toml")).read_text(), "P"),
        "zrdpm_gear_contour": (Path(example_path("zrdpm_gear_contour.toml")).read_text(), None),
        "chain20": (chain20(), "Q6"),
    }


def edited(text: str, i: int) -> str:
    """The model with its last point moved by ``1e-4 i`` in y (a drag step)."""
    lines = text.splitlines()
    start = lines.index("[points]")
    end = next(j for j in range(start + 1, len(lines)) if not lines[j].strip() or lines[j].startswith("["))
    name, _, value = lines[end - 1].partition("=")
    x, y = (float(v) for v in value.strip().strip("[]").split(","))
    lines[end - 1] = f"{name.strip()} = [{x!r}, {y + 1e-4 * i!r}]"
    return "\n".join(lines) + "\n"


def start_server(workspace: Path):
    proc = subprocess.Popen(
        [sys.executable, "-m", "gearlever", "workbench", str(workspace), "--port", "0", "--no-browser"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=dict(os.environ, PYTHONUNBUFFERED="1"),
    )
    line = proc.stdout.readline()
    if not line.startswith("workbench: "):
        raise SystemExit(f"the workbench did not start: {proc.stderr.read()}")
    base, token = line.split(" ", 1)[1].strip().split("/?token=")
    return proc, base, token


def edited_obj(obj: dict, i: int) -> dict:
    """The model object with its last point moved by ``1e-4 i`` in y (the page's drag step)."""
    pts = dict(obj["points"])
    name = list(pts)[-1]
    x, y = pts[name]
    pts[name] = [x, y + 1e-4 * i]
    return {**obj, "points": pts}


def server_cpu_ms(text: str, n: int = 15) -> float:
    """Median CPU time (ms) of the worker's share of an edit as the page sends it (the model as JSON): check,
    write the TOML, compile, solve and encode a cycle of 360 frames (``engine.dump_solve``)."""
    from gearlever.workbench import engine
    from gearlever.workbench.app import _HAS_ORJSON, _encode

    obj = engine.parse(text)["model"]
    runs = []
    for i in range(n):
        t0 = time.process_time()
        _encode(engine.dump_solve(edited_obj(obj, 10_000 + i), FRAMES, plain=not _HAS_ORJSON))
        runs.append(time.process_time() - t0)
    return float(np.median(runs[2:])) * 1000


def percentiles(times: list) -> tuple:
    return float(np.percentile(times, 50)), float(np.percentile(times, 95))


def contention() -> float:
    """How much slower than its CPU time a fixed single-threaded workload runs now (>= 1): other work's share."""
    import json

    data = [i * 0.001 for i in range(200_000)]
    best = float("inf")
    for _ in range(3):
        w0, c0 = time.perf_counter(), time.process_time()
        json.loads(json.dumps(data))
        best = min(best, (time.perf_counter() - w0) / max(time.process_time() - c0, 1e-9))
    return max(1.0, best)


def main() -> None:
    import httpx

    from gearlever.cli import main as cli

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edits", type=int, default=40, help="edits timed per model (default 40)")
    args = ap.parse_args()
    factor = contention()
    print(f"{machine_line()}; contention x{factor:.2f} (wall / CPU time of a fixed workload: 1 on an idle machine)")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        proc, base, token = start_server(tmp)
        try:
            client = httpx.Client(base_url=base, headers={"Authorization": f"Bearer {token}"}, timeout=120)
            # the worker processes warm up
            deadline = time.monotonic() + 120
            while client.post("/api/solve", json={"model": models()["fourbar"][0], "frames": 36}).status_code != 200:
                if time.monotonic() > deadline:
                    raise SystemExit("the workbench did not answer")
                time.sleep(0.5)
            print(
                f"{'model':20s} {'p50 ms':>8s} {'p95 ms':>8s} {'page p50':>9s} {'page p95':>9s} {'server CPU':>10s} "
                f"{'analyze ms':>11s} {'ratio':>6s} {'p50/contention':>14s}  target"
            )
            for name, (text, point) in models().items():
                times = []
                for i in range(args.edits + 3):
                    body = {"model": edited(text, i + 1), "frames": FRAMES}
                    t0 = time.perf_counter()
                    r = client.post("/api/solve", json=body)
                    d = r.json()
                    dt = time.perf_counter() - t0
                    if r.status_code != 200:
                        raise SystemExit(f"{name}: {r.status_code} {d}")
                    if point is not None and len(d["point"][point]) != FRAMES:
                        raise SystemExit(f"{name}: {len(d['point'][point])} frames")
                    if i >= 3:  # the first edits warm the path
                        times.append(dt * 1000)
                p50, p95 = percentiles(times)
                obj = client.post("/api/parse", json={"model": text}).json()["model"]
                page = []
                for i in range(args.edits + 3):
                    body = {"model": edited_obj(obj, i + 1), "frames": FRAMES}
                    t0 = time.perf_counter()
                    r = client.post("/api/solve", json=body)
                    d = r.json()
                    dt = time.perf_counter() - t0
                    if r.status_code != 200 or not d["toml"]:
                        raise SystemExit(f"{name}: {r.status_code} {d}")
                    if i >= 3:
                        page.append(dt * 1000)
                page50, page95 = percentiles(page)
                cpu = server_cpu_ms(text)
                path = tmp / f"{name}.toml"
                path.write_text(text)
                out = tmp / f"{name}.csv"
                runs = []
                for _ in range(5):
                    t0 = time.perf_counter()
                    code = cli(["mechanism", "analyze", str(path), "--points", str(FRAMES), "--out", str(out)])
                    runs.append((time.perf_counter() - t0) * 1000)
                    assert code == 0
                analyze = float(np.median(runs))
                target = TARGETS_MS.get(name)
                verdict = "" if target is None else f"p50 <= {target:g} ms: {'ok' if p50 <= target else 'ABOVE'}"
                print(
                    f"{name:20s} {p50:8.1f} {p95:8.1f} {page50:9.1f} {page95:9.1f} {cpu:10.1f} "
                    f"{analyze:11.1f} {p50 / analyze:6.2f} {p50 / factor:14.1f}  {verdict}"
                )
            print(f"load average now {os.getloadavg()[0]:.1f}, contention x{contention():.2f}")
            client.close()
        finally:
            proc.send_signal(signal.SIGTERM)
            proc.communicate(timeout=60)


if __name__ == "__main__":
    main()
