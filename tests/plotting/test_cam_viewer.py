"""The cam page's data against the cam module: profile, follower pose, contact, escaping, refusals."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from gearlever.cams import FOLLOWERS, FollowerParams, design_cam, load_cam
from gearlever.errors import GearleverError
from gearlever.laws import load_law
from gearlever.plotting.cam_viewer import cam_viewer_data, cam_viewer_html
from tests.plotting._cam_designs import EXAMPLES, designs

DESIGNS = designs()
FRAMES = [0, 37, 90, 133, 200, 251, 299, 359]


def _stroke_length(cam) -> float:
    """The stroke as a length: the follower's travel, or the arc of the contact's arm for a rocker."""
    if FOLLOWERS[cam.follower].law_output == "angle":
        return cam.stroke * (cam.arm if math.isfinite(cam.arm) else cam.pivot_distance)
    return cam.stroke


def _rotated_profile(d, k):
    """The page's profile polygon turned by the page's cam angle of frame k (fixed frame)."""
    t = d["theta"][k]
    x, y = np.array(d["profile"]["x"]), np.array(d["profile"]["y"])
    return np.stack([x * math.cos(t) - y * math.sin(t), x * math.sin(t) + y * math.cos(t)], axis=-1)


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_page_data_equals_the_cam_module_at_several_frames(name):
    cam = DESIGNS[name]
    d = cam_viewer_data(cam, frames=360)
    kind = FOLLOWERS[cam.follower]
    scale = 180 / math.pi if kind.law_output == "angle" else 1.0
    L = d["L"]
    for k in FRAMES:
        i = k * 10
        assert d["index"][k] == i
        assert d["theta"][k] == pytest.approx(cam.theta[i], abs=1e-9)
        assert d["theta"][k] == pytest.approx(2 * math.pi * k / 360, abs=1e-9)
        assert d["F"]["s"][k] == pytest.approx(cam.s[i] * scale, rel=1e-9, abs=1e-9)
        assert d["F"]["phi"][k] == pytest.approx(math.degrees(cam.pressure_angle[i]), rel=1e-9, abs=1e-9)
        assert d["F"]["cx"][k] == pytest.approx(cam.contact[i, 0], abs=1e-9 * L)
        assert d["F"]["cy"][k] == pytest.approx(cam.contact[i, 1], abs=1e-9 * L)
    # the profile drawn is the cam surface (its vertices are samples of it)
    assert len(d["profile"]["x"]) == cam.theta.size  # 3600 points: every sample is a vertex
    np.testing.assert_allclose(d["profile"]["x"], cam.surface[:, 0], atol=1e-9 * L)
    np.testing.assert_allclose(d["profile"]["y"], cam.surface[:, 1], atol=1e-9 * L)


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_follower_touches_the_rotated_profile_and_sits_where_the_law_puts_it(name):
    """Independent of the page's own contact point: the rotated polygon against the roller or face."""
    cam = DESIGNS[name]
    d = cam_viewer_data(cam, frames=360)
    kind = FOLLOWERS[cam.follower]
    tol = 1e-6 * _stroke_length(cam)
    p = FollowerParams(
        0.0 if math.isnan(cam.roller_radius) else cam.roller_radius,
        0.0 if math.isnan(cam.offset) else cam.offset,
        None if math.isnan(cam.arm) else cam.arm,
        None if math.isnan(cam.pivot_distance) else cam.pivot_distance,
    )
    theta = np.array(d["theta"])
    law_s = np.array(d["F"]["s"]) * (math.pi / 180 if kind.law_output == "angle" else 1.0)
    for k in FRAMES:
        poly = _rotated_profile(d, k)
        if kind.contact == "roller":
            c = np.array([d["F"]["rx"][k], d["F"]["ry"][k]])
            gap = np.hypot(*(poly - c).T) - cam.roller_radius
            assert abs(gap.min()) < tol, (k, gap.min())
            # the roller centre where the follower kind puts it for the law's output
            q, _, _ = kind.path(np.array([law_s[k]]), p, cam.base_radius)
            np.testing.assert_allclose(c, q[0], atol=tol)
            if kind.law_output == "angle":
                arm = np.array(d["F"]["arm"])[:, k]
                assert arm[:2].tolist() == [cam.pivot_distance, 0]
                assert math.hypot(arm[2] - arm[0], arm[3] - arm[1]) == pytest.approx(cam.arm, rel=1e-9)
            else:
                assert c[0] == pytest.approx(p.offset, abs=1e-12)
        else:
            x0, y0, x1, y1 = np.array(d["F"]["face"])[:, k]
            u = np.array([x1 - x0, y1 - y0])
            n = np.array([-u[1], u[0]]) / np.hypot(*u)
            if n @ np.array([x0, y0]) < 0:
                n = -n  # the face normal away from the cam centre
            gap = poly @ n - n @ np.array([x0, y0])
            assert abs(gap.max()) < tol, (k, gap.max())  # touches, and nothing of the cam crosses the face
            beta, *_, h, _, _ = kind.face(np.array([law_s[k]]), p, cam.base_radius)
            assert n @ np.array([x0, y0]) == pytest.approx(h[0], abs=tol)
            assert math.atan2(n[1], n[0]) == pytest.approx(float(np.broadcast_to(beta, (1,))[0]), abs=1e-9)
        assert d["F"]["s"][k] == pytest.approx(
            (cam.s[k * 10]) * (180 / math.pi if kind.law_output == "angle" else 1.0), rel=1e-9, abs=1e-9
        )
    # the cam turns counterclockwise: frame k is the cam angle 2 pi k / N
    assert np.all(np.diff(theta) > 0)


def test_law_output_in_the_page_is_the_law_itself():
    law = load_law(EXAMPLES / "law_lift.toml")
    d = cam_viewer_data(DESIGNS["translating-roller"], frames=72)
    vals = law.evaluate(np.array(d["theta"]))
    np.testing.assert_allclose(d["F"]["s"], vals.s - vals.s.min(), atol=1e-9)
    np.testing.assert_allclose(d["F"]["v"], vals.v, atol=1e-8)


def test_profile_is_decimated_but_keeps_every_contact_as_a_vertex():
    law = load_law(EXAMPLES / "law_lift.toml")
    cam = design_cam(law, "translating-roller", base_radius=40.0, roller_radius=8.0, points=36_000)
    d = cam_viewer_data(cam, frames=360)
    assert len(d["profile"]["x"]) <= 7200 + 360
    px, py = np.array(d["profile"]["x"]), np.array(d["profile"]["y"])
    for k in range(0, 360, 7):
        i = d["index"][k]
        assert np.min(np.hypot(px - cam.surface[i, 0], py - cam.surface[i, 1])) < 1e-8


def test_hostile_name_is_escaped_in_the_data_block_and_the_title():
    evil = '"</script><!--<script>alert(1)</script>&amp; \u2028\u2029 ü'
    page = cam_viewer_html(DESIGNS["translating-flat"], frames=36, name=evil)
    assert page.count("</script>") == 2  # the page's own two script elements
    assert "<!--<script>" not in page
    block = re.search(r'<script id="gl-data" type="application/json">(.*?)</script>', page, re.S).group(1)
    assert "\u2028" not in block and "\u2029" not in block and "<" not in block and "&" not in block
    assert json.loads(block)["name"] == evil
    assert "<title>&quot;&lt;/script&gt;" in page


@pytest.mark.parametrize("frames", [1, 3601, 2.5, True, 7])
def test_bad_frames_are_refused_naming_frames(frames):
    with pytest.raises(GearleverError, match="frames"):
        cam_viewer_data(DESIGNS["translating-roller"], frames=frames)


def test_load_cam_reads_what_cam_design_writes(tmp_path):
    from gearlever.cli import main

    out = tmp_path / "cam.toml"
    law = EXAMPLES / "law_dwell_rocker.toml"
    assert (
        main(
            [
                "cam",
                "design",
                str(law),
                "--follower",
                "oscillating-roller",
                "--base-radius",
                "30",
                "--roller-radius",
                "6",
                "--arm",
                "50",
                "--pivot-distance",
                "70",
                "--out",
                str(out),
            ]
        )  # fmt: skip
        == 0
    )
    cam = load_cam(out)
    ref = DESIGNS["oscillating-roller"]
    np.testing.assert_allclose(cam.surface, ref.surface, atol=1e-9)
    assert load_cam(out, points=720).theta.size == 720


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ('[law]\noutput = "angle"\n', "a [cam] table is missing"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = 1\ncolour = 1\n', "unknown key 'colour'"),
        ('[cam]\nfollower = "translating-flat"\n', "base_radius is missing"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = "big"\n', "base_radius must be a number"),
        ('[cam]\nfollower = "translating-flat"\nbase_radius = 1\npoints = 3\n', "points must be an integer"),
    ],
)
def test_load_cam_refusals_name_the_file_and_key(tmp_path, text, needle):
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(GearleverError, match=re.escape(needle)) as exc:
        load_cam(p)
    assert str(p) in str(exc.value)
