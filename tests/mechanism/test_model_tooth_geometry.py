"""The model's optional tooth geometry: [mechanism] module and pressure_angle, per gear shift, face_width, helix."""

from __future__ import annotations

import math

import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism.model import model_from_dict


def _model(ga=None, gb=None, c=(3.0, 0.0), mech=None):
    return {
        "mechanism": {"module": 0.1, **(mech or {})},
        "points": {"O": [0, 0], "C": list(c)},
        "links": {"ground": ["O", "C"], "a": ["O"], "b": ["C"]},
        "gears": {
            "ga": {"link": "a", "centre": "O", "teeth": 20, **(ga or {})},
            "gb": {"link": "b", "centre": "C", "teeth": 40, **(gb or {})},
        },
        "meshes": [{"gears": ["ga", "gb"]}],
        "inputs": [{"link": "a"}],
    }


def test_keys_are_kept_on_the_gears():
    m = model_from_dict(_model({"shift": 0.2, "face_width": 1.5}, {"shift": -0.2}))
    ga, gb = m.gears["ga"], m.gears["gb"]
    assert (ga.shift, ga.face_width, ga.helix, gb.shift, gb.face_width) == (0.2, 1.5, 0.0, -0.2, None)


def test_shifted_centre_distance_is_the_working_one():
    # KHK's shifted spur example: m 3, z 12 and 24, x 0.6 and 0.36 -> a = 56.4999 mm
    from gearlever.mechanism.model import tight_centre_distance

    def pair(a):
        return _model({"teeth": 12, "shift": 0.6}, {"teeth": 24, "shift": 0.36}, c=(a, 0.0), mech={"module": 3.0})

    with pytest.raises(GearleverError, match=r"centre distance 54 .*shifts and helix = 56.49986"):
        model_from_dict(pair(54.0))
    m = model_from_dict(pair(56.4999))  # the printed value is within the loader's 1e-6 relative tolerance
    assert tight_centre_distance(3.0, *m.gears.values()) == pytest.approx(56.4999, abs=5e-5)


def test_helical_centre_distance_uses_the_transverse_module():
    beta = 20.0
    a = 0.1 * 60 / (2 * math.cos(math.radians(beta)))
    m = model_from_dict(_model({"helix": beta}, {"helix": beta}, c=(a, 0.0)))
    assert m.gears["ga"].helix == pytest.approx(math.radians(beta))
    assert m.pitch_radius("ga") == pytest.approx(0.1 * 20 / (2 * math.cos(math.radians(beta))))


@pytest.mark.parametrize(
    "ga, gb, words",
    [
        ({"shift": "x"}, {}, "gears.ga.shift must be a number"),
        ({"shift": 7}, {}, "gears.ga.shift must be in [-5, 5]"),
        ({"face_width": 0}, {}, "gears.ga.face_width must be positive"),
        ({"face_width": -2}, {}, "gears.ga.face_width must be positive"),
        ({"helix": 45}, {"helix": 45}, "gears.ga.helix must be in [0, 45) deg"),
        ({"helix": 10}, {}, "meshes[0] (ga-gb): the helix angles differ"),
        ({"shift": -3}, {"shift": -3}, "meshes[0] (ga-gb): the shifts -3, -3 leave no working pressure angle"),
    ],
)
def test_bad_values_name_the_element(ga, gb, words):
    with pytest.raises(GearleverError) as exc:
        model_from_dict(_model(ga, gb))
    assert words in str(exc.value)
