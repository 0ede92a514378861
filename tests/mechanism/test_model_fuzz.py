"""Hypothesis-generated model files through load -> structure -> analyze -> forces: refused or answered, never a crash.

Models are built as data (a four-bar with random pivots and lengths, random
extra dyads, masses and loads), written as TOML, and often mutated at one
random place with a hostile value (a name with a comma or a newline, a huge
integer, NaN, a bool, a wrong type, a deep nesting, an unknown reference).
Each file goes through :func:`load_model`, the structure analysis, a short
kinematic sweep and the inverse dynamics.  Every step must either return or
raise :class:`GearleverError`; a model built without a mutation must load.
Settings: ``deadline=None`` and a bounded number of examples (a few seconds).
"""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearlever._io import table_text
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.loads import gravity_of, parse_loads, parse_masses, pressure_angle_of
from gearlever.mechanism.model import load_model, model_from_dict

EXAMPLES = 40

#: 20 nested arrays (the cap is 16 levels)
DEEP: list = [1]
for _ in range(19):
    DEEP = [DEEP]

HOSTILE = [
    "P,x",
    "a\nb",
    'q"q',
    "a=b",
    " ",
    "",
    "2x",
    "\x00",
    "曲柄",
    10**400,
    -(10**400),
    float("nan"),
    float("inf"),
    1e308,
    -1e308,
    True,
    [],
    {},
    DEEP,
    "ground",
    "crnak",
    0,
    -1,
    1e-300,
]


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a JSON string is a TOML basic string (same escapes)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{json.dumps(str(k))} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def to_toml(d: dict) -> str:
    """TOML text of a model dict (tables of values, arrays of tables); keys quoted."""
    out = []
    for top, body in d.items():
        if isinstance(body, list) and body and all(isinstance(t, dict) for t in body):
            for t in body:
                out.append(f"[[{top}]]")
                out += [f"{json.dumps(str(k))} = {_toml_value(v)}" for k, v in t.items()]
        elif isinstance(body, dict):
            out.append(f"[{top}]")
            out += [f"{json.dumps(str(k))} = {_toml_value(v)}" for k, v in body.items()]
        else:
            out.append(f"{top} = {_toml_value(body)}")
    return "\n".join(out) + "\n"


@st.composite
def models(draw):
    """A four-bar with random geometry plus up to two dyads, masses and loads (valid by construction)."""
    coord = st.integers(-40, 40).map(float)
    pts = {"O2": [0.0, 0.0], "O4": [draw(st.integers(20, 60)) * 1.0, draw(coord) / 4]}
    pts["A"] = [draw(st.integers(3, 12)) * 1.0, draw(st.integers(-5, 5)) * 1.0]
    pts["B"] = [pts["O4"][0] + draw(st.integers(-10, 10)), pts["O4"][1] + draw(st.integers(8, 30))]
    links = {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]}
    for k in range(draw(st.integers(0, 2))):
        base = draw(st.sampled_from(["A", "B"]))
        c, g = f"C{k}", f"G{k}"
        pts[c] = [pts[base][0] + draw(st.integers(5, 25)), pts[base][1] + draw(st.integers(-20, 20))]
        pts[g] = [pts[c][0] + draw(st.integers(-10, 10)), pts[c][1] - draw(st.integers(10, 30))]
        links["ground"].append(g)
        links[f"d{k}a"] = [base, c]
        links[f"d{k}b"] = [g, c]
    d = {
        "mechanism": {"name": "fuzz", "units": "mm", "gravity": [0.0, -9810.0]},
        "points": pts,
        "links": links,
        "inputs": [{"link": "crank"}],
    }
    if draw(st.booleans()):
        d["masses"] = {"crank": {"mass": 1.0, "centre": "A", "inertia": 0.1}, "coupler": {"mass": 2.0, "centre": "B"}}
    if draw(st.booleans()):
        d["loads"] = [{"link": "rocker", "torque": float(draw(st.integers(-100, 100)))}]
    return d


def _paths(obj, prefix=()):
    """Every (path, is_key) place of a nested dict/list where a value or a key can be replaced."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield (*prefix, k), True
            yield from _paths(v, (*prefix, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _paths(v, (*prefix, i))
    if prefix:
        yield prefix, False


def _mutate(d, path, is_key, value):
    *head, last = path
    node = d
    for p in head:
        node = node[p]
    if is_key:
        if not isinstance(value, str):
            value = str(value)
        node[value] = node.pop(last)
    else:
        node[last] = value


@st.composite
def model_files(draw):
    d = draw(models())
    mutated = draw(st.booleans())
    if mutated and draw(st.booleans()):  # a point that no link carries
        d["points"]["Z9"] = [1.0, 2.0]
    elif mutated:
        places = list(_paths(d))
        path, is_key = draw(st.sampled_from(places))
        _mutate(d, path, is_key, draw(st.sampled_from(HOSTILE)))
    return d, mutated


def _validated_at_load(model) -> None:
    """A loaded model's masses, loads, gravity and pressure angle are already valid (no later refusal)."""
    parse_masses(model)
    parse_loads(model)
    gravity_of(model)
    pressure_angle_of(model)


def _csv_is_sound(r) -> None:
    """The analyze table of the result: unique column names, every row as wide as the header."""
    cols = dict(r.columns(degrees=True))
    cols["reason"] = list(r.reason)
    rows = list(csv.reader(io.StringIO(table_text(cols, "csv"))))
    assert len(set(rows[0])) == len(rows[0]) == len(cols), "column names collide"
    assert {len(row) for row in rows} == {len(rows[0])}


def _pipeline(m: Mechanism) -> None:
    s = m.structure()
    assert s.dof >= 0
    q = m.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 7)
    r = m.solve(q)
    assert r.closed.shape == (7,)
    assert np.all(np.isfinite(r.angle["crank"][r.closed]))
    _csv_is_sound(r)
    if "masses" in m.model.extra and r.closed.all():
        d = m.inverse_dynamics(q, np.full_like(q, 10.0), np.zeros_like(q))
        assert np.all(np.isfinite(d.input_force))


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(case=model_files())
def test_generated_model_files_load_and_analyse_or_are_refused(tmp_path_factory, case):
    d, mutated = case
    path = tmp_path_factory.mktemp("model") / "m.toml"
    try:
        path.write_text(to_toml(d), encoding="utf-8")
    except (TypeError, UnicodeEncodeError):  # a value TOML cannot hold (never produced by the strategies)
        raise AssertionError(f"the test's TOML writer failed on {d!r}") from None
    try:
        model = load_model(path)
    except GearleverError as exc:
        assert mutated, f"a valid model was refused: {exc}"
        assert "\n" not in str(exc)
        return
    _validated_at_load(model)
    try:
        _pipeline(Mechanism(model))
    except GearleverError as exc:
        assert "\n" not in str(exc)


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(case=model_files())
def test_model_from_dict_refuses_what_the_file_loader_refuses(tmp_path_factory, case):
    """The API (dict) and the file loader agree: both accept, or both refuse with the same message."""
    d, _ = case
    path = tmp_path_factory.mktemp("model") / "m.toml"
    path.write_text(to_toml(d), encoding="utf-8")
    try:
        load_model(path)
        file_error = None
    except GearleverError as exc:
        file_error = str(exc).split(": ", 1)[1]
    try:
        model_from_dict(d)
        dict_error = None
    except GearleverError as exc:
        dict_error = str(exc)
    if file_error is None or dict_error is None:
        assert file_error == dict_error


def test_model_from_dict_refuses_non_string_keys_and_wrong_types():
    base = {
        "points": {"O": [0, 0], "A": [1, 0]},
        "links": {"ground": ["O"], "crank": ["O", "A"]},
        "inputs": [{"link": "crank"}],
    }
    bad = [
        ({**base, "points": {1: [0, 0], "A": [1, 0]}}, "[points]"),
        ({**base, 3: {}}, "table names must be strings"),
        ({**base, "masses": ["crank"]}, "masses"),
        ({**base, "masses": {"crank": 5.0}}, "masses.crank"),
        ({**base, "mechanism": {"gravity": "down"}}, "mechanism.gravity"),
        ({**base, "points": {"O": [True, 0], "A": [1, 0]}}, "points.O[0]"),
    ]
    for d, words in bad:
        try:
            model_from_dict(d)
        except GearleverError as exc:
            assert words in str(exc), (words, str(exc))
        else:
            raise AssertionError(f"accepted {d!r}")


def test_solve_refuses_bools_and_text_naming_q():
    m = Mechanism.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )
    for q in ([True, False], ["1", "2"], "abc", [0.1, "x"], True):
        try:
            m.solve(q)
        except GearleverError as exc:
            assert str(exc).startswith("q "), str(exc)
        else:
            raise AssertionError(f"solve accepted q={q!r}")


def test_misspelt_result_names_are_refused_listing_the_valid_ones():
    m = Mechanism.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )
    r = m.solve([0.1, 0.2])
    for mapping, name, listed in ((r.angle, "crnak", "crank"), (r.point, "Q", "O2"), (r.omega, "rocekr", "rocker")):
        try:
            mapping[name]
        except GearleverError as exc:
            assert isinstance(exc, KeyError) and name in str(exc) and listed in str(exc)
        else:
            raise AssertionError(f"{name!r} was found")
    assert "crank" in r.angle and "Q" not in r.point and r.point.get("Q") is None


def test_the_hypothesis_profile_has_no_deadline():
    assert settings.default.deadline is None
