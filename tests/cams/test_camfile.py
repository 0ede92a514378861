"""CAM.toml both ways (gearlever.cams.camfile): what cam_toml writes, load_cam reads as the same design."""

import tomllib

import numpy as np
import pytest

from gearlever.cams import design_cam, load_cam
from gearlever.cams.camfile import cam_toml
from gearlever.laws import law_from_segments

LAW = [
    {"to": 150, "motion": "cycloidal", "rise": 20},
    {"to": 210, "motion": "dwell"},
    {"to": 360, "motion": "harmonic", "rise": -20},
]


@pytest.mark.parametrize(
    "kind, dims",
    [
        ("translating-roller", {"roller_radius": 6.0, "offset": 3.0}),
        ("translating-flat", {}),
        ("oscillating-roller", {"roller_radius": 5.0, "arm": 60.0, "pivot_distance": 80.0}),
    ],
)
def test_written_cam_reads_back_as_the_same_design(tmp_path, kind, dims):
    law = law_from_segments(
        "angle" if kind.startswith("oscillating") else "displacement",
        "deg" if kind.startswith("oscillating") else "mm",
        LAW,
    )
    cam = design_cam(law, kind, base_radius=40.0, points=720, **dims)
    text = cam_toml(
        cam, law.to_dict(), {"undercut": cam.undercut, "note": "x", "nan": float("nan"), "list": [1]}, "one\ntwo"
    )
    assert text.startswith("# one\n# two\n")
    data = tomllib.loads(text)
    assert data["report"] == {
        "undercut": cam.undercut,
        "note": "x",
    }  # non-finite numbers and lists left to the JSON report
    path = tmp_path / "cam.toml"
    path.write_text(text)
    back = load_cam(path)
    assert back.follower == kind and back.theta.size == 720
    assert np.allclose(back.surface, cam.surface, rtol=1e-11, atol=1e-11 * 40.0)


def test_centre_is_written_and_read_back_and_leaves_the_design_alone(tmp_path):
    from gearlever.cams import cam_centre

    law = law_from_segments("displacement", "mm", LAW)
    cam = design_cam(law, "translating-roller", base_radius=40.0, roller_radius=6.0, points=720)
    path = tmp_path / "cam.toml"
    path.write_text(cam_toml(cam, law.to_dict(), {}, centre=(120.5, -1 / 3)))
    assert cam_centre(path) == (120.5, float(f"{-1 / 3:.12g}"))
    assert np.allclose(load_cam(path).surface, cam.surface, rtol=1e-11, atol=1e-11 * 40.0)  # about the pivot
    plain = tmp_path / "plain.toml"
    plain.write_text(cam_toml(cam, law.to_dict(), {}))
    assert "centre" not in tomllib.loads(plain.read_text())["cam"] and cam_centre(plain) == (0.0, 0.0)


@pytest.mark.parametrize("bad", ["[1]", '["a", 2]', "[1, nan]", "3", "[true, 1]"])
def test_a_centre_that_is_not_two_finite_numbers_is_refused_naming_it(tmp_path, bad):
    from gearlever.cams import cam_centre
    from gearlever.errors import GearleverError

    law = law_from_segments("displacement", "mm", LAW)
    cam = design_cam(law, "translating-roller", base_radius=40.0, roller_radius=6.0, points=720)
    text = cam_toml(cam, law.to_dict(), {}).replace("[cam]\n", f"[cam]\ncentre = {bad}\n")
    path = tmp_path / "cam.toml"
    path.write_text(text)
    for read in (load_cam, cam_centre):
        with pytest.raises(GearleverError, match=r"\[cam\] centre must be \[x, y\]"):
            read(path)
    with pytest.raises(GearleverError, match="centre"):
        cam_toml(cam, law.to_dict(), {}, centre=(1.0, float("inf")))


def test_a_cam_file_whose_oscillating_pivot_lies_inside_the_cam_is_refused_naming_the_cam_key(tmp_path):
    """The pivot (the arm's shaft) inside the disc the cam sweeps: the file's [cam] pivot_distance is named."""
    from gearlever.errors import GearleverError

    law = law_from_segments("angle", "deg", LAW)
    dims = {"roller_radius": 5.0, "arm": 40.0}
    cam = design_cam(law, "oscillating-roller", base_radius=30.0, pivot_distance=60.0, points=720, **dims)
    text = cam_toml(cam, law.to_dict(), {})
    good = tmp_path / "good.toml"
    good.write_text(text)
    assert load_cam(good).pivot_distance == 60.0
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("pivot_distance = 60", "pivot_distance = 30", 1))
    with pytest.raises(GearleverError) as exc:
        load_cam(bad)
    line = str(exc.value)
    assert line.startswith(f"{bad}: [cam] pivot_distance 30: the follower's pivot lies inside the cam")
    assert "a [cam] pivot_distance above" in line and "[cam] arm" in line and "--" not in line
