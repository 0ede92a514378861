"""The viewer page as text: size, strict JSON, no external resources, data equal to the solver."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.centres import instant_centres
from gearlever.plotting.viewer import (
    GRID_STEPS,
    MAX_PAGE_BYTES,
    MAX_VIEW_LINKS,
    MAX_VIEW_WORK,
    page_estimate,
    viewer_data,
    viewer_html,
)

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _mech(name):
    return Mechanism.load(EXAMPLES / f"{name}.toml")


def _payload(page: str) -> str:
    m = re.search(r'<script id="gl-data" type="application/json">(.*?)</script>', page, re.S)
    assert m, "no data block"
    return m.group(1)


def _strict_loads(text):
    def refuse(c):
        raise ValueError(f"non-strict JSON constant {c}")

    return json.loads(text, parse_constant=refuse)


def test_watt_sixbar_page_at_360_frames_is_under_300_kb():
    page = viewer_html(_mech("watt_sixbar"), frames=360)
    assert len(page.encode("utf-8")) < 300_000


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "whitworth", "geared_fivebar", "zrdpm_gear_contour"])
def test_example_pages_stay_under_300_kb(name):
    assert len(viewer_html(_mech(name)).encode("utf-8")) < 300_000


def test_page_json_is_strict_and_cannot_close_its_script():
    page = viewer_html(_mech("slider_crank"), frames=36)  # slider/ground centre at infinity: nulls
    text = _payload(page)
    assert "</" not in text
    d = _strict_loads(text)
    assert "NaN" not in text and "Infinity" not in text
    assert d["ic"]["x"]["ground/piston"] == [None]


def test_a_name_with_a_closing_tag_is_escaped():
    m = Mechanism.from_dict(
        {
            "mechanism": {"name": "</script>__DATA__<b>x</b>"},
            "points": {"O": [0, 0], "A": [1, 0]},
            "links": {"ground": ["O"], "crank": ["O", "A"]},
            "inputs": [{"link": "crank"}],
        }
    )
    page = viewer_html(m, frames=4)
    assert page.count("</script>") == 2  # the data block and the code block
    assert _strict_loads(_payload(page))["name"] == "</script>__DATA__<b>x</b>"
    assert "<b>x</b>" not in page.split("<script", 1)[0]  # title and heading escaped


def test_page_loads_nothing_from_outside():
    page = viewer_html(_mech("watt_sixbar"), frames=36)
    assert "http" not in page.lower()
    assert not re.search(r"""\b(src|href)\s*=\s*["'](?!#)""", page)
    assert "@import" not in page and "url(" not in page.replace("url(#head-", "")


def test_frames_follow_the_contract_and_points_equal_the_solver_to_six_digits():
    mech = _mech("fourbar")
    N = 90
    d = viewer_data(mech, frames=N)
    q = mech.sketch_inputs[0] + 2 * np.pi * np.arange(N) / N
    r = mech.solve(q)
    assert d["N"] == N and d["M"] == 1
    for p in ("A", "B", "P"):
        got = np.array(d["S"]["x"][p][0], dtype=float)
        np.testing.assert_allclose(got, r.point[p][:, 0], rtol=6e-6, atol=1e-12)
    assert d["S"]["x"]["O4"] == [40]  # a ground point: one value
    ic = instant_centres(r)
    k = ic.pairs.index("ground/coupler")
    got = np.array([np.nan if v is None else v for v in d["ic"]["x"]["ground/coupler"][0]])
    np.testing.assert_allclose(got, ic.xy[:, k, 0], rtol=6e-6)


def test_two_input_model_gets_a_grid_of_the_second_input():
    mech = _mech("zrdpm_gear_contour")
    d = viewer_data(mech, frames=12, inputs={"lever1": 0.25})
    assert d["M"] == GRID_STEPS and d["ic"] is None
    assert d["grid"]["values"][0] == pytest.approx(0.25)
    assert d["grid"]["values"][1] == pytest.approx(0.25 + 2 * math.pi / GRID_STEPS)
    j = 5
    q = np.column_stack([np.arange(12) * 2 * np.pi / 12, np.full(12, d["grid"]["values"][j])])
    r = mech.solve(q, np.tile([1.0, 0.0], (12, 1)))
    got = d["S"]["x"]["E"][j]
    want = r.point["E"][:, 0]
    if isinstance(got, (int, float)):  # E is on the lever: constant while the first input turns
        got = [got] * 12
    np.testing.assert_allclose(got, want, rtol=6e-6, atol=1e-9)
    assert len(d["closed"]) == 12 * GRID_STEPS


def test_rpm_gives_velocities_per_second_and_the_period():
    mech = _mech("slider_crank")
    d0, d1 = viewer_data(mech, frames=8), viewer_data(mech, frames=8, rpm=600)
    assert d1["period"] == pytest.approx(0.1)
    v0 = np.array(d0["S"]["vx"]["B"][0], dtype=float)
    v1 = np.array(d1["S"]["vx"]["B"][0], dtype=float)
    np.testing.assert_allclose(v1, v0 * 600 * math.pi / 30, rtol=1e-5, atol=1e-9)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"frames": 1}, "frames"),
        ({"frames": 10**6}, "frames"),
        ({"rpm": {"crnk": 3}}, "rpm"),
        ({"inputs": {"crank": float("nan")}}, "inputs"),
        ({"inputs": {"x": 1.0}}, "inputs"),
    ],
)
def test_bad_arguments_are_refused_naming_the_parameter(kw, match):
    with pytest.raises(GearleverError, match=match):
        viewer_data(_mech("fourbar"), **kw)


# ---------------------------------------------------------------------------- hostile text, size and work caps

#: Mechanism names (free text) that would end, comment out or re-open the data block if embedded raw.
HOSTILE_TITLES = [
    '"<!--<script>',
    "</script><script>alert(1)</script>",
    "<!-- -->&amp;&lt;b&gt;<b>bold</b>",
    "a\u2028b\u2029c ]]> ${x} `tick` 'q'",
]
#: The most unusual names the model file accepts for points, links and inputs (letters, digits, '.', '-').
ODD = {"pivot": "Ø.2", "pin": "A-1.x", "crank": "κρανκ-1", "rocker": "名前.r"}


def hostile_model(title: str) -> dict:
    o, a = ODD["pivot"], ODD["pin"]
    return {
        "mechanism": {"name": title, "units": "µm", "module": 1.0},
        "points": {o: [0, 0], a: [10, 0], "B-2": [28, 20], "O.4": [40, 0]},
        "links": {"ground": [o, "O.4"], ODD["crank"]: [o, a], "cöupler": [a, "B-2"], ODD["rocker"]: ["O.4", "B-2"]},
        "gears": {"ζ-gear.1": {"link": ODD["crank"], "centre": o, "teeth": 12}},
        "inputs": [{"link": ODD["crank"]}],
    }


@pytest.mark.parametrize("title", HOSTILE_TITLES)
def test_hostile_text_is_escaped_in_the_data_block_and_the_title(title):
    page = viewer_html(Mechanism.from_dict(hostile_model(title)), frames=8)
    text = _payload(page)
    assert not set(text) & set("<>&\u2028\u2029")  # escaped as \\u003c ... inside the JSON strings
    d = _strict_loads(text)
    assert d["name"] == title and d["units"] == "µm"
    assert {lk["name"] for lk in d["links"]} == {ODD["crank"], "cöupler", ODD["rocker"]}
    assert d["inputs"][0]["label"] == ODD["crank"] and ODD["pivot"] in d["points"]
    assert d["gears"][0]["name"] == "ζ-gear.1" and d["joints"][0] == ODD["pivot"]
    # the page's own markup is intact: two scripts, no comment opened, the title escaped as text
    assert page.count("<script") == 2 and page.count("</script>") == 2 and "<!--" not in page
    head = page.split('<script id="gl-data"', 1)[0]
    shown = title.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
    assert head.count(shown) == 2  # <title> and <h1>, as text
    assert "<b>" not in head and "<script>alert" not in head


def test_page_estimate_bounds_the_data_block_of_every_example():
    for path in sorted(EXAMPLES.glob("*.toml")):
        if path.name.startswith("law_"):  # a motion law (LAW.toml), not a mechanism model
            continue
        mech = Mechanism.load(path)
        if mech.model.inputs[0].kind != "link":
            continue
        for frames in (36, 360):
            payload = _payload(viewer_html(mech, frames=frames))
            est = page_estimate(mech.model, frames)
            assert len(payload) <= est["bytes"], (path.name, frames)


def _refuse_solving(monkeypatch):
    def boom(*a, **k):
        raise AssertionError("solved before the cap refused")

    monkeypatch.setattr(Mechanism, "solve", boom)


def test_a_page_over_the_size_cap_is_refused_before_solving_naming_frames(monkeypatch):
    # a four-bar whose coupler carries 100 tracer points: few links, a large page
    model = {
        "points": {"O2": [0, 0], "A": [10, 0], "B": [28, 20], "O4": [40, 0]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }
    tracers = {f"P{i}": [10 + 0.1 * i, 5 + 0.05 * i] for i in range(100)}
    model["points"].update(tracers)
    model["links"]["coupler"] = ["A", "B", *tracers]
    mech = Mechanism.from_dict(model)
    est = page_estimate(mech.model, 3600)
    assert est["work"] <= MAX_VIEW_WORK and est["bytes"] > MAX_PAGE_BYTES
    _refuse_solving(monkeypatch)
    with pytest.raises(GearleverError, match=r"^frames: .* MB, more than the cap of 20 MB; use at most (\d+) frames"):
        viewer_data(mech, frames=3600)


def test_the_size_cap_holds_at_the_frames_it_suggests(monkeypatch):
    import gearlever.plotting.viewer as v

    mech = _mech("fourbar")
    monkeypatch.setattr(v, "MAX_PAGE_BYTES", 400_000)
    with pytest.raises(GearleverError, match="frames") as e:
        v.viewer_html(mech, frames=3600)
    most = int(re.search(r"at most (\d+) frames", str(e.value)).group(1))
    page = v.viewer_html(mech, frames=most)
    assert len(_payload(page)) <= 400_000
    with pytest.raises(GearleverError, match="frames"):
        v.viewer_html(mech, frames=most + 1)
    # the check after the page is built refuses too when the estimate is beaten
    monkeypatch.setattr(v, "_BYTES_PER_VALUE", 1)
    with pytest.raises(GearleverError, match=r"^frames: the page of 3600 frames would be"):
        v.viewer_html(mech, frames=3600)


def chain_model(dyads: int) -> dict:
    """A crank driving ``dyads`` RR dyads (2 dyads + 1 moving links), each closing on its own ground pivot."""
    pts = {"O": [0.0, 0.0], "A": [10.0, 0.0]}
    links = {"ground": ["O"], "crank": ["O", "A"]}
    for i in range(dyads):
        t = 0.3 * math.sin(i)
        g = np.array([40 * math.cos(t), 40 * math.sin(t)])
        a = np.array([10.0, 0.0])
        dvec = g - a
        dist = float(np.hypot(*dvec))
        along = (35.0**2 - 30.0**2 + dist**2) / (2 * dist)
        h = math.sqrt(35.0**2 - along**2)
        c = a + along * dvec / dist + h * np.array([-dvec[1], dvec[0]]) / dist
        pts[f"G{i}"], pts[f"C{i}"] = g.tolist(), c.tolist()
        links["ground"].append(f"G{i}")
        links[f"cp{i}"], links[f"rk{i}"] = ["A", f"C{i}"], [f"G{i}", f"C{i}"]
    return {"mechanism": {"units": "mm"}, "points": pts, "links": links, "inputs": [{"link": "crank"}]}


def test_work_cap_refuses_many_links_times_frames_before_solving(monkeypatch):
    mech = Mechanism.from_dict(chain_model(50))  # 101 moving links
    _refuse_solving(monkeypatch)
    with pytest.raises(GearleverError, match=r"^frames: 3600 frames x 101 moving links .* at most 2475 frames"):
        viewer_data(mech, frames=3600)
    big = Mechanism.from_dict(chain_model(MAX_VIEW_LINKS // 2))  # 2 (cap // 2) + 1 > cap links
    n = 2 * (MAX_VIEW_LINKS // 2) + 1
    with pytest.raises(GearleverError, match=rf"^mech: \[links\] has {n} moving links, more than .* cap of"):
        viewer_data(big, frames=2)


def test_instant_centres_are_left_out_above_the_body_cap():
    d = viewer_data(Mechanism.from_dict(chain_model(8)), frames=4)  # 17 links, 18 bodies: 153 centres
    assert d["ic"] is None and d["centres_capped"] is True
    d = viewer_data(Mechanism.from_dict(chain_model(7)), frames=4)  # 16 bodies: shown
    assert d["ic"] is not None and len(d["ic"]["pairs"]) == 16 * 15 // 2


@pytest.mark.parametrize("value, match", [(1e10, "turns from its sketch"), (1e308, "turns from its sketch")])
def test_a_start_far_from_the_sketch_is_refused_before_solving(monkeypatch, value, match):
    _refuse_solving(monkeypatch)
    with pytest.raises(GearleverError, match=f"^inputs: crank is .* {match} value, more than the cap of 1000 turns"):
        viewer_data(_mech("fourbar"), inputs={"crank": value})
