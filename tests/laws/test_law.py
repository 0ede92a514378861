"""Motion laws from segments, samples and LAW.toml: evaluation, continuity (Norton's fundamental
law of cam design) and the refusals of bad input."""

import math

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.laws import law_from_samples, law_from_segments, load_law

DWELL_RISE_RETURN = [
    {"to": 120, "motion": "dwell"},
    {"to": 240, "motion": "cycloidal", "rise": 45},
    {"to": 360, "motion": "345", "rise": -45},
]


def test_segment_law_values_and_derivatives_match_finite_differences():
    law = law_from_segments("angle", "deg", DWELL_RISE_RETURN)
    th = np.linspace(0.001, 2 * math.pi - 0.001, 1001)
    th = th[np.min(np.abs(th[:, None] - law.breaks[None, :]), axis=1) > 1e-3]
    h = 1e-6
    v0, vp, vm = law.evaluate(th), law.evaluate(th + h), law.evaluate(th - h)
    for lo, hi in (("s", "v"), ("v", "a"), ("a", "j")):
        fd = (getattr(vp, lo) - getattr(vm, lo)) / (2 * h)
        scale = max(1.0, np.max(np.abs(getattr(v0, hi))))
        np.testing.assert_allclose(fd, getattr(v0, hi), atol=2e-5 * scale)


def test_segment_law_endpoint_and_peak_values():
    law = law_from_segments("angle", "deg", DWELL_RISE_RETURN)
    v = law.evaluate(np.radians([0, 60, 120, 180, 240, 300, 360, 420]))
    np.testing.assert_allclose(np.degrees(v.s), [0, 0, 0, 22.5, 45, 22.5, 0, 0], atol=1e-12)
    beta, h = math.radians(120), math.radians(45)
    fine = law.evaluate(np.linspace(math.radians(120), math.radians(240), 20001))
    assert np.max(fine.v) == pytest.approx(2 * h / beta, rel=1e-9)  # cycloidal: 2 h / beta
    assert np.max(fine.a) == pytest.approx(2 * math.pi * h / beta**2, rel=1e-6)  # 2 pi h / beta^2
    ret = law.evaluate(np.linspace(math.radians(240), math.radians(360), 20001))
    assert np.max(np.abs(ret.a)) == pytest.approx(5.7735 * h / beta**2, rel=1e-4)  # 3-4-5


def test_per_second_scales_by_powers_of_omega():
    law = law_from_segments("displacement", "mm", DWELL_RISE_RETURN)
    th = np.linspace(0, 6, 7)
    r, s = law.evaluate(th), law.evaluate(th).per_second(120)
    w = 4 * math.pi
    np.testing.assert_allclose(s.v, r.v * w)
    np.testing.assert_allclose(s.a, r.a * w**2)
    np.testing.assert_allclose(s.j, r.j * w**3)
    assert list(s.to_frame().columns) == ["theta_rad", "s_mm", "v_mm_per_s", "a_mm_per_s2", "j_mm_per_s3"]


def test_cycloidal_and_345_law_is_continuous_in_s_v_a():
    rep = law_from_segments("angle", "deg", DWELL_RISE_RETURN).continuity()
    assert rep.ok and rep.problems() == []
    assert np.abs(rep.jump_j[1]) > 0  # the jerk may jump (finite): allowed by the fundamental law


def test_linear_next_to_a_dwell_reports_infinite_acceleration():
    law = law_from_segments(
        "displacement",
        "mm",
        [
            {"to": 90, "motion": "dwell"},
            {"to": 180, "motion": "linear", "rise": 10},
            {"to": 360, "motion": "linear", "rise": -10},
        ],
    )
    rep = law.continuity()
    assert not rep.ok
    np.testing.assert_allclose(np.degrees(rep.infinite_acceleration), [0, 90, 180])
    np.testing.assert_allclose(rep.jump_v[1], 10 / (math.pi / 2))
    assert "acceleration infinite" in rep.problems()[0]


def test_harmonic_next_to_a_dwell_reports_infinite_jerk():
    law = law_from_segments(
        "displacement",
        "mm",
        [
            {"to": 90, "motion": "dwell"},
            {"to": 180, "motion": "harmonic", "rise": 10},
            {"to": 360, "motion": "cycloidal", "rise": -10},
        ],
    )
    rep = law.continuity()
    assert not rep.ok and rep.infinite_acceleration.size == 0
    np.testing.assert_allclose(np.degrees(rep.infinite_jerk), [90, 180])
    np.testing.assert_allclose(rep.jump_a[1], 10 * math.pi**2 / 2 / (math.pi / 2) ** 2)


def test_net_change_of_a_non_returning_law():
    law = law_from_segments("angle", "deg", [{"to": 360, "motion": "linear", "rise": 90}])
    assert law.net_change() == pytest.approx(math.pi / 2)
    assert law.continuity().ok  # the joint is compared with the net change removed


def test_samples_law_is_a_periodic_spline_reproducing_a_smooth_law():
    x = np.arange(0, 360, 2.0)
    law = law_from_samples("displacement", "mm", x, 5 - 5 * np.cos(np.radians(x)))
    th = np.linspace(0, 2 * math.pi, 777)
    v = law.evaluate(th)
    np.testing.assert_allclose(v.s, 5 - 5 * np.cos(th), atol=1e-6)
    np.testing.assert_allclose(v.v, 5 * np.sin(th), atol=1e-5)
    np.testing.assert_allclose(v.a, 5 * np.cos(th), atol=1e-3)
    assert law.continuity().ok and law.net_change() == 0.0


def test_samples_law_spanning_0_to_360_keeps_its_net_change():
    x = np.linspace(0, 360, 37)
    law = law_from_samples("angle", "deg", x, x / 2 + 3 * np.sin(np.radians(x)))
    assert law.net_change() == pytest.approx(math.pi)
    np.testing.assert_allclose(law.evaluate(math.radians(90)).s, math.radians(45 + 3), atol=1e-4)


@pytest.mark.parametrize(
    ("segments", "match"),
    [
        ([{"to": 120, "motion": "dwell"}, {"to": 300, "motion": "cycloidal", "rise": 5}], "must end at 360"),
        ([{"to": 120, "motion": "dwell"}, {"to": 100, "motion": "cycloidal", "rise": 5}], "segment 2.*overlap"),
        (
            [{"to": 120, "motion": "dwell", "rise": 3}, {"to": 360, "motion": "linear", "rise": 5}],
            "segment 1.*on a dwell",
        ),
        ([{"to": 360, "motion": "cycloid", "rise": 5}], "did you mean 'cycloidal'"),
        ([{"to": 360, "motion": "cycloidal"}], "segment 1: rise .* is missing"),
        ([{"to": 360, "motion": "cycloidal", "rise": 5, "rize": 1}], "unknown key 'rize'"),
        ([{"to": 400, "motion": "dwell"}], "past 360"),
        ([{"to": 1e-300, "motion": "linear", "rise": 5}, {"to": 360, "motion": "linear", "rise": -5}], "span at least"),
        ([], "non-empty"),
    ],
)
def test_bad_segments_are_refused_naming_the_segment(segments, match):
    with pytest.raises(GearleverError, match=match):
        law_from_segments("displacement", "mm", segments, source="L.toml")


@pytest.mark.parametrize(
    ("x", "y", "match"),
    [
        ([0, 10, 20, 30, 40], [0, 1, float("nan"), 1, 0], r"row 3: output is nan"),
        ([0, 10, 10, 30, 40], [0, 1, 2, 1, 0], "row 3: input_deg 10 duplicates"),
        ([0, 10, 30, 20, 40], [0, 1, 2, 1, 0], "row 4: input_deg 20 after 30"),
        ([0, 10, 20, 30, 400], [0, 1, 2, 1, 0], "0 .. 360"),
    ],
)
def test_bad_samples_are_refused_naming_the_row(x, y, match):
    with pytest.raises(GearleverError, match=match):
        law_from_samples("displacement", "mm", x, y, source="law.csv")


def test_load_law_toml_segments_and_samples(tmp_path):
    p = tmp_path / "law.toml"
    p.write_text(
        '[law]\noutput = "angle"\nunits = "deg"\n'
        '[[law.segment]]\nto = 120\nmotion = "dwell"\n'
        '[[law.segment]]\nto = 240\nmotion = "cycloidal"\nrise = 45\n'
        '[[law.segment]]\nto = 360\nmotion = "345"\nrise = -45\n'
    )
    law = load_law(p)
    assert law.motions == ("dwell", "cycloidal", "345")
    np.testing.assert_allclose(law.rises, np.radians([0, 45, -45]))
    csv = tmp_path / "law.csv"
    x = np.arange(0, 360, 10)
    csv.write_text("input_deg,output\n" + "".join(f"{a},{np.sin(np.radians(a))}\n" for a in x))
    (tmp_path / "s.toml").write_text('[law]\noutput = "displacement"\nunits = "mm"\nsamples = "law.csv"\n')
    slaw = load_law(tmp_path / "s.toml")
    assert float(slaw.evaluate(math.pi / 2).s) == pytest.approx(1.0, abs=1e-4)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("[law\n", "not valid TOML"),
        ('[law]\noutput = "angle"\n', "units is missing"),
        ('[law]\noutput = "angel"\nunits = "deg"\nsamples = "x.csv"\n', "did you mean 'angle'"),
        ('[law]\noutput = "displacement"\nunits = "mm"\nsamples = "missing.csv"\n', "no such file"),
        ('[law]\noutput = "displacement"\nunits = "mm"\nsegments = []\n', "unknown key 'segments'.*'segment'"),
    ],
)
def test_bad_law_files_are_refused_naming_the_file(tmp_path, text, match):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(GearleverError, match=match) as exc:
        load_law(p)
    assert "bad.toml" in str(exc.value)
