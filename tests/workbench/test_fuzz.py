"""Fuzzing the workbench API (hypothesis): every route of the OpenAPI document, generated bodies and names.

Bodies are arbitrary JSON, JSON shaped like each route's schema with wrong
types and out-of-range numbers, and model texts built from the schema's
tables with random names, numbers and broken lines (so that the generated
models reach the solver, not only the parser).  Every answer must be below
500, carry no traceback, and a 4xx must be ``{"error": ...}``.  The examples
are bounded so the module runs in well under a minute.
"""

from __future__ import annotations

import json

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.workbench._client import api_client, example_text

EXAMPLES = 30
FUZZ = settings(
    max_examples=EXAMPLES, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True, database=None
)


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    ws = tmp_path_factory.mktemp("fuzz")
    (ws / "m.toml").write_text(example_text("fourbar"))
    with api_client(ws, solve_seconds=20.0) as c:
        yield c


def check(r) -> None:
    assert r.status_code < 500, (r.status_code, r.text[:500])
    assert "Traceback" not in r.text and 'File "' not in r.text
    if r.status_code >= 400:
        body = r.json()
        assert isinstance(body.get("error"), str) and body["error"]


names = st.sampled_from(["O", "A", "B", "C", "P", "ground", "crank", "coupler", "rocker", "g1", "s1", "é", "</x>"])
numbers = st.one_of(
    st.integers(-(10**6), 10**6),
    st.floats(-1e6, 1e6, allow_nan=False),
    st.sampled_from([0, 1e300, -1e-300, 1e12, 2**63, 10**30]),
)
json_values = st.recursive(
    st.one_of(st.none(), st.booleans(), numbers, st.text(max_size=20)),
    lambda kids: st.one_of(st.lists(kids, max_size=4), st.dictionaries(st.text(max_size=8), kids, max_size=4)),
    max_leaves=12,
)


def _toml_value(v) -> str:
    return json.dumps(v)


@st.composite
def model_texts(draw):
    """A model file from the schema's tables: random points, links, inputs, sliders, gears, meshes, lines."""
    base = draw(st.sampled_from(["fourbar", "slider_crank", "watt_sixbar", "geared_fivebar", "none"]))
    lines = [] if base == "none" else example_text(base).splitlines()
    for _ in range(draw(st.integers(0, 4))):
        kind = draw(st.integers(0, 9))
        n, m = draw(names), draw(names)
        if kind == 0 and lines:
            del lines[draw(st.integers(0, len(lines) - 1))]
        elif kind == 1:
            lines += ["[points]", f"{n} = [{draw(numbers)}, {draw(numbers)}]"]
        elif kind == 2:
            lines += ["[links]", f"{n} = {_toml_value(draw(st.lists(names, max_size=4)))}"]
        elif kind == 3:
            lines += ["[[inputs]]", f'link = "{n}"']
        elif kind == 4:
            lines += [
                "[[sliders]]",
                f'link = "{n}"',
                f'on = "{m}"',
                f'point = "{draw(names)}"',
                f"direction = [{draw(numbers)}, {draw(numbers)}]",
            ]
        elif kind == 5:
            lines += ["[gears]", f'{n} = {{ link = "{m}", centre = "{draw(names)}", teeth = {draw(numbers)} }}']
        elif kind == 6:
            lines += ["[[meshes]]", f'gears = ["{n}", "{m}"]']
        elif kind == 7 and lines:
            i = draw(st.integers(0, len(lines) - 1))
            lines[i] = lines[i].replace(
                draw(st.sampled_from(["0", "A", "=", "[", '"', "crank"])), draw(st.text(max_size=3))
            )
        elif kind == 8:
            lines.append(draw(st.text(max_size=30)))
        else:
            lines += ["[masses]", f"{n} = {{ mass = {draw(numbers)} }}", "[[loads]]", f'link = "{m}"']
    return "\n".join(lines) + "\n"


frames = st.one_of(st.integers(-5, 400), st.sampled_from([2, 3600, 3601, 10**9]), json_values)


def bodies(model_key_value):
    return st.one_of(
        json_values,
        st.fixed_dictionaries(
            {"model": model_key_value},
            optional={
                "frames": frames,
                "inputs": st.one_of(json_values, st.dictionaries(names, numbers, max_size=2)),
                "rpm": st.one_of(json_values, st.dictionaries(names, numbers, max_size=2)),
            },
        ),
    )


model_bodies = bodies(st.one_of(model_texts(), json_values))


@FUZZ
@given(path=st.sampled_from(["/api/solve", "/api/parse", "/api/structure", "/api/forces"]), body=model_bodies)
def test_model_routes_never_answer_5xx(client, path, body):
    check(client.post(path, json=body))


@FUZZ
@given(obj=json_values, joint=st.one_of(st.sampled_from(["B", "A", "P"]), json_values), text=model_texts())
def test_model_objects_and_branch_flips_never_answer_5xx(client, obj, joint, text):
    # the page's edit (the model as a JSON object) and the assembly-branch flip of a dyad's joint
    check(client.post("/api/solve", json={"model": obj, "frames": 8}))
    check(client.post("/api/branch", json={"model": text, "joint": joint}))


@FUZZ
@given(fmt=st.sampled_from(["svg", "csv", "html", "toml", "x", "..", "png", "dxf", "svg-outline"]), body=model_bodies)
def test_export_never_answers_5xx(client, fmt, body):
    if isinstance(body, dict) and fmt in ("svg", "png", "html", "csv", "dxf", "svg-outline"):
        body["frames"] = 8  # drawing is slow: a short cycle
    check(client.post(f"/api/export/{fmt}", json=body))


@FUZZ
@given(
    body=st.one_of(
        json_values,
        st.fixed_dictionaries(
            {
                "model": st.one_of(
                    json_values,
                    st.dictionaries(
                        st.sampled_from(["points", "links", "inputs", "mechanism", "lengths", "sliders", "x"]),
                        json_values,
                        max_size=4,
                    ),
                )
            }
        ),
    )
)
def test_dump_never_answers_5xx(client, body):
    check(client.post("/api/dump", json=body))


job_bodies = st.one_of(
    json_values,
    st.fixed_dictionaries(
        {"kind": st.sampled_from(["path", "curve", "function", "motion", "law", "x"])},
        optional={
            "target": st.one_of(json_values, st.lists(st.lists(numbers, min_size=2, max_size=2), max_size=5)),
            "poses": st.one_of(json_values, st.lists(st.lists(numbers, min_size=3, max_size=3), max_size=6)),
            "budget": st.one_of(numbers, json_values),
            "time": st.one_of(numbers, json_values),
            "expr": st.one_of(st.text(max_size=10), st.sampled_from(["x", "log10(x)", "__import__('os')", "x**x**x"])),
            "x_range": st.lists(numbers, max_size=3),
            "law": st.one_of(st.text(max_size=40), st.just(example_text("fourbar"))),
        },
    ),
)


@FUZZ
@given(body=job_bodies)
def test_jobs_never_answer_5xx(client, body):
    r = client.post("/api/jobs", json=body)
    check(r)
    if r.status_code == 202:  # a valid job: stop it, the next example needs the slot
        job_id = r.json()["id"]
        check(client.delete(f"/api/jobs/{job_id}"))
        check(client.get(f"/api/jobs/{job_id}"))


CAM_FILE = (
    '[cam]\nfollower = "translating-roller"\nbase_radius = 30.0\nroller_radius = 5.0\ncentre = [3.0, 4.0]\n'
    + example_text("law_lift")
)

cam_bodies = st.one_of(
    json_values,
    st.fixed_dictionaries(
        {},
        optional={
            "example": st.one_of(st.sampled_from(["law_lift", "law_dwell_rocker", "fourbar", "../x"]), json_values),
            "law": st.one_of(st.text(max_size=40), st.just(example_text("law_lift")), json_values),
            "file": st.one_of(
                st.text(max_size=40),
                st.just(CAM_FILE),
                st.just(CAM_FILE.replace("centre = [3.0, 4.0]", "centre = [1e400, 2]")),
                st.just(CAM_FILE.replace("[cam]", '[cam]\nwheel = "x"')),
                json_values,
            ),
            "follower": st.one_of(
                st.sampled_from(["translating-roller", "translating-flat", "oscillating-roller", "x"]), json_values
            ),
            "centre": st.one_of(json_values, st.lists(numbers, max_size=3)),
            "base_radius": st.one_of(numbers, json_values),
            "roller_radius": st.one_of(numbers, json_values),
            "offset": numbers,
            "arm": numbers,
            "pivot_distance": numbers,
            "max_pressure_angle_deg": st.one_of(numbers, json_values),
            "frames": st.one_of(st.integers(-5, 50), json_values),
            "angles_deg": st.one_of(json_values, st.lists(numbers, max_size=5)),
            "x": json_values,
        },
    ),
)


@FUZZ
@given(body=cam_bodies)
def test_cam_never_answers_5xx(client, body):
    check(client.post("/api/cam", json=body))


@FUZZ
@given(
    fmt=st.sampled_from(["dxf", "svg-outline", "csv"]),
    cam=st.one_of(st.just(CAM_FILE), st.text(max_size=40), json_values),
    angle=st.one_of(numbers, json_values),
)
def test_export_with_a_cam_never_answers_5xx(client, fmt, cam, angle):
    body = {"model": example_text("fourbar"), "frames": 8, "cam": cam, "cam_angle_deg": angle}
    check(client.post(f"/api/export/{fmt}", json=body))


@FUZZ
@given(
    name=st.one_of(
        st.text(max_size=30),
        st.sampled_from(["m.toml", "../m.toml", "a.links.json", "%2e%2e", "con.toml", "m.cam.toml"]),
    ),
    method=st.sampled_from(["GET", "PUT"]),
    body=st.one_of(
        json_values,
        st.fixed_dictionaries(
            {"model": st.one_of(st.text(max_size=50), st.just(CAM_FILE), st.just(CAM_FILE[:90]), json_values)}
        ),
    ),
    if_match=st.one_of(st.none(), st.text(max_size=20).filter(lambda s: s.isprintable() and s.isascii())),
)
def test_files_never_answer_5xx(client, name, method, body, if_match):
    from urllib.parse import quote

    headers = {} if if_match is None else {"If-Match": if_match}
    r = client.request(
        method, f"/api/files/{quote(name, safe='')}", json=body if method == "PUT" else None, headers=headers
    )
    check(r)


@FUZZ
@given(path=st.text(max_size=30))
def test_any_path_never_answers_5xx(client, path):
    from urllib.parse import quote

    for prefix in ("/api/", "/api/jobs/", "/api/examples/", "/static/"):
        check(client.get(prefix + quote(path, safe="/")))


@FUZZ
@given(raw=st.binary(max_size=200))
def test_raw_bytes_never_answer_5xx(client, raw):
    check(client.post("/api/solve", content=raw))
