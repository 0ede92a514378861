"""The workbench's cam (``POST /api/cam``, ``GET /api/laws``) through Starlette's test client.

The cam and its follower are the library's (:func:`gearlever.cams.design_cam`, sized by
:func:`gearlever.cams.size_base_radius`); the answer is checked against the translating roller follower's
closed forms (R. L. Norton, *Design of Machinery*, sec. 8.6: the roller centre at ``sqrt(Rp**2 - e**2) + s``
on the follower's axis, the pressure angle ``arctan((v - e) / (s + sqrt(Rp**2 - e**2)))``), against the
geometry of contact (the cam surface touches the roller) and of the arm (an oscillating follower's roller stays
one arm from its pivot).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.workbench._client import api_client, error_line, example_text, ok


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    with api_client(tmp_path_factory.mktemp("workspace")) as c:
        yield c


def test_laws_lists_the_shipped_laws_with_their_output(client):
    laws = {e["name"]: e["output"] for e in ok(client.get("/api/laws"))["examples"]}
    assert laws == {"law_dwell_rocker": "angle", "law_lift": "displacement", "law_quick_return": "displacement"}


def test_translating_roller_cam_matches_nortons_closed_forms_and_touches_its_roller(client):
    from gearlever.data import example_path
    from gearlever.laws import load_law

    e = 4.0
    c = ok(client.post("/api/cam", json={"example": "law_lift", "centre": [10, -5], "offset": e, "frames": 360}))
    assert c["follower_kind"] == "translating-roller" and c["sized"] and c["roller_radius"] == 5.0
    law = load_law(example_path("law_lift.toml"))
    theta = np.radians(c["cam_angle_deg"])
    ev = law.evaluate(theta)
    s, v = ev.s - ev.s.min(), ev.v
    rp = c["base_radius"] + c["roller_radius"]
    y0 = math.sqrt(rp**2 - e**2)
    rc = np.array(c["roller_centre"]) - [10, -5]
    tol = 1e-5 * (c["base_radius"] + c["stroke"])  # six digits of the cam's size
    np.testing.assert_allclose(rc[:, 0], e, atol=tol)
    np.testing.assert_allclose(rc[:, 1], y0 + s, atol=tol)
    phi = np.degrees(np.arctan((v - e) / (s + y0)))
    np.testing.assert_allclose(np.abs(c["pressure_angle_deg"]), np.abs(phi), atol=1e-4)
    assert c["pressure_angle_max_deg"] <= 30.0 + 1e-9 and c["pressure_angle_max_deg"] > 29.9  # sized to the bound
    # the profile turned by the cam's angle touches the roller at every frame: nearest point one roller radius off
    prof = np.array(c["profile"]) - [10, -5]
    for k in range(0, 360, 30):
        t = math.radians(c["cam_angle_deg"][k])
        turned = prof @ np.array([[math.cos(t), math.sin(t)], [-math.sin(t), math.cos(t)]])
        gap = np.min(np.hypot(*(turned - rc[k]).T))
        assert abs(gap - c["roller_radius"]) < 0.01 * c["base_radius"], (k, gap)
    # the contact lies on the roller
    ct = np.array(c["contact"]) - [10, -5]
    np.testing.assert_allclose(np.hypot(*(ct - rc).T), c["roller_radius"], atol=2 * tol)


def test_flat_and_oscillating_followers_keep_their_geometry(client):
    flat = ok(client.post("/api/cam", json={"example": "law_lift", "follower": "translating-flat", "frames": 72}))
    a, b, ct = (np.array(x) for x in (flat["face"][0], flat["face"][1], flat["contact"]))
    # the contact lies on the face segment, which stays horizontal (the face normal is the follower's axis)
    np.testing.assert_allclose(a[:, 1], b[:, 1], atol=1e-6)
    np.testing.assert_allclose(ct[:, 1], a[:, 1], atol=1e-4)
    assert np.all((ct[:, 0] >= np.minimum(a[:, 0], b[:, 0])) & (ct[:, 0] <= np.maximum(a[:, 0], b[:, 0])))
    np.testing.assert_allclose(a[:, 1], flat["base_radius"] + np.array(flat["s"]), atol=1e-4)
    rock = ok(client.post("/api/cam", json={"example": "law_dwell_rocker", "frames": 72}))
    assert rock["follower_kind"] == "oscillating-roller" and rock["pivot"] == [100.0, 0.0]
    rc = np.array(rock["roller_centre"])
    np.testing.assert_allclose(np.hypot(*(rc - rock["pivot"]).T), rock["arm"], atol=1e-3)
    assert math.isclose(max(rock["s"]) - min(rock["s"]), 45.0, abs_tol=1e-4)  # the law's 45 deg swing


def test_a_workspace_law_text_gives_the_same_cam_as_its_example(client):
    text = example_text("law_lift")
    a = ok(client.post("/api/cam", json={"law": text, "frames": 36}))
    b = ok(client.post("/api/cam", json={"example": "law_lift", "frames": 36}))
    assert a == b


def test_a_cam_turned_by_given_angles_is_the_cam_of_the_nearest_tenth_of_a_degree(client):
    turn = ok(client.post("/api/cam", json={"example": "law_lift", "frames": 360}))
    ok_angles = [float(k) for k in range(360)]
    given = ok(client.post("/api/cam", json={"example": "law_lift", "angles_deg": ok_angles}))
    assert given["frames"] == 360 and given["cam_angle_deg"] == turn["cam_angle_deg"]
    assert given["s"] == turn["s"] and given["roller_centre"] == turn["roller_centre"]
    odd = ok(client.post("/api/cam", json={"example": "law_lift", "angles_deg": [100.04, 460.0, -150.0, 123.44]}))
    assert odd["cam_angle_deg"] == [100.0, 100.0, 210.0, 123.4]
    ref = ok(client.post("/api/cam", json={"example": "law_lift", "frames": 3600}))
    rows = (1000, 1000, 2100, 1234)
    assert min(odd["s"]) > 1.0  # on the rise and the return, not a dwell
    np.testing.assert_allclose(odd["s"], [ref["s"][k] for k in rows], atol=1e-4)
    np.testing.assert_allclose(odd["roller_centre"], [ref["roller_centre"][k] for k in rows], atol=1e-4)


@pytest.mark.parametrize(
    ("body", "field"),
    [
        ({"example": "law_lift", "follower": "oscillating-roller"}, "follower: oscillating-roller follows an angle"),
        ({"example": "law_lift", "follower": "wheel"}, "follower must be one of"),
        ({"example": "law_lift", "law": "x"}, "law: give the law's TOML text (law) or"),
        ({}, "law: give the law's TOML text"),
        ({"example": "fourbar"}, "example: unknown law 'fourbar'"),
        ({"law": example_text("fourbar")}, "law"),
        ({"example": "law_lift", "colour": 1}, "colour: not a parameter of a cam"),
        ({"example": "law_lift", "centre": [1]}, "centre must be [x, y]"),
        ({"example": "law_lift", "frames": 1}, "frames must be an integer"),
        ({"example": "law_lift", "frames": 4, "angles_deg": [0, 1]}, "frames: give frames or angles_deg"),
        ({"example": "law_lift", "angles_deg": [0, "x"]}, "angles_deg must be a list"),
        ({"example": "law_lift", "roller_radius": -1}, "roller_radius must be a number"),
        ({"example": "law_dwell_rocker", "pivot_distance": 30}, "pivot_distance"),
    ],
)
def test_cam_refusals_name_the_field_in_one_line(client, body, field):
    assert field in error_line(client.post("/api/cam", json=body), 400)


def test_cam_refusal_names_the_benchs_field_not_the_command_lines_flag(client):
    msg = error_line(client.post("/api/cam", json={"example": "law_dwell_rocker", "pivot_distance": 30}), 400)
    assert "--" not in msg and "pivot_distance" in msg


def test_cam_saved_as_a_cam_file_reopens_as_the_same_cam_at_its_pivot(client, tmp_path):
    """The answer's cam_toml is a CAM.toml the library reads (load_cam: the same surface about the pivot,
    cam_centre: the pivot); PUT as NAME.cam.toml with the model's ETag rules, listed as a cam, and POSTed back
    as ``file`` it gives the same law, follower, base radius, pivot and frames."""
    from gearlever.cams import cam_centre, design_cam, load_cam
    from gearlever.data import example_path
    from gearlever.laws import load_law

    first = ok(
        client.post("/api/cam", json={"example": "law_lift", "follower": "translating-flat", "centre": [40, 7.5]})
    )
    text = first["cam_toml"]
    path = tmp_path / "bench.cam.toml"
    path.write_text(text)
    assert cam_centre(path) == (40.0, 7.5)
    law = load_law(example_path("law_lift.toml"))
    own = design_cam(law, "translating-flat", base_radius=first["base_radius"], points=360)
    assert np.allclose(load_cam(path).surface, own.surface, rtol=1e-10, atol=1e-10 * first["base_radius"])
    saved = ok(client.put("/api/files/bench.cam.toml", json={"model": text}), 201)
    listed = {f["name"]: f["kind"] for f in ok(client.get("/api/files"))["files"]}
    assert listed["bench.cam.toml"] == "cam"
    assert "If-Match" in error_line(client.put("/api/files/bench.cam.toml", json={"model": text}), 428)
    stale = client.put("/api/files/bench.cam.toml", json={"model": text}, headers={"If-Match": '"0000"'})
    assert "changed since it was read" in error_line(stale, 412)
    r = client.get("/api/files/bench.cam.toml")
    assert r.headers["ETag"] == saved["etag"] and r.json()["model"] == text  # not clobbered
    again = ok(client.post("/api/cam", json={"file": r.json()["model"]}))
    for key in ("follower_kind", "centre", "frames", "cam_angle_deg"):
        assert again[key] == first[key], key
    assert again["base_radius"] == pytest.approx(first["base_radius"], rel=1e-11)  # written at 12 digits
    size = first["base_radius"] + first["stroke"]
    for key in ("s", "profile", "face"):
        np.testing.assert_allclose(np.array(again[key], float), np.array(first[key], float), atol=1e-9 * size)
    assert again["sized"] is False


@pytest.mark.parametrize(
    "text, says",
    [
        ("not toml = = 1", "TOML"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = 30.0\n', "law"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = 30.0\ncentre = "here"\n', "centre"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = 30.0\nwheel = 2\n', "wheel"),
    ],
)
def test_a_cam_file_that_the_library_refuses_is_not_written_and_not_drawn(client, text, says):
    line = error_line(client.put("/api/files/bad.cam.toml", json={"model": text}), 400)
    assert line.startswith("model: ") and says in line
    assert "bad.cam.toml" not in [f["name"] for f in ok(client.get("/api/files"))["files"]]
    line = error_line(client.post("/api/cam", json={"file": text}), 400)
    assert line.startswith("file: ") and says in line
    assert "one" in error_line(client.post("/api/cam", json={"file": text, "example": "law_lift"}), 400)


def test_export_dxf_and_outline_svg_carry_the_cam_profile_on_its_own_layer(client, tmp_path):
    """The cam layer's polyline is the library's profile (load_cam's surface) turned by the frame's cam angle
    about the pivot, to 1e-6; the DXF audits clean; the outline SVG has the cam's group."""
    import ezdxf

    from gearlever.cams import load_cam

    fourbar = example_text("fourbar")
    text = ok(client.post("/api/cam", json={"example": "law_lift", "centre": [30, -20], "frames": 36}))["cam_toml"]
    angle = 37.5
    body = {"model": fourbar, "frames": 36, "inputs": {"crank": 90}, "cam": text, "cam_angle_deg": angle}
    r = client.post("/api/export/dxf", json=body)
    assert r.status_code == 200, r.text
    path = tmp_path / "m.dxf"
    path.write_bytes(r.content)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    assert {"ground", "crank", "coupler", "rocker", "cam"} <= {layer.dxf.name for layer in doc.layers}
    polys = doc.modelspace().query('LWPOLYLINE[layer=="cam"]')
    assert len(polys) == 1 and polys[0].closed
    got = np.array([(p[0], p[1]) for p in polys[0].get_points("xy")])
    cam_file = tmp_path / "c.cam.toml"
    cam_file.write_text(text)
    t = math.radians(angle)
    surface = load_cam(cam_file).surface
    want = surface @ np.array([[math.cos(t), math.sin(t)], [-math.sin(t), math.cos(t)]]) + [30, -20]
    assert got.shape == want.shape and np.abs(got - want).max() <= 1e-6
    circles = doc.modelspace().query('CIRCLE[layer=="cam"]')
    assert [tuple(c.dxf.center)[:2] for c in circles] == [(30.0, -20.0)]  # the bore at the pivot
    svg = client.post("/api/export/svg-outline", json=body)
    assert svg.status_code == 200 and 'id="link-cam"' in svg.text
    # without a cam: no cam layer; a cam for a raster format or a bad cam text is refused, named
    plain = client.post("/api/export/dxf", json={k: v for k, v in body.items() if not k.startswith("cam")})
    path.write_bytes(plain.content)
    assert "cam" not in {layer.dxf.name for layer in ezdxf.readfile(path).layers}
    assert "cam:" in error_line(client.post("/api/export/png", json={"model": fourbar, "cam": text}), 400)
    bad = client.post("/api/export/dxf", json={**body, "cam": "[cam]\nfollower = 1\n"})
    assert error_line(bad, 400).startswith("cam: ")
    assert "cam_angle_deg" in error_line(client.post("/api/export/dxf", json={**body, "cam_angle_deg": "x"}), 400)
