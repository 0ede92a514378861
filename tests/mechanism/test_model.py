"""Model files: schema, the parsed frozen dataclass, and one-line refusals naming the element."""

from __future__ import annotations

import dataclasses
import math

import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism.model import load_model, model_from_dict

from ._models import all_examples, example


def base():
    return {
        "mechanism": {"name": "four-bar", "units": "mm"},
        "points": {"O2": [0.0, 0.0], "O4": [40.0, 0.0], "A": [10.0, 0.0], "B": [45.1, 28.3], "P": [30.0, 45.0]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B", "P"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }


def test_every_example_loads():
    for p in all_examples():
        m = load_model(p)
        assert m.inputs and "ground" in m.links


def test_model_is_frozen_and_has_body_fixed_coordinates():
    m = model_from_dict(base())
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.name = "x"
    c = m.links["coupler"]
    assert c.points == ("A", "B", "P")
    assert c.angle0 == pytest.approx(math.atan2(28.3, 35.1))
    xi, eta = c.local["B"]
    assert xi == pytest.approx(math.hypot(35.1, 28.3)) and eta == pytest.approx(0.0, abs=1e-12)
    assert m.joints == (
        ("O2", "ground", "crank"),
        ("O4", "ground", "rocker"),
        ("A", "crank", "coupler"),
        ("B", "coupler", "rocker"),
    )


def test_masses_loads_gravity_pressure_angle_are_kept_raw_in_extra():
    d = base()
    d["masses"] = {"crank": {"mass": 1.0, "centre": "A"}}
    d["loads"] = [{"link": "rocker", "torque": 2.0}]
    d["mechanism"]["gravity"] = [0.0, -9.81]
    d["mechanism"]["pressure_angle"] = 20.0
    m = model_from_dict(d)
    assert m.extra == {
        "masses": {"crank": {"mass": 1.0, "centre": "A"}},
        "loads": [{"link": "rocker", "torque": 2.0}],
        "gravity": [0.0, -9.81],
        "pressure_angle": 20.0,
    }


def _refused(d, *words):
    with pytest.raises(GearleverError) as exc:
        model_from_dict(d)
    msg = str(exc.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


def test_unknown_point_in_a_link_is_named():
    d = base()
    d["links"]["coupler"] = ["A", "B", "Q"]
    _refused(d, "links.coupler", "unknown point 'Q'")


def test_link_with_no_points():
    d = base()
    d["links"]["extra"] = []
    _refused(d, "links.extra", "at least one point")


def test_missing_ground():
    d = base()
    d["links"]["frame"] = d["links"].pop("ground")
    _refused(d, "ground")


def test_input_on_ground():
    d = base()
    d["inputs"] = [{"link": "ground"}]
    _refused(d, "inputs[0].link", "ground")


def test_unknown_table_and_key_are_named():
    d = base()
    d["springs"] = {}
    _refused(d, "[springs]")
    d = base()
    d["mechanism"]["colour"] = "red"
    _refused(d, "[mechanism]", "colour")


def test_non_finite_point():
    d = base()
    d["points"]["A"] = [float("nan"), 0.0]
    _refused(d, "points.A", "finite")


def gears():
    return {
        "mechanism": {"module": 2.0},
        "points": {"O": [0.0, 0.0], "P": [30.0, 0.0]},
        "links": {"ground": ["O", "P"], "g1": ["O"], "g2": ["P"]},
        "gears": {"a": {"link": "g1", "centre": "O", "teeth": 10}, "b": {"link": "g2", "centre": "P", "teeth": 20}},
        "meshes": [{"gears": ["a", "b"]}],
        "inputs": [{"link": "g1"}],
    }


def test_gear_centre_not_on_its_link():
    d = gears()
    d["gears"]["a"]["centre"] = "P"
    _refused(d, "gears.a.centre", "not on the gear's link")


def test_mesh_with_no_carrier_or_two():
    d = gears()
    d["links"]["ground"] = ["O"]
    d["links"]["g2"] = ["P"]
    d["links"]["arm"] = ["O"]
    d["points"]["Q"] = [0.0, 5.0]
    d["links"]["g2"] = ["P", "Q"]
    d["links"]["ground"] = ["O", "Q"]
    _refused(d, "meshes[0] (a-b)", "no carrier")
    d = gears()
    d["links"]["arm"] = ["O", "P"]
    _refused(d, "meshes[0] (a-b)", "two or more carriers")


def test_centre_distance_must_match_the_module():
    d = gears()
    d["mechanism"]["module"] = 3.0
    _refused(d, "meshes[0] (a-b)", "module")


def slider():
    return {
        "points": {"O2": [0.0, 0.0], "A": [10.0, 0.0], "B": [40.0, 5.0]},
        "links": {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "piston": ["B"]},
        "sliders": [{"link": "piston", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
        "inputs": [{"link": "crank"}],
    }


def test_slider_point_not_on_its_link():
    d = slider()
    d["sliders"][0]["point"] = "A"
    _refused(d, "sliders[0] (piston).point", "not on the sliding link")


def test_slider_guide_on_the_sliding_link_itself():
    d = slider()
    d["sliders"][0]["on"] = "piston"
    _refused(d, "sliders[0] (piston)", "another link")


def test_slider_zero_direction():
    d = slider()
    d["sliders"][0]["direction"] = [0.0, 0.0]
    _refused(d, "direction", "non-zero")


def test_toml_syntax_error_names_the_line(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[points]\nO = [0, 0]\nA = = 1\n[links]\n")
    with pytest.raises(GearleverError, match="line 3"):
        load_model(p)
    p.write_text("[points]\nO = [0, 0]\nA = [1, \n")
    with pytest.raises(GearleverError, match="line"):
        load_model(p)


def test_unreadable_file(tmp_path):
    with pytest.raises(GearleverError, match="cannot be read"):
        load_model(tmp_path / "missing.toml")


def test_example_file_path_prefixes_errors(tmp_path):
    text = example("fourbar").read_text().replace('"A", "B", "P"', '"A", "B", "Z"')
    p = tmp_path / "m.toml"
    p.write_text(text)
    with pytest.raises(GearleverError, match=r"m\.toml: links\.coupler: unknown point 'Z'"):
        load_model(p)
