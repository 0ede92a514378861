"""Published cam values (src/gearlever/data/cam_published.toml, each entry with its source)
reproduced by gearlever.laws and gearlever.cams within the printed precision."""

import math
import tomllib

import numpy as np
import pytest

from gearlever.cams import design_cam, size_base_radius
from gearlever.data import read_text
from gearlever.laws import law_from_segments
from gearlever.laws.motions import MOTIONS

DATA = tomllib.loads(read_text("cam_published.toml"))


@pytest.mark.parametrize("case", DATA["sizing"], ids=lambda c: c["name"])
def test_base_circle_sizing_reproduces_the_printed_answer(case):
    law = law_from_segments("displacement", case["units"], case["segments"])
    rb = size_base_radius(law, case["follower"], min_curvature_radius=case["min_curvature_radius"])
    assert rb == pytest.approx(case["base_radius"], abs=case["base_radius_tolerance"]), case["source"]
    cam = design_cam(law, case["follower"], base_radius=rb)
    assert cam.face_width == pytest.approx(case["face_width"], abs=case["face_width_tolerance"]), case["source"]


@pytest.mark.parametrize("case", DATA["coefficients"], ids=lambda c: c["name"])
def test_printed_motion_coefficients_match_the_motion(case):
    u = np.linspace(case["lo"], case["hi"], 201)[:-1]
    printed = case["c0"] + case["c1"] * u + case["c2"] * np.sin(case["w"] * u + case["p"])
    got = MOTIONS[case["motion"]].y(u)
    assert np.max(np.abs(got - printed)) < case["tolerance"], case["source"]


def test_every_entry_names_its_source():
    for table in ("sizing", "coefficients"):
        assert all(len(c["source"]) > 20 for c in DATA[table])
    assert math.isfinite(DATA["sizing"][0]["base_radius"])
