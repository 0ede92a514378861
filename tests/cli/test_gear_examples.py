"""Every shipped example with gears (found in examples/*.toml, not listed by hand): ``mechanism check`` and
``mechanism export`` run on each (issue 32, "Done when")."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest

from gearlever.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _geared() -> list[str]:
    """The examples whose model has gear meshes."""
    names = []
    for path in sorted(EXAMPLES.glob("*.toml")):
        model = tomllib.loads(path.read_text(encoding="utf-8"))
        if model.get("meshes"):
            names.append(path.stem)
    return names


GEARED = _geared()


def test_the_examples_with_gears_are_all_found():
    """The loop below sees every example with meshes (five at this writing, the ZRDPM gear contour among them)."""
    assert {"geared_fivebar", "planetary", "compound_planetary", "ferguson", "zrdpm_gear_contour"} <= set(GEARED)


@pytest.mark.parametrize("name", GEARED)
def test_mechanism_check_and_export_run_on_every_example_with_gears(name, tmp_path, capsys):
    """check: exit 0, one report per mesh of the model with its contact ratio; export: a DXF that passes ezdxf's
    audit with the layer of every geared link and each gear's tooth outline on it, and an SVG."""
    import ezdxf

    model = EXAMPLES / f"{name}.toml"
    data = tomllib.loads(model.read_text(encoding="utf-8"))
    meshes = data["meshes"]
    assert main(["mechanism", "check", str(model), "--points", "12", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert len(d["meshes"]) == len(meshes)
    assert all(m["sketch"]["contact_ratio_transverse"] >= 1 for m in d["meshes"])
    for suffix in ("dxf", "svg"):
        out = tmp_path / f"{name}.{suffix}"
        assert main(["mechanism", "export", str(model), "--out", str(out)]) == 0
        capsys.readouterr()
        assert out.stat().st_size > 0
    doc = ezdxf.readfile(tmp_path / f"{name}.dxf")
    assert not doc.audit().has_errors
    layers = {layer.dxf.name for layer in doc.layers}
    geared_links = {data["gears"][g]["link"] for m in meshes for g in m["gears"]}
    assert geared_links <= layers, (geared_links, layers)
    # each gear drawn as its whole tooth outline: a closed polyline of at least 10 points a tooth on its link's layer
    for g in {g for m in meshes for g in m["gears"]}:
        spec = data["gears"][g]
        sizes = [len(e) for e in doc.modelspace().query(f'LWPOLYLINE[layer=="{spec["link"]}"]') if e.closed]
        assert max(sizes, default=0) >= 10 * spec["teeth"], (g, sizes)
    assert (tmp_path / f"{name}.svg").read_text(encoding="utf-8").lstrip().startswith(("<?xml", "<svg"))
