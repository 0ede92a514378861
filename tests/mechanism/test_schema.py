"""One model schema (gearlever.mechanism.schema) drives the reader, the writer and the guide; models round-trip.

Checked: the reader refuses an unknown table or key with the schema's list and
a missing required key by name; the writer writes every table the reader
accepts (``[lengths]`` included) in the schema's order; the guide page lists
exactly the schema's tables and keys; ``Mechanism.loads(m.dumps())`` gives the
same model and the same solve (1e-12) for every shipped example, every
``.links.json`` and hypothesis-generated models; the mechanism package imports
nothing of the synthesis packages and the loads module nothing of the loader.
"""

from __future__ import annotations

import ast
import json
import math
import re
import tomllib
from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism, model_from_dict, schema
from gearlever.mechanism.linkage import read_linkage_model
from gearlever.mechanism.modelfile import model_dict, model_toml

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "gearlever"
GUIDE = ROOT / "docs" / "guide" / "model-file.rst"
EXAMPLES = sorted((SRC / "data" / "examples").glob("*.toml"))

FOURBAR = {
    "points": {"O2": [0.0, 0.0], "O4": [4.0, 0.0], "A": [1.0, 0.0], "B": [4.5, 2.8]},
    "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
    "inputs": [{"link": "crank"}],
}


# --------------------------------------------------------------------------- the reader
def _element(name: str) -> dict:
    """A minimal valid element of table ``name`` on the four-bar (``d`` patched by :func:`_with`)."""
    return {
        "mechanism": {"name": "m"},
        "sliders": {"link": "slider", "on": "ground", "point": "B", "direction": [1.0, 0.0]},
        "gears": {"link": "crank", "centre": "O2", "teeth": 20},
        "meshes": {"gears": ["g1", "g2"]},
        "inputs": {"link": "crank"},
        "masses": {"mass": 1.0, "centre": "A", "inertia": 0.1},
        "loads": {"link": "rocker", "torque": 1.0},
        "friction": {"coefficient": 0.1, "pin_radius": 0.05},
        "poses": {"point": [1.0, 2.0], "angle_deg": 30.0},
    }[name]


def _with(name: str, element: dict) -> dict:
    d = json.loads(json.dumps(FOURBAR))
    if name == "mechanism":
        d["mechanism"] = element
    elif name == "sliders":  # a slider-crank: the block B slides on the ground
        d["points"] = {"O2": [0.0, 0.0], "A": [1.0, 0.0], "B": [4.5, 0.5]}
        d["links"] = {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "slider": ["B"]}
        d["sliders"] = [element]
    elif name == "gears":
        d["gears"] = {"g1": element}
    elif name == "meshes":
        d["gears"] = {
            "g1": {"link": "crank", "centre": "O2", "teeth": 20},
            "g2": {"link": "rocker", "centre": "O4", "teeth": 60},
        }
        d["meshes"] = [element]
    elif name == "inputs":
        d["inputs"] = [element]
    elif name == "masses":
        d["masses"] = {"crank": element}
    elif name == "loads":
        d["loads"] = [element]
    elif name == "friction":
        d["friction"] = element
    elif name == "poses":
        d["poses"] = [element]
    return d


KEYED = [t.name for t in schema.TABLES if t.form != "map"]


@pytest.mark.parametrize("name", KEYED)
def test_reader_takes_every_key_of_the_schema_and_refuses_others_with_its_list(name):
    good = _with(name, _element(name))
    model_from_dict(good)  # the minimal element loads
    bad = _with(name, dict(_element(name), colour="red"))
    with pytest.raises(GearleverError, match=re.escape(f"(allowed: {', '.join(schema.allowed_keys(name))})")):
        model_from_dict(bad)


@pytest.mark.parametrize("name", [n for n in KEYED if schema.required_keys(n)])
def test_reader_refuses_a_missing_required_key_of_the_schema(name):
    for key in schema.required_keys(name):
        element = {k: v for k, v in _element(name).items() if k != key}
        with pytest.raises(GearleverError, match=re.escape(key)):
            model_from_dict(_with(name, element))


def test_reader_refuses_an_unknown_table_with_the_schemas_list():
    with pytest.raises(GearleverError, match=re.escape(f"(allowed: {', '.join(schema.allowed_tables())})")):
        model_from_dict(dict(FOURBAR, colours={}))
    for t in schema.TABLES:
        if t.required:
            with pytest.raises(GearleverError, match=re.escape(t.name)):
                model_from_dict({k: v for k, v in FOURBAR.items() if k != t.name})


def test_reader_keeps_the_schemas_kept_tables_in_extra():
    d = dict(FOURBAR, lengths={"crank": 1.5}, masses={"crank": {"mass": 1.0, "centre": "A"}})
    d["loads"] = [{"link": "rocker", "torque": 2.0}]
    d["friction"] = {"coefficient": 0.1, "pin_radius": 0.05}
    d["poses"] = [{"point": [1.0, 2.0], "angle_deg": 30.0}]
    m = model_from_dict(d)
    assert set(m.extra) == set(schema.kept_tables())


# --------------------------------------------------------------------------- the writer
def _headers(text: str) -> list:
    return re.findall(r"^\[\[?([A-Za-z_]+)\]\]?$", text, flags=re.M)


def test_writer_writes_every_table_in_the_schemas_order_and_keeps_lengths():
    d = _with("sliders", _element("sliders"))
    d["lengths"] = {"crank": 1.25, "rod.A-B": 4.0}
    d["masses"] = {"crank": {"mass": 1.0, "centre": "A", "inertia": 0.1}}
    d["loads"] = [{"link": "slider", "force": [1.0, 0.0], "point": "B"}]
    d["inputs"] = [{"link": "crank"}]
    d["mechanism"] = {"name": "all tables", "units": "mm", "gravity": [0.0, -9810.0]}
    d["gears"] = {"g1": {"link": "crank", "centre": "O2", "teeth": 20}}
    text = model_toml(d)
    order = [n for n in schema.write_order() if n in d]
    seen = list(dict.fromkeys(_headers(text)))
    assert seen == order
    assert tomllib.loads(text) == d
    assert model_from_dict(tomllib.loads(text)).extra["lengths"] == {"crank": 1.25, "rod.A-B": 4.0}


def test_writer_refuses_a_table_the_schema_does_not_know():
    with pytest.raises(GearleverError, match=r"\[colours\]"):
        model_toml(dict(FOURBAR, colours={"crank": "red"}))


def test_write_order_puts_every_plain_table_before_the_arrays_of_tables():
    kinds = [schema.table(n).is_array for n in schema.write_order()]
    assert kinds == sorted(kinds)
    assert set(schema.write_order()) == set(schema.allowed_tables())


# --------------------------------------------------------------------------- the guide
def _guide_sections() -> dict:
    """Section title -> its text, for titles naming a table (``[points]``, ``[[inputs]]``)."""
    text = GUIDE.read_text(encoding="utf-8")
    parts = re.split(r"^(.+)\n-{3,}\n", text, flags=re.M)
    out = {}
    for title, body in zip(parts[1::2], parts[2::2]):
        m = re.match(r"``(\[\[?[a-z_]+\]\]?)``", title)
        if m:
            out[m.group(1)] = body
    return out


def test_guide_has_a_section_for_every_table_of_the_schema_and_no_other():
    assert set(_guide_sections()) == {t.header for t in schema.TABLES}


def test_guide_names_every_key_of_the_schema_and_lists_no_other():
    sections = _guide_sections()
    for t in schema.TABLES:
        body = sections[t.header]
        if t.form != "map":
            for key in schema.allowed_keys(t.name):
                assert f"``{key}``" in body, f"{t.header}: key {key} missing from the guide"
            listed = re.findall(r"^\s+\* - ``([a-z_]+)``", body, flags=re.M)
            assert set(listed) <= set(schema.allowed_keys(t.name)), f"{t.header}: {listed}"
    top = GUIDE.read_text(encoding="utf-8").split("Allowed tables:")[1].split("Any")[0]
    assert re.findall(r"``(\[\[?[a-z_]+\]\]?)``", top) == [t.header for t in schema.TABLES]


# --------------------------------------------------------------------------- round trips
def _same_model(a, b) -> None:
    """Field by field; slider directions (unit vectors normalized again on reading) to 1e-15."""
    for f in fields(a):
        va, vb = getattr(a, f.name), getattr(b, f.name)
        if f.name == "sliders":
            np.testing.assert_allclose([s.direction for s in va], [s.direction for s in vb], rtol=0, atol=1e-15)
            va = [s.__class__(s.name, s.link, s.on, s.point, ()) for s in va]
            vb = [s.__class__(s.name, s.link, s.on, s.point, ()) for s in vb]
        assert va == vb, f.name


def _same_solve(m1: Mechanism, m2: Mechanism) -> None:
    q0 = m1.sketch_inputs
    np.testing.assert_array_equal(q0, m2.sketch_inputs)
    q = q0[None, :] + np.linspace(0.0, 1.0, 5)[:, None] * (1.0 if q0.size else 0.0)
    r1, r2 = m1.solve(q), m2.solve(q)
    np.testing.assert_array_equal(r1.closed, r2.closed)
    for p in m1.model.points:
        np.testing.assert_allclose(r1.point[p], r2.point[p], rtol=0, atol=1e-12 * max(1.0, m1.model.length_scale))


def _is_model(path: Path) -> bool:
    return "[law]" not in path.read_text(encoding="utf-8")


def test_every_shipped_example_is_a_model_or_a_motion_law():
    assert EXAMPLES
    laws = [p.name for p in EXAMPLES if not _is_model(p)]
    assert laws == ["law_dwell_rocker.toml", "law_lift.toml", "law_quick_return.toml"]


@pytest.mark.parametrize("path", [p for p in EXAMPLES if _is_model(p)], ids=lambda p: p.stem)
def test_every_shipped_example_round_trips_through_dumps_and_loads(path):
    m = Mechanism.load(path)
    text = m.dumps()
    m2 = Mechanism.loads(text)
    _same_model(m.model, m2.model)
    assert m2.dumps() == text  # the written text is a fixed point
    _same_solve(m, m2)


def test_links_json_goes_through_the_same_reader_and_round_trips(tmp_path):
    p = tmp_path / "four.links.json"
    p.write_text(
        json.dumps(
            {"x0": [[0, 0], [0.3, 1.1], [3, 0], [2.2, 2.1]], "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2]}
            | {"motor": [0, 1]}
        )
    )
    m = Mechanism.load(p)
    assert m.model == model_from_dict(read_linkage_model(p))
    m2 = Mechanism.loads(m.dumps())
    _same_model(m.model, m2.model)
    _same_solve(m, m2)
    bad = tmp_path / "bad.links.json"
    bad.write_text(json.dumps({"x0": [[0, 0], [1, 0]], "edges": [[0, 1]], "fixed_joints": [1], "motor": [0, 1]}))
    with pytest.raises(GearleverError, match=re.escape(str(bad))):
        Mechanism.load(bad)


NAMES = st.sampled_from(["a", "crank_2", "кривошип", "曲柄", "L.1", "_x", "r-3"])
FLOATS = st.floats(-50.0, 50.0, allow_nan=False, allow_subnormal=False)


@st.composite
def models(draw):
    """A four-bar of random float geometry and names, with optional slider dyad, gears, masses, loads, lengths."""
    crank, coupler, rocker = draw(st.lists(NAMES, min_size=3, max_size=3, unique=True))
    pts = {
        "O2": [0.0, 0.0],
        "O4": [draw(st.floats(20.0, 60.0)), draw(FLOATS) / 4],
        "A": [draw(st.floats(3.0, 12.0)), draw(st.floats(-5.0, 5.0))],
    }
    pts["B"] = [pts["O4"][0] + draw(st.floats(-10.0, 10.0)), pts["O4"][1] + draw(st.floats(8.0, 30.0))]
    links = {"ground": ["O2", "O4"], crank: ["O2", "A"], coupler: ["A", "B"], rocker: ["O4", "B"]}
    mech = {"name": draw(st.sampled_from(["fuzz", 'a "quoted" name', "back\\slash", "Zürich"]))}
    if draw(st.booleans()):
        mech["units"] = draw(st.sampled_from(["mm", "m", "in"]))
    d: dict = {"mechanism": mech, "points": pts, "links": links, "inputs": [{"link": crank}]}
    if draw(st.booleans()):  # a slider dyad driven by the coupler: B - C on a guide through C
        pts["C"] = [pts["B"][0] + draw(st.floats(5.0, 20.0)), pts["B"][1] + draw(st.floats(-5.0, 5.0))]
        links["rod"], links["block"] = ["B", "C"], ["C"]
        u = [draw(st.floats(0.1, 1.0)), draw(st.floats(-1.0, 1.0))]
        d["sliders"] = [{"link": "block", "on": "ground", "point": "C", "direction": u}]
        if draw(st.booleans()):
            d["sliders"][0]["name"] = "ram"
    if draw(st.booleans()):
        d["gears"] = {
            "g1": {"link": crank, "centre": "O2", "teeth": draw(st.integers(8, 40))},
            "g2": {"link": rocker, "centre": "O4", "teeth": draw(st.integers(8, 40)), "internal": draw(st.booleans())},
        }
        mesh = {"gears": ["g1", "g2"]}
        if draw(st.booleans()):
            mesh["efficiency"] = draw(st.floats(0.5, 1.0))
        d["meshes"] = [mesh]
    if draw(st.booleans()):
        mech["gravity"] = [0.0, -draw(st.floats(0.0, 10000.0))]
        mech["pressure_angle"] = draw(st.floats(0.0, 30.0))
        mech["mesh_efficiency"] = draw(st.floats(0.5, 1.0))
        d["masses"] = {crank: {"mass": draw(st.floats(0.0, 5.0)), "centre": "A", "inertia": 0.1}}
        d["loads"] = [{"link": rocker, "torque": draw(FLOATS)}, {"link": coupler, "point": [1.5, 2.5], "force": [1, 2]}]
    if draw(st.booleans()):
        d["lengths"] = {crank: draw(st.floats(3.0, 12.0)), f"{coupler}.A-B": draw(st.floats(10.0, 40.0))}
    return d


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(d=models())
def test_hypothesis_models_round_trip_through_dumps_and_loads(d):
    try:
        m = Mechanism.from_dict(d)
    except GearleverError:
        assume(False)
    text = m.dumps()
    m2 = Mechanism.loads(text)
    _same_model(m.model, m2.model)
    assert m2.dumps() == text
    _same_model(model_from_dict(model_dict(m.model)), m.model)
    try:
        _same_solve(m, m2)
    except GearleverError as exc:  # refused alike (an over-constrained gear pair)
        with pytest.raises(GearleverError, match=re.escape(str(exc))):
            _same_solve(m2, m)


def test_dumps_writes_floats_exactly_and_loads_refuses_bad_text():
    d = json.loads(json.dumps(FOURBAR))
    d["points"]["B"] = [4.5 + 1e-13, 2.8 / 3]
    m = Mechanism.from_dict(d)
    assert Mechanism.loads(m.dumps()).model.points == m.model.points
    with pytest.raises(GearleverError, match="TOML syntax error"):
        Mechanism.loads("[points\n")
    with pytest.raises(GearleverError, match="cap"):
        Mechanism.loads("#" * (schema.MAX_MODEL_BYTES + 1))


# --------------------------------------------------------------------------- no circles
def _imports(path: Path) -> set:
    """Every module a file imports, at module level or inside functions."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out |= {node.module} | {f"{node.module}.{a.name}" for a in node.names}
    return out


def test_mechanism_imports_nothing_of_curves_or_synthesis_and_loads_not_the_loader():
    for path in (SRC / "mechanism").glob("*.py"):
        bad = [m for m in _imports(path) if m.startswith(("gearlever.synthesis.curve", "gearlever.synthesis"))]
        assert not bad, f"{path.name} imports {bad}"
    assert not [m for m in _imports(SRC / "mechanism" / "loads.py") if m.startswith("gearlever.mechanism.model")]
    assert not [m for m in _imports(SRC / "mechanism" / "schema.py") if m.startswith("gearlever")]


def test_schema_caps_are_the_readers():
    from gearlever.mechanism import loads, model

    assert model.MAX_LINKS == schema.MAX_LINKS and loads.MAX_LOAD == schema.MAX_LOAD
    assert math.isclose(schema.MAX_COORDINATE, 1e12)


def test_poses_round_trip_through_dumps_and_loads_and_read_in_radians():
    from gearlever.mechanism.model import parse_poses

    d = dict(FOURBAR, poses=[{"point": [0.5, 2.0], "angle_deg": 30.0}, {"point": [1.5, 2.5], "angle_deg": -15.5}])
    m = Mechanism.from_dict(d)
    again = Mechanism.loads(m.dumps())
    assert again.model.extra["poses"] == d["poses"]
    assert parse_poses(again.model.extra["poses"]) == [(0.5, 2.0, math.radians(30.0)), (1.5, 2.5, math.radians(-15.5))]


def test_poses_beyond_the_five_motion_synthesis_takes_are_refused_naming_the_table():
    d = dict(FOURBAR, poses=[{"point": [0.0, float(k)], "angle_deg": 0.0} for k in range(schema.MAX_POSES + 1)])
    with pytest.raises(GearleverError, match=r"\[\[poses\]\]: 6 entries, more than the cap of 5"):
        model_from_dict(d)
    with pytest.raises(GearleverError, match=r"poses\[0\]\.angle_deg must be a finite number"):
        model_from_dict(dict(FOURBAR, poses=[{"point": [0.0, 0.0], "angle_deg": float("nan")}]))
