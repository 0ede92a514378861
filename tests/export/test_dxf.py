"""DXF export (gearlever.export.dxf): ezdxf's audit passes, and the file reopens with the layers and holes."""

from __future__ import annotations

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.export import export, export_parts
from gearlever.mechanism import Mechanism

EXAMPLES = [
    "fourbar",
    "slider_crank",
    "watt_sixbar",
    "whitworth",
    "geared_fivebar",
    "planetary",
    "compound_planetary",
    "ferguson",
    "zrdpm_gear_contour",
]


@pytest.mark.parametrize("name", EXAMPLES)
def test_dxf_audits_clean_and_reopens_with_layers_and_holes(name, tmp_path):
    import ezdxf

    mech = Mechanism.load(example_path(f"{name}.toml"))
    out = tmp_path / f"{name}.dxf"
    drawing = export(mech, out, pin_diameter=1.0)
    doc = ezdxf.readfile(out)
    auditor = doc.audit()
    assert not auditor.has_errors and not auditor.errors
    m = mech.model
    assert doc.header["$INSUNITS"] == {"mm": 4}.get(m.units, 0)
    layers = {layer.dxf.name for layer in doc.layers}
    assert {p.name for p in drawing.parts} <= layers
    msp = doc.modelspace()
    for part in drawing.parts:
        circles = msp.query(f'CIRCLE[layer=="{part.name}"]')
        got = sorted((round(c.dxf.center.x, 9), round(c.dxf.center.y, 9)) for c in circles)
        # a pin hole at every point of the link, where the model puts it (the sketch)
        for p in m.links[part.name].points:
            x, y = m.points[p]
            assert (round(x, 9), round(y, 9)) in got
        assert all(c.dxf.radius == pytest.approx(0.5) for c in circles if c.dxf.radius >= 0.5)
        polylines = msp.query(f'LWPOLYLINE[layer=="{part.name}"]')
        assert sum(pl.closed for pl in polylines) == len(part.outlines)


def test_dxf_is_the_same_bytes_on_every_run(tmp_path):
    mech = Mechanism.load(example_path("geared_fivebar.toml"))
    export(mech, tmp_path / "a.dxf")
    export(mech, tmp_path / "b.dxf")
    assert (tmp_path / "a.dxf").read_bytes() == (tmp_path / "b.dxf").read_bytes()


def test_parts_are_one_dxf_each_in_their_body_frame(tmp_path):
    import ezdxf

    mech = Mechanism.load(example_path("fourbar.toml"))
    drawing = export(mech, tmp_path / "m.svg", inputs={"crank": 0.5})
    paths = export_parts(drawing, tmp_path)
    assert sorted(p.name for p in paths) == ["coupler.dxf", "crank.dxf", "ground.dxf", "rocker.dxf"]
    doc = ezdxf.readfile(tmp_path / "coupler.dxf")
    centres = [np.array([c.dxf.center.x, c.dxf.center.y]) for c in doc.modelspace().query("CIRCLE")]
    m = mech.model
    # first point at the origin; the others at their distances from it, whatever the pose
    assert any(np.allclose(c, 0.0, atol=1e-9) for c in centres)
    for p in ("B", "P"):
        want = np.hypot(*np.subtract(m.points[p], m.points["A"]))
        assert any(abs(np.hypot(*c) - want) < 1e-9 for c in centres)
