"""The workbench HTTP API through Starlette's test client: every route, its answers and its error codes.

The numbers a route answers are checked against the library called directly
(:meth:`gearlever.mechanism.Mechanism.solve`), the velocities against finite
differences of the positions, the transmission angle against the law of
cosines of the four-bar (Shigley and Uicker, *Theory of Machines and
Mechanisms*, sec. 2.11).
"""

from __future__ import annotations

import json
import math
import time

import numpy as np
import pytest

from tests.workbench._client import api_client, error_line, example_text, ok

FOURBAR = example_text("fourbar")


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with api_client(tmp_path_factory.mktemp("workspace")) as c:
        yield c


# --------------------------------------------------------------------------- examples, openapi
def test_examples_list_the_shipped_models_with_links_and_each_opens(client):
    names = [e["name"] for e in ok(client.get("/api/examples"))["examples"]]
    assert {"fourbar", "watt_sixbar", "zrdpm_gear_contour", "slider_crank"} <= set(names)
    assert "law_lift" not in names  # a law, not a model
    assert ok(client.get("/api/examples/fourbar"))["model"] == FOURBAR
    assert "unknown example" in error_line(client.get("/api/examples/nope"), 404)


def test_openapi_document_names_every_api_route(client):
    doc = ok(client.get("/api/openapi.json"))
    assert doc["openapi"].startswith("3.")
    for path in (
        "/api/parse",
        "/api/dump",
        "/api/solve",
        "/api/structure",
        "/api/forces",
        "/api/export/{format}",
        "/api/jobs",
        "/api/jobs/{id}",
        "/api/jobs/{id}/events",
        "/api/files",
        "/api/files/{name}",
        "/api/examples",
        "/api/examples/{name}",
    ):
        assert path in doc["paths"], path


def test_unknown_route_and_method_answer_json_errors(client):
    assert "no route" in error_line(client.get("/api/nothing"), 404)
    assert "not allowed" in error_line(client.delete("/api/solve"), 405)


# --------------------------------------------------------------------------- parse, dump
def test_parse_answers_the_model_its_dof_and_inputs(client):
    d = ok(client.post("/api/parse", json={"model": FOURBAR}))
    assert d["dof"] == 1 and d["inputs"] == ["crank"]
    assert d["model"]["links"]["coupler"] == ["A", "B", "P"]


def test_parse_error_names_the_toml_line(client):
    text = '[points]\nO = [0, 0]\nA = [1, 0\n[links]\nground = ["O"]\n'
    r = client.post("/api/parse", json={"model": text})
    assert "TOML syntax error" in error_line(r, 400)
    assert r.json()["line"] in (3, 4)


def test_parse_refusal_names_the_element(client):
    text = FOURBAR.replace('rocker  = ["O4", "B"]', 'rocker  = ["O4", "Q"]')
    assert "Q" in error_line(client.post("/api/parse", json={"model": text}), 400)


@pytest.mark.parametrize("name", ["fourbar", "watt_sixbar", "zrdpm_gear_contour", "slider_crank", "whitworth"])
def test_dump_round_trips_parse(client, name):
    parsed = ok(client.post("/api/parse", json={"model": example_text(name)}))
    text = ok(client.post("/api/dump", json={"model": parsed["model"]}))["model"]
    again = ok(client.post("/api/parse", json={"model": text}))
    assert again["model"] == parsed["model"]


@pytest.mark.parametrize("name", ["fourbar", "zrdpm_gear_contour", "watt_sixbar"])
def test_an_edit_builds_its_mechanism_once_and_it_is_the_one_its_text_reads_to(name, monkeypatch):
    from gearlever.mechanism import Mechanism
    from gearlever.workbench import engine

    obj = engine.parse(example_text(name))["model"]
    obj["points"] = {k: [x + 1e-3, y] for k, (x, y) in obj["points"].items()}  # a model not seen before
    built = []
    real = engine._mechanism
    monkeypatch.setattr(engine, "_mechanism", lambda *a, **k: built.append(1) or real(*a, **k))
    answer = engine.dump_solve(obj, frames=12)
    assert len(built) == 1  # dump builds it; the solve of its text finds it
    cached = engine.load(answer["toml"])
    assert len(built) == 1 and cached.model == Mechanism.loads(answer["toml"]).model
    # and it moves as the mechanism read from the text does, row by row
    fresh = Mechanism.loads(answer["toml"])
    q = fresh.sketch_inputs[None, :] + np.linspace(0.0, 1.0, 7)[:, None]
    a, b = cached.solve(q), fresh.solve(q)
    for p in fresh.model.points:
        np.testing.assert_array_equal(a.point[p], b.point[p])


def test_dump_refuses_a_non_object_and_a_bad_model(client):
    assert "JSON object" in error_line(client.post("/api/dump", json={"model": "text"}), 400)
    assert "links" in error_line(client.post("/api/dump", json={"model": {"points": {"A": [0, 0]}}}), 400)


# --------------------------------------------------------------------------- solve
def test_solve_answers_the_library_positions_for_every_frame(client):
    from gearlever.mechanism import Mechanism

    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 72}))
    mech = Mechanism.from_dict(ok(client.post("/api/parse", json={"model": FOURBAR}))["model"])
    q = mech.sketch_inputs[0] + 2 * np.pi * np.arange(72) / 72
    r = mech.solve(q)
    for p in ("A", "B", "P"):
        got = np.array(d["point"][p], dtype=float)
        assert np.allclose(got, r.point[p], atol=1e-4 * 40), p  # 6 digits of the model's size
    assert np.allclose(d["input_deg"], np.degrees(q), atol=1e-3)
    assert d["closed"] == [True] * 72 and d["message"] == ""
    assert d["dof"] == 1 and d["redundant"] == 0 and d["input_kind"] == {"crank": "angle"}
    assert d["direction"] == [1] * 72
    assert len(d["extent"]) == 4 and d["extent"][0] < d["extent"][2]


def test_solve_velocity_is_the_derivative_of_position_per_radian_of_the_input(client):
    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 360}))
    P = np.array(d["point"]["P"], dtype=float)
    V = np.array(d["velocity"]["P"], dtype=float)
    A = np.array(d["acceleration"]["P"], dtype=float)
    h = 2 * np.pi / 360  # positions at 6 digits of the size: a finer step would difference their rounding
    fd_v = (np.roll(P, -1, axis=0) - np.roll(P, 1, axis=0)) / (2 * h)
    fd_a = (np.roll(V, -1, axis=0) - np.roll(V, 1, axis=0)) / (2 * h)
    scale_v, scale_a = np.abs(V).max(), np.abs(A).max()
    assert np.abs(fd_v - V).max() < 2e-3 * scale_v
    assert np.abs(fd_a - A).max() < 2e-3 * scale_a
    w = np.array(d["omega"]["coupler"])
    th = np.radians(np.unwrap(np.radians(d["angle_deg"]["coupler"]), period=2 * np.pi) * 180 / np.pi)
    fd_w = (np.roll(th, -1) - np.roll(th, 1)) / (2 * h)
    assert np.abs(fd_w[1:-1] - w[1:-1]).max() < 2e-3 * np.abs(w).max()


def test_solve_transmission_angle_is_the_law_of_cosines_angle_at_the_rocker_pin(client):
    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 36}))
    A, B = np.array(d["point"]["A"]), np.array(d["point"]["B"])
    O4 = np.array([40.0, 0.0])
    b, c = np.hypot(*(B - A).T), np.hypot(*(B - O4).T)  # coupler A-B, rocker O4-B
    f = np.hypot(*(A - O4).T)  # the diagonal A-O4
    mu = np.degrees(np.arccos((b**2 + c**2 - f**2) / (2 * b * c)))
    assert np.allclose(d["transmission_deg"], mu, atol=1e-3)


def test_solve_gives_instant_centres_and_gear_pitch_circles(client):
    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 8}))
    assert d["centres"] is not None and all(len(v) == 8 for v in d["centres"].values())
    g = ok(client.post("/api/solve", json={"model": example_text("geared_fivebar"), "frames": 8}))
    assert g["gears"] and all(x["radius"] > 0 for x in g["gears"])


def test_solve_with_two_inputs_turns_the_first_and_holds_the_second_at_its_start(client):
    d = ok(
        client.post(
            "/api/solve", json={"model": example_text("fivebar_two_inputs"), "frames": 12, "inputs": {"right": 80}}
        )
    )
    assert len(d["inputs"]) == 2
    assert d["inputs_deg"]["right"] == [80.0] * 12


def test_solve_of_a_model_that_does_not_assemble_says_where_and_why(client):
    # crank 25 of a 40 ground, coupler 10, rocker 10: B cannot be reached for most crank angles
    text = (
        "[points]\nO2 = [0, 0]\nO4 = [40, 0]\nA = [25, 0]\nB = [32, 6]\n"
        '[links]\nground = ["O2", "O4"]\ncrank = ["O2", "A"]\ncoupler = ["A", "B"]\nrocker = ["O4", "B"]\n'
        '[[inputs]]\nlink = "crank"\n'
    )
    # from the sketch the crank rocks between its dead points (+-21.9049 deg: |A O4| = sqrt(85) + 10), one oscillation
    d = ok(client.post("/api/solve", json={"model": text, "frames": 36}))
    dead = math.degrees(math.acos((25**2 + 40**2 - (math.sqrt(85) + 10) ** 2) / (2 * 25 * 40)))
    assert all(d["closed"]) and abs(max(d["input_deg"]) - dead) < 1e-3 and abs(min(d["input_deg"]) + dead) < 1e-3
    assert (
        d["message"]
        == f"crank rocks between {-dead:.4f} and {dead:.4f} deg (dead points: links coupler, rocker): one oscillation"
    )
    # started at 120 deg, where it cannot assemble: where and why
    d = ok(client.post("/api/solve", json={"model": text, "frames": 36, "inputs": {"crank": 120}}))
    assert not all(d["closed"])
    first = d["closed"].index(False)
    assert d["message"].startswith(f"crank at {d['input_deg'][first]:.4g} deg")
    # the gap at that crank angle: |A O4| less the coupler (|A B| = sqrt(85)) and the rocker (|O4 B| = 10)
    a = math.radians(d["input_deg"][first])
    gap = math.hypot(25 * math.cos(a) - 40, 25 * math.sin(a)) - math.sqrt(85) - 10
    assert gap > 0
    assert f"B cannot be reached, links coupler and rocker {gap:.3g} short" in d["message"]
    assert all(p is None for p in [d["point"]["B"][i] for i, c in enumerate(d["closed"]) if not c])


@pytest.mark.parametrize(
    ("body", "word"),
    [
        ({"model": FOURBAR, "frames": 1}, "frames"),
        ({"model": FOURBAR, "frames": 3601}, "frames"),
        ({"model": FOURBAR, "frames": 36.5}, "frames"),
        ({"model": FOURBAR, "frames": True}, "frames"),
        ({"model": FOURBAR, "inputs": {"nope": 1}}, "inputs"),
        ({"model": FOURBAR, "inputs": {"crank": "x"}}, "inputs.crank"),
        ({"model": FOURBAR, "inputs": [1]}, "inputs"),
        ({"model": 3}, "model"),
        ({}, "model"),
        ({"model": FOURBAR, "extra": 1}, "extra"),
    ],
)
def test_solve_refusals_name_the_field(client, body, word):
    assert word in error_line(client.post("/api/solve", json=body), 400)


def test_solve_refuses_bodies_that_are_not_json_objects(client):
    assert "not JSON" in error_line(
        client.post("/api/solve", content=b"{", headers={"content-type": "application/json"}), 400
    )
    assert "JSON object" in error_line(client.post("/api/solve", json=[1, 2]), 400)
    assert "NaN" in error_line(client.post("/api/solve", content=b'{"model": NaN}'), 400)


def test_caps_on_links_and_link_frames_are_named(client):
    from gearlever.workbench.engine import MAX_LINKS, MAX_WORK

    n = MAX_LINKS + 1
    pts = "\n".join(f"P{i} = [{i}, 0]" for i in range(n + 1))
    links = "\n".join(f'l{i} = ["P{i}", "P{i + 1}"]' for i in range(n))
    text = f'[points]\n{pts}\n[links]\nground = ["P0"]\n{links}\n[[inputs]]\nlink = "l0"\n'
    assert str(MAX_LINKS) in error_line(client.post("/api/solve", json={"model": text}), 400)
    n = 80
    pts = "\n".join(f"P{i} = [{i}, 0]" for i in range(n + 1))
    links = "\n".join(f'l{i} = ["P{i}", "P{i + 1}"]' for i in range(n))
    text = f'[points]\n{pts}\n[links]\nground = ["P0"]\n{links}\n' + "".join(
        f'[[inputs]]\nlink = "l{i}"\n' for i in range(n)
    )
    assert str(MAX_WORK) in error_line(client.post("/api/solve", json={"model": text, "frames": 3600}), 400)


def test_body_over_the_cap_is_413_naming_the_cap(client):
    from gearlever.workbench.app import MAX_BODY_BYTES

    big = json.dumps({"model": "#" * (MAX_BODY_BYTES + 10)})
    assert str(MAX_BODY_BYTES) in error_line(client.post("/api/solve", content=big), 413)


def test_model_text_over_the_character_cap_is_named(client):
    from gearlever.workbench.engine import MAX_MODEL_CHARS

    assert str(MAX_MODEL_CHARS) in error_line(
        client.post("/api/parse", json={"model": "#" * (MAX_MODEL_CHARS + 1)}), 400
    )


def test_a_solve_past_its_time_cap_is_stopped_and_the_bench_goes_on(tmp_path):
    with api_client(tmp_path, solve_seconds=0.001, workers=1) as c:
        time.sleep(0.5)
        msg = error_line(c.post("/api/solve", json={"model": FOURBAR, "frames": 3600}), 400)
        assert "cap of 0.001 s" in msg
    with api_client(tmp_path, workers=1) as c:
        assert ok(c.post("/api/solve", json={"model": FOURBAR, "frames": 10}))["frames"] == 10


# --------------------------------------------------------------------------- structure, forces, export
def test_structure_answers_mobility_and_says_when_inputs_do_not_match(client):
    d = ok(client.post("/api/structure", json={"model": FOURBAR}))
    assert (d["dof"], d["redundant"], d["inputs"], d["message"]) == (1, 0, ["crank"], "")
    assert {"point": "A", "links": ["crank", "coupler"]} in d["joints"]
    two = FOURBAR + '\n[[inputs]]\nlink = "rocker"\n'
    r = client.post("/api/structure", json={"model": two})
    assert r.status_code == 400 or "degrees of freedom" in r.json()["message"]


def test_forces_torque_does_the_work_of_the_loads_over_a_turn(client):
    """Virtual work over a turn at constant speed: the input torque's work is the loads' (gravity: 0)."""
    d = ok(client.post("/api/forces", json={"model": example_text("engine"), "frames": 360, "rpm": {"crank": 60}}))
    tau = np.array(d["torque"]["crank"], dtype=float)
    assert len(tau) == 360 and np.isfinite(tau).all()
    assert d["pin"] and d["units"]["torque"].startswith("N")
    assert "rpm" in error_line(client.post("/api/forces", json={"model": FOURBAR, "rpm": {"nope": 1}}), 400)
    assert "rpm" in error_line(client.post("/api/forces", json={"model": FOURBAR, "rpm": {"crank": 0}}), 400)


@pytest.mark.parametrize(
    ("fmt", "ctype", "magic"),
    [
        ("svg", "image/svg+xml", b"<?xml"),
        ("png", "image/png", b"\x89PNG"),
        ("csv", "text/csv", b"input_crank_deg"),
        ("html", "text/html", b"<!DOCTYPE html>"),
        ("toml", "application/toml", b"[mechanism]"),
    ],
)
def test_export_answers_the_file_with_its_type_and_name(client, fmt, ctype, magic):
    r = client.post(f"/api/export/{fmt}", json={"model": FOURBAR, "frames": 36})
    assert r.status_code == 200, r.text[:300]
    assert r.headers["content-type"].startswith(ctype)
    assert (
        r.headers["content-disposition"].startswith("attachment; filename=")
        and f'.{fmt}"' in r.headers["content-disposition"]
    )
    assert magic in r.content[:400]


def test_export_csv_rows_are_the_frames(client):
    r = client.post("/api/export/csv", json={"model": FOURBAR, "frames": 36})
    lines = r.text.strip().splitlines()
    assert len(lines) == 37 and lines[0].split(",")[0] == "input_crank_deg"


def test_export_unknown_format_is_404(client):
    assert "format" in error_line(client.post("/api/export/docx", json={"model": FOURBAR}), 404)


# --------------------------------------------------------------------------- jobs
def _wait(client, job_id, timeout=120):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        j = ok(client.get(f"/api/jobs/{job_id}"))
        if j["state"] != "running":
            return j
        time.sleep(0.2)
    raise AssertionError("job did not end")


MOTION = {"kind": "motion", "poses": [[0, 0, 0], [1, 0.5, 20], [2, 0.5, 45]], "fixed_pivots": [[0, -2], [2.5, -2]]}


def test_motion_job_answers_a_model_that_passes_through_the_poses(client):
    from gearlever.mechanism import Mechanism

    job_id = ok(client.post("/api/jobs", json=MOTION), 202)["id"]
    j = _wait(client, job_id)
    assert j["state"] == "done", j
    best = j["results"][0]
    assert best["rank"] == 1 and best["score"]["residual"] < 1e-9
    m = Mechanism.from_dict(ok(client.post("/api/parse", json={"model": best["model"]}))["model"])
    assert m.structure().dof == 1
    assert m.model.points["P"] == (0.0, 0.0)  # the coupler point at the first pose


def test_function_job_answers_a_four_bar(client):
    body = {
        "kind": "function",
        "expr": "log10(x)",
        "x_range": [1, 2],
        "input_range_deg": [45, 105],
        "output_range_deg": [135, 225],
        "points": 3,
    }
    j = _wait(client, ok(client.post("/api/jobs", json=body), 202)["id"])
    assert j["state"] == "done", j
    assert "[links]" in j["results"][0]["model"]


def test_second_job_while_one_runs_is_409_with_the_running_id_and_cancel_stops_it(client):
    body = {"kind": "curve", "target": [[math.cos(t), math.sin(t)] for t in np.linspace(0, 6.2, 40)], "time": 600}
    first = ok(client.post("/api/jobs", json=body), 202)["id"]
    r = client.post("/api/jobs", json=MOTION)
    assert r.status_code == 409 and r.json()["id"] == first
    assert ok(client.delete(f"/api/jobs/{first}"))["state"] == "cancelled"
    j = ok(client.get(f"/api/jobs/{first}"))
    assert j["state"] == "cancelled"
    proc = client.app.state.jobs.get(first).process
    assert not proc.is_alive()  # the job's process is stopped, not left running
    # the bench takes the next job
    assert _wait(client, ok(client.post("/api/jobs", json=MOTION), 202)["id"])["state"] == "done"


def test_job_events_stream_progress_until_the_end(client):
    job_id = ok(client.post("/api/jobs", json=MOTION), 202)["id"]
    events = []
    with client.stream("GET", f"/api/jobs/{job_id}/events") as s:
        assert s.headers["content-type"].startswith("text/event-stream")
        for line in s.iter_lines():
            if line.startswith("data: "):
                events.append(json.loads(line[6:]))
    assert events and events[-1]["state"] == "done" and events[-1]["results"]


@pytest.mark.parametrize(
    ("body", "word"),
    [
        ({"kind": "nope"}, "kind"),
        ({}, "kind"),
        ({"kind": "path", "target": [[0, 0]]}, "target"),
        ({"kind": "path", "target": [[0, 0], [1, "x"], [2, 2]]}, "target[1]"),
        ({"kind": "path", "target": [[0, 0], [1, 1], [2, 2]], "budget": 5}, "budget"),
        ({"kind": "curve", "target": [[0, 0], [1, 1], [2, 2]], "time": 0.1}, "time"),
        ({"kind": "function", "expr": "x+", "x_range": [1, 2]}, "expr"),
        ({"kind": "motion", "poses": [[0, 0, 0], [1, 0, 10]]}, "poses"),
        ({"kind": "motion", "poses": [[0, 0, 0], [1, 0, 10], [2, 0, 20]]}, "pivots"),
        ({"kind": "law", "law": "[law\n"}, "law"),
        ({"kind": "motion", "poses": [[0, 0, 0]] * 3, "colour": 1}, "colour"),
    ],
)
def test_job_refusals_name_the_field_before_anything_starts(client, body, word):
    assert word in error_line(client.post("/api/jobs", json=body), 400)


def test_unknown_job_is_404(client):
    assert "job" in error_line(client.get("/api/jobs/abc"), 404)
    assert "job" in error_line(client.delete("/api/jobs/abc"), 404)
    assert "job" in error_line(client.get("/api/jobs/abc/events"), 404)


# --------------------------------------------------------------------------- files
def test_files_put_get_list_with_etags(client):
    r = client.put("/api/files/new.toml", json={"model": FOURBAR})
    created = ok(r, 201)
    assert r.headers["etag"] == created["etag"]
    r = client.get("/api/files/new.toml")
    assert ok(r)["model"] == FOURBAR and r.headers["etag"] == created["etag"]
    names = [f["name"] for f in ok(client.get("/api/files"))["files"]]
    assert "new.toml" in names
    # overwrite: If-Match required (428), stale refused (412), current accepted (200)
    edited = FOURBAR.replace("45.0]", "46.0]")
    assert "If-Match" in error_line(client.put("/api/files/new.toml", json={"model": edited}), 428)
    stale = client.put("/api/files/new.toml", json={"model": edited}, headers={"If-Match": '"0000"'})
    assert "changed" in error_line(stale, 412)
    r = client.put("/api/files/new.toml", json={"model": edited}, headers={"If-Match": created["etag"]})
    assert ok(r)["etag"] != created["etag"]
    # the old ETag is stale now
    assert error_line(
        client.put("/api/files/new.toml", json={"model": FOURBAR}, headers={"If-Match": created["etag"]}), 412
    )
    assert ok(client.get("/api/files/new.toml"))["model"] == edited


def test_files_write_leaves_no_temporary_file(client):
    ws = client.app.state.files.root
    ok(client.put("/api/files/clean.toml", json={"model": FOURBAR}), 201)
    assert not [p for p in ws.iterdir() if p.name.startswith(".")]


def test_files_refuse_what_is_not_a_model(client):
    assert "TOML" in error_line(client.put("/api/files/bad.toml", json={"model": "[a\n"}), 400)
    assert "JSON object" in error_line(client.put("/api/files/bad.links.json", json={"model": "[1]"}), 400)
    assert error_line(client.get("/api/files/missing.toml"), 404)
    assert ".toml" in error_line(client.get("/api/files/notes.txt"), 400)


def test_a_call_whose_request_went_away_does_not_answer_the_next_call():
    """The pool's worker still finishes the abandoned solve; its reply is skipped, never given to the next caller."""
    import asyncio

    from gearlever.workbench.app import WorkerPool

    async def run():
        pool = WorkerPool(1)
        await pool.start()
        try:
            first = asyncio.create_task(pool.call("solve", 60.0, text=FOURBAR, frames=3600))
            await asyncio.sleep(0.05)
            first.cancel()
            answer = await pool.call("parse", 60.0, text=FOURBAR)
            return json.loads(answer)
        finally:
            pool.close()

    d = asyncio.run(run())
    assert d["dof"] == 1 and "model" in d and "point" not in d


def test_a_rocking_input_is_drawn_and_loaded_over_one_oscillation_as_analyze_sweeps_it(client):
    """PMKS+'s Watt I six-bar rocks between 67.3 and 78.3 deg: before, 118 of 120 frames did not assemble."""
    import numpy as np

    from gearlever.mechanism import Mechanism, sweep_rows

    text = example_text("watt_i")
    d = ok(client.post("/api/solve", json={"model": text, "frames": 120}))
    m = Mechanism.loads(text)
    s = sweep_rows(m, 120)
    assert s.oscillates and all(d["closed"]) and d["direction"] == s.direction.tolist()
    np.testing.assert_allclose(d["input_deg"], np.degrees(s.q[:, 0]), atol=1e-4)  # the answer's 6 digits
    assert d["message"].startswith("AB rocks between 67.2")
    f = ok(client.post("/api/forces", json={"model": text, "frames": 120}))
    want = m.inverse_dynamics(s.q, s.qdot, np.zeros_like(s.q)).input_force[:, 0]
    got = np.array(f["torque"]["AB"], dtype=float)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-5 * np.abs(want).max())  # 6 digits of the largest
