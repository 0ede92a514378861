"""The workbench API's design aids through Starlette's test client: Kennedy's lines, forces, assembly branch, export.

Kennedy's lines are checked against the Aronhold-Kennedy theorem (the three instant centres of three bodies
lie on one line: J. J. Uicker, G. R. Pennock and J. E. Shigley, *Theory of Machines and Mechanisms*, 5th ed.,
ch. 3); the forces against the library called directly and against virtual work (input power equals the
rate of work of the loads); the export against the library's writer (:mod:`gearlever.export`).
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.workbench._client import api_client, error_line, example_text, ok

FOURBAR = example_text("fourbar")


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with api_client(tmp_path_factory.mktemp("workspace")) as c:
        yield c


# --------------------------------------------------------------------------- Kennedy's lines
@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "watt_sixbar"])
def test_kennedy_triples_name_three_centres_on_one_line_uicker_pennock_shigley_ch3(client, name):
    d = ok(client.post("/api/solve", json={"model": example_text(name), "frames": 36}))
    bodies = ["ground"] + list(d["angle_deg"])
    n = len(bodies)
    assert len(d["kennedy"]) == n * (n - 1) * (n - 2) // 6
    for keys in d["kennedy"]:
        assert len(keys) == 3 and all(k in d["centres"] for k in keys)
        assert len({b for k in keys for b in k.split("/")}) == 3  # three bodies, their three pairs
    span = max(d["extent"][2] - d["extent"][0], d["extent"][3] - d["extent"][1])
    eps = 2e-5 * span  # the centres are answered at 6 significant digits of the model's size
    checked = 0
    for i in range(36):
        if not d["closed"][i]:
            continue
        for keys in d["kennedy"]:
            pts = [d["centres"][k][i] for k in keys]
            dirs = {k: r[1:] for k in keys for r in d["centre_direction"].get(k, []) if r[0] == i}
            fin = [np.array(p) for p in pts if p is not None]
            if len(fin) == 3:
                u, v = fin[1] - fin[0], fin[2] - fin[0]
                lu, lv = np.hypot(*u), np.hypot(*v)
                if lu > 100 * eps and lv > 100 * eps:
                    assert abs(u[0] * v[1] - u[1] * v[0]) <= eps * (lu + lv) + 1e-9 * lu * lv, (i, keys)
                    checked += 1
            elif len(fin) == 2 and dirs:
                u = fin[1] - fin[0]
                w = np.array(next(iter(dirs.values())))
                if np.hypot(*u) > 100 * eps:
                    assert abs(u[0] * w[1] - u[1] * w[0]) <= 2 * eps + 1e-5 * np.hypot(*u), (i, keys)
                    checked += 1
    assert checked >= 36


def test_centre_direction_of_a_slider_is_normal_to_its_guide(client):
    d = ok(client.post("/api/solve", json={"model": example_text("slider_crank"), "frames": 12}))
    # the piston translates on a horizontal guide: its centre with the ground is at infinity, straight up or down
    key = next(k for k in d["centre_direction"] if set(k.split("/")) == {"ground", "piston"})
    rows = d["centre_direction"][key]
    assert len(rows) == 12 and all(abs(abs(uy) - 1) < 1e-6 and abs(ux) < 1e-6 for _, ux, uy in rows)
    assert all(p is None for p in d["centres"][key])


def test_no_kennedy_lines_past_the_centre_cap(client):
    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 8, "centres": False}))
    assert d["centres"] is None and d["kennedy"] is None and d["centre_direction"] is None


# --------------------------------------------------------------------------- assembly branch
def test_branch_moves_the_dyad_joint_to_the_mirror_of_the_line_of_its_pins_and_back(client):
    import tomllib

    d = ok(client.post("/api/solve", json={"model": FOURBAR, "frames": 8}))
    assert d["branches"] == [
        {"joint": "B", "links": ["coupler", "rocker"], "kind": "RRR", "about": ["A", "O4"], "sigma": 1.0}
    ]
    flipped = ok(client.post("/api/branch", json={"model": FOURBAR, "joint": "B"}))["model"]
    p0, p1 = tomllib.loads(FOURBAR)["points"], tomllib.loads(flipped)["points"]
    A, O4, B, B1 = (np.array(p, dtype=float) for p in (p0["A"], p0["O4"], p0["B"], p1["B"]))
    # B mirrored about the line A-O4 (the second intersection of the circles about A and O4)
    u = (O4 - A) / np.hypot(*(O4 - A))
    foot = A + u * np.dot(B - A, u)
    assert np.allclose(B1, 2 * foot - B, atol=1e-9)
    # the coupler point P moves rigidly with the coupler: its distances to A and B are kept, its side too
    P, P1 = np.array(p0["P"], dtype=float), np.array(p1["P"], dtype=float)
    assert np.isclose(np.hypot(*(P1 - A)), np.hypot(*(P - A))) and np.isclose(np.hypot(*(P1 - B1)), np.hypot(*(P - B)))
    cross = lambda a, b, c: (b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]  # noqa: E731
    assert np.sign(cross(A, B, P)) == np.sign(cross(A, B1, P1))
    assert p1["O2"] == p0["O2"] and p1["O4"] == p0["O4"] and p1["A"] == p0["A"]
    s = ok(client.post("/api/solve", json={"model": flipped, "frames": 36}))
    assert s["branches"][0]["sigma"] == -1.0 and all(s["closed"])
    back = ok(client.post("/api/branch", json={"model": flipped, "joint": "B"}))["model"]
    assert tomllib.loads(back)["points"] == {k: [float(c) for c in v] for k, v in p0.items()}


def test_branch_refusals_name_the_joint(client):
    assert "'A' is not placed by a dyad" in error_line(
        client.post("/api/branch", json={"model": FOURBAR, "joint": "A"}), 400
    )
    assert "joint: missing" in error_line(client.post("/api/branch", json={"model": FOURBAR}), 400)
    geared = example_text("geared_fivebar")
    assert "no assembly branch" in error_line(client.post("/api/branch", json={"model": geared, "joint": "C"}), 400)


# --------------------------------------------------------------------------- export
def test_export_dxf_has_a_layer_per_link_and_audits_clean(client, tmp_path):
    import ezdxf

    r = client.post("/api/export/dxf", json={"model": FOURBAR, "frames": 36, "inputs": {"crank": 90}})
    assert r.status_code == 200 and r.headers["content-type"].startswith("application/dxf")
    assert 'filename="crank-rocker_with_coupler_point.dxf"' in r.headers["content-disposition"]
    path = tmp_path / "m.dxf"
    path.write_bytes(r.content)
    doc = ezdxf.readfile(path)
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"ground", "crank", "coupler", "rocker"} <= layers and not doc.audit().has_errors


def test_export_svg_outline_is_the_library_drawing_at_the_pose_asked(client):
    import math

    from gearlever.export import mechanism_drawing, svg
    from gearlever.mechanism import Mechanism

    r = client.post("/api/export/svg-outline", json={"model": FOURBAR, "frames": 36, "inputs": {"crank": 90}})
    assert r.status_code == 200 and r.headers["content-type"].startswith("image/svg+xml")
    mech = Mechanism.from_dict(__import__("tomllib").loads(FOURBAR))
    assert r.text == svg.text(mechanism_drawing(mech, {"crank": math.pi / 2}))
    assert r.text != svg.text(mechanism_drawing(mech))  # the pose asked, not the sketch


def test_export_pose_refusals(client):
    assert "inputs: a pose is for" in error_line(
        client.post("/api/export/csv", json={"model": FOURBAR, "frames": 36, "inputs": {"crank": 90}}), 400
    )
    assert "unknown input" in error_line(
        client.post("/api/export/dxf", json={"model": FOURBAR, "frames": 36, "inputs": {"nope": 90}}), 400
    )


# --------------------------------------------------------------------------- forces
LOADED = FOURBAR + '\n[[loads]]\nlink = "coupler"\npoint = "P"\nforce = [3.0, -10.0]\n'


def test_input_torque_of_a_load_alone_is_its_virtual_work_per_crank_turn(client):
    # no mass: T w + F . v_P = 0 at every frame, v_P per unit crank rate from the solve (virtual work)
    f = ok(client.post("/api/forces", json={"model": LOADED, "frames": 36, "rpm": {"crank": 60}}))
    s = ok(client.post("/api/solve", json={"model": LOADED, "frames": 36}))
    assert np.allclose(f["input_deg"], s["input_deg"])
    v = np.array(s["velocity"]["P"])
    expected = -(3.0 * v[:, 0] - 10.0 * v[:, 1])
    T = np.array(f["torque"]["crank"])
    assert np.allclose(T, expected, atol=1e-4 * np.abs(expected).max())
    assert f["units"] == {"force": "N", "torque": "N_mm"} and set(f["pin"]) >= {"A", "B", "O2", "O4"}


# --------------------------------------------------------------------------- the page's edit in one round trip
def test_solve_of_a_model_object_answers_its_toml_and_the_same_cycle_as_dump_then_solve(client):
    obj = ok(client.post("/api/parse", json={"model": FOURBAR}))["model"]
    obj["points"]["P"] = [31.0, 44.0]
    one = ok(client.post("/api/solve", json={"model": obj, "frames": 36}))
    text = ok(client.post("/api/dump", json={"model": obj}))["model"]
    two = ok(client.post("/api/solve", json={"model": text, "frames": 36}))
    assert one.pop("toml") == text and one == two
    assert "points" in error_line(client.post("/api/solve", json={"model": {"links": {}}, "frames": 36}), 400)


# --------------------------------------------------------------------------- synthesis kinds
@pytest.mark.parametrize(("family", "auto"), [("path", True), ("function", False), ("law", True)])
def test_job_types_are_the_kinds_of_the_one_synthesis_registry(family, auto):
    from gearlever.synthesis.registry import names
    from gearlever.workbench.engine import WorkbenchError, check_job

    base = {
        "path": {"target": [[0, 0], [1, 1], [2, 0]]},
        "function": {"expr": "x", "x_range": [1, 2], "input_range_deg": [0, 90], "output_range_deg": [0, 90]},
        "law": {"law": example_text("law_lift")},
    }[family]
    known = names(family) + (("auto",) if auto else ())
    for t in known:
        assert check_job({"kind": family, **base, "type": t})["type"] == t
    with pytest.raises(WorkbenchError, match=f"type must be one of {', '.join(known)}, got 'nope'"):
        check_job({"kind": family, **base, "type": "nope"})


def test_a_motion_job_runs_the_registrys_kind_for_its_number_of_poses():
    from gearlever.synthesis.motion import synthesize_motion
    from gearlever.workbench.engine import check_job, run_job

    poses = [[0.0, 0.0, 0.0], [2.0, 1.0, 20.0], [4.0, 1.0, 45.0], [5.0, 0.0, 70.0]]
    seen = []
    results = run_job(check_job({"kind": "motion", "poses": poses}), progress=lambda *a: seen.append(a[0]))
    assert seen[0] == "start" and seen[-1] == "done" and results[0]["rank"] == 1
    # the same designs as the library's driver called directly
    ref = synthesize_motion(np.array(poses)[:, :2], np.radians(np.array(poses)[:, 2]))
    good = [s for s in ref.solutions if not s.defect] or list(ref.solutions)
    assert len(results) == min(len(good), 10)
    assert results[0]["score"]["residual"] == pytest.approx(good[0].residual, rel=1e-12, abs=1e-15)
