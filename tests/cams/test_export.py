"""Profile exports of a cam (gearlever.cams.export): the registry, the formats' content, determinism."""

import io

import numpy as np
import pytest

from gearlever.cams import design_cam
from gearlever.cams.export import EXPORTS, export_profile, profile_csv, profile_dxf, profile_svg
from gearlever.errors import GearleverError
from gearlever.laws import law_from_segments


@pytest.fixture(scope="module")
def cam():
    law = law_from_segments(
        "displacement",
        "mm",
        [
            {"to": 120, "motion": "cycloidal", "rise": 10},
            {"to": 180, "motion": "dwell"},
            {"to": 360, "motion": "345", "rise": -10},
        ],
    )
    return design_cam(law, "translating-roller", base_radius=30.0, roller_radius=5.0, points=360)


def test_the_registry_holds_csv_svg_and_dxf_by_suffix():
    assert list(EXPORTS) == [".csv", ".svg", ".dxf"]
    assert all(fmt.suffix == suffix for suffix, fmt in EXPORTS.items())


def test_csv_reads_back_as_the_cam_surface_to_12_digits(cam):
    rows = np.loadtxt(io.StringIO(profile_csv(cam)), delimiter=",", skiprows=1)
    assert rows.shape == cam.surface.shape
    assert np.allclose(rows, cam.surface, rtol=1e-11, atol=1e-11 * cam.base_radius)


def test_svg_polygon_holds_every_point_with_y_flipped(cam):
    text = profile_svg(cam)
    pts = text.split('points="', 1)[1].split('"', 1)[0].split()
    xy = np.array([[float(v) for v in p.split(",")] for p in pts])
    assert np.allclose(xy[:, 0], cam.surface[:, 0], atol=1e-7) and np.allclose(-xy[:, 1], cam.surface[:, 1], atol=1e-7)
    assert 'width="' in text and "mm" in text


def test_dxf_is_the_same_bytes_twice_and_reads_back_as_the_surface(cam, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    data = profile_dxf(cam)
    assert data == profile_dxf(cam)
    path = tmp_path / "p.dxf"
    path.write_bytes(data)
    poly = [e for e in ezdxf.readfile(path).modelspace() if e.dxftype() == "LWPOLYLINE"]
    assert len(poly) == 1 and poly[0].closed
    xy = np.array([(p[0], p[1]) for p in poly[0].get_points()])
    assert np.allclose(xy, cam.surface, atol=1e-9)


def test_export_profile_picks_the_format_from_the_name_and_refuses_others(cam):
    assert export_profile(cam, "P.CSV") == profile_csv(cam)
    assert export_profile(cam, "p.svg") == profile_svg(cam)
    with pytest.raises(GearleverError, match=r"profile must end with \.csv, \.svg, \.dxf, got 'p\.png'"):
        export_profile(cam, "p.png")
