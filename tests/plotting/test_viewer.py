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
from gearlever.plotting.viewer import GRID_STEPS, viewer_data, viewer_html

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
