"""Function generation: Freudenstein four-bar and slider-crank, exact recovery of known linkages, defects, refusals."""

import re
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from gearlever.errors import GearleverError, GearleverWarning
from gearlever.loops.fourbar import fourbar
from gearlever.mechanism import Mechanism
from gearlever.synthesis.function import function_targets, precision_points, synthesize_function
from tests.synthesis._function_check import RECOMPUTE_TOL, recompute


def _recompute(r):
    return recompute(r.model, r.input_angle, r.target, r.dense_input, r.dense_target)


def test_chebyshev_points_formula_freudenstein_1955():
    # x_j = (a+b)/2 - (b-a)/2 cos((2j-1) pi / 2n): 1 + 0.5 (1 - cos 30 deg), 1.5, 1 + 0.5 (1 + cos 30 deg)
    c = np.cos(np.pi / 6)
    np.testing.assert_allclose(precision_points(1, 2, 3), [1.5 - 0.5 * c, 1.5, 1.5 + 0.5 * c], rtol=1e-15)
    np.testing.assert_allclose(precision_points(0, 1, 5, "even"), [0, 0.25, 0.5, 0.75, 1])


@pytest.mark.parametrize("n", [3, 4, 8])
@pytest.mark.parametrize(
    ("d", "a", "b", "c", "branch"), [(1.0, 0.4, 1.1, 0.9, "open"), (2.0, 0.7, 1.6, 1.9, "crossed")]
)
def test_exact_recovery_of_a_known_fourbar(n, d, a, b, c, branch):
    phi = np.radians(np.linspace(20, 110, n))
    psi = fourbar(d, a, b, c, phi, branch=branch).theta4
    r = synthesize_function(phi, psi, ground=d)
    size = max(d, a, b, c)
    got = [r.lengths[k] for k in ("ground", "crank", "coupler", "rocker")]
    np.testing.assert_allclose(got, [d, a, b, c], atol=1e-9 * size)
    assert np.abs(r.error).max() < 1e-9
    assert r.branch == branch and r.defect == ""
    assert r.exact == (n == 3)


def test_freudenstein_identity_holds_along_the_engine_motion():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    K1, K2, K3 = r.coefficients
    phi, psi = r.dense_input, r.dense_achieved
    lhs = K1 * np.cos(psi) - K2 * np.cos(phi) + K3
    np.testing.assert_allclose(lhs, np.cos(phi - psi), atol=1e-12)
    d, a, b, c = (r.lengths[k] for k in ("ground", "crank", "coupler", "rocker"))
    # K from the lengths (signs: a negative K is a link pointing the other way)
    assert abs(abs(K1) - d / a) < 1e-12 and abs(abs(K2) - d / c) < 1e-12


def test_log10_three_chebyshev_points_met_exactly_and_structural_error_from_engine():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    np.testing.assert_allclose(np.degrees(t.input_angle), [49.0192378865, 75.0, 100.9807621135], atol=1e-9)
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    # the error of the model as written: coordinates at 10 digits of its size (gearlever._format)
    assert np.abs(r.error).max() < 1e-8
    # the structural error vanishes at the precision points and is the engine's, over the range
    assert 0 < r.structural_error_max < np.radians(0.5)
    at = np.interp(t.input_angle, r.dense_input, np.abs(r.dense_achieved - r.dense_target))
    assert at.max() < 1e-3 * r.structural_error_max + 1e-6
    m = Mechanism.from_dict(r.model)
    res = m.solve(m.sketch_inputs[None, :])
    assert bool(res.closed[0])


def test_more_points_by_least_squares_do_not_meet_every_target():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]), points=7)
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    assert not r.exact and np.abs(r.error).max() > 1e-6 and r.defect == ""


def test_branch_defect_flagged_when_a_target_is_on_the_other_assembly():
    d, a, b, c = 1.0, 0.4, 1.1, 0.9
    phi = np.radians([20.0, 60.0, 100.0])
    psi = fourbar(d, a, b, c, phi, branch="open").theta4
    psi[2] = fourbar(d, a, b, c, phi[2:], branch="crossed").theta4[0]
    r = synthesize_function(phi, psi)
    assert "branch defect" in r.defect


@pytest.mark.parametrize("n", [3, 6])
def test_slider_crank_exact_recovery(n):
    a, b, e = 2.0, 5.0, 1.0
    phi = np.radians(np.linspace(10, 150, n))
    s = a * np.cos(phi) + np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    r = synthesize_function(phi, s, kind="slider-crank")
    np.testing.assert_allclose([r.lengths["crank"], r.lengths["rod"], r.lengths["offset"]], [a, b, e], atol=1e-9 * b)
    assert np.abs(r.error).max() < 1e-9 * b
    assert r.branch == "+" and r.defect == ""
    assert r.grashof == "crank turns fully"


@pytest.mark.parametrize(
    ("phi", "out", "match"),
    [
        ([0.1, 0.2], [1.0, 1.1], "at least 3"),
        ([0.1, 0.2, 0.2], [1.0, 1.1, 1.2], "repeats"),
        ([0.1, 0.2, np.nan], [1.0, 1.1, 1.2], "finite"),
        ([0.1, 0.2, 0.3], [1.0, 1.1], "same length"),
    ],
)
def test_bad_targets_refused(phi, out, match):
    with pytest.raises(GearleverError, match=match):
        synthesize_function(phi, out)


def test_zero_width_ranges_refused():
    with pytest.raises(GearleverError, match="x_range"):
        function_targets("x", (1, 1), (0, 1), (0, 1))
    with pytest.raises(GearleverError, match="input_range"):
        function_targets("x", (1, 2), (1, 1), (0, 1))
    with pytest.raises(GearleverError, match="same value"):
        function_targets("cos(x)", (-1, 1), (0, 1), (0, 1))


def test_slider_crank_branch_defect_flagged():
    a, b, e = 2.0, 5.0, 1.0
    phi = np.radians([10.0, 60.0, 110.0])
    root = np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    s = a * np.cos(phi) + root
    s[1] = a * np.cos(phi[1]) - root[1]  # the slider behind the crank pin at target 2
    r = synthesize_function(phi, s, kind="slider-crank")
    assert "branch defect" in r.defect


def test_input_range_extends_the_structural_error_to_the_ends_of_the_design_range():
    # Chebyshev targets lie inside the range: its ends (x = 1 and x = 2) must be in the structural error
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    inner = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    full = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    np.testing.assert_allclose(full.dense_input[[0, -1]], np.radians([45, 105]), rtol=1e-15)
    np.testing.assert_allclose(inner.dense_input[[0, -1]], t.input_angle[[0, -1]], rtol=1e-15)
    np.testing.assert_array_equal(full.lengths["coupler"], inner.lengths["coupler"])
    # the engine's output at the range ends, against the formula: the worst error is at x = 1
    end_err = full.dense_achieved[[0, -1]] - t.target_at(np.radians([45, 105]))
    assert full.structural_error_max == pytest.approx(np.abs(full.dense_achieved - full.dense_target).max())
    assert full.structural_error_max == pytest.approx(abs(end_err[0]), rel=1e-12)
    assert full.structural_error_max > 1.3 * inner.structural_error_max
    with pytest.raises(GearleverError, match="input_range"):
        synthesize_function(t.input_angle, t.target, input_range=(1.0, 1.0))


# ---------------------------------------------------------------------------
# Every combination of signs and ranges: the written model, checked independently
# ---------------------------------------------------------------------------


@given(
    fx=st.sampled_from(
        [
            ("x**1.5", 1, 4),
            ("log10(x)", 1, 2),
            ("log(x)", 1, 3),
            ("sin(x)", 0, 1.5),
            ("exp(x)", 0, 1),
            ("x**2", 0, 1),
            ("1/x", 1, 3),
            ("x**-0.5", 1, 4),
            ("tan(x)", 0, 1),
            ("sqrt(x)", 0.5, 2),
        ]
    ),
    start=st.floats(0, 360),
    span=st.floats(5, 300) | st.floats(-300, -5),
    out_start=st.floats(0, 360),
    out_span=st.floats(5, 270) | st.floats(-270, -5),
    points=st.integers(3, 5),
    kind=st.sampled_from(["fourbar", "fourbar", "slider-crank"]),
)
@settings(max_examples=80, suppress_health_check=[HealthCheck.too_slow])
# found by hypothesis: the least-squares rocker misses target 1 by 122.7 deg (reported 6.605 rad, recomputed 9.747)
@example(fx=("x**1.5", 1, 4), start=0.0, span=151.0, out_start=0.0, out_span=-269.0, points=4, kind="fourbar")
def test_any_ranges_give_a_model_whose_structural_error_is_recomputed_or_a_clean_refusal(
    fx, start, span, out_start, out_span, points, kind
):
    expr, x0, x1 = fx
    orange = np.radians([out_start, out_start + out_span]) if kind == "fourbar" else (out_start / 60, out_span / 60)
    if kind == "slider-crank":
        orange = (orange[0], orange[0] + orange[1])
    t = function_targets(expr, (x0, x1), np.radians([start, start + span]), orange, points)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", GearleverWarning)
            r = synthesize_function(
                t.input_angle, t.target, kind=kind, target_at=t.target_at, input_range=t.input_range
            )
    except GearleverError as exc:
        assert "\n" not in str(exc)
        return
    err_t, sem, margin = _recompute(r)
    tol = RECOMPUTE_TOL * (1.0 if kind == "fourbar" else r.size)
    if r.defect:
        # a refusal has a cause: the linkage folds flat (or cannot close) somewhere in the range,
        # or an exact target lies on the other branch
        assert margin.min() < 1e-6 or (r.exact and np.abs(err_t).max() > 1e-9), r.defect
        return
    assert margin.min() > 0
    if kind == "fourbar":  # a kept four-bar meets every target within a quarter turn (else it is refused)
        assert np.abs(r.error).max() <= np.pi / 2
    for v in (r.structural_error_max, r.structural_error_rms, *r.transmission_range):
        assert np.isfinite(v)
    assert np.all(np.isfinite(r.achieved)) and np.all(np.isfinite(r.dense_achieved))
    assert r.structural_error_max == pytest.approx(sem, abs=tol)
    np.testing.assert_allclose(
        np.angle(np.exp(1j * (r.error - err_t))) if kind == "fourbar" else r.error - err_t, 0, atol=tol
    )
    if r.exact:
        # the written model's coordinates carry 10 digits of its size (gearlever._format): an exact target is
        # met to about 1e-10 of the size over the shortest link, an angle error growing with the link ratio
        assert np.abs(r.error).max() < tol + 1e-8 * r.link_ratio
    assert all(v > 0 for k, v in r.lengths.items() if k != "offset")


def _freudenstein_rocker(K, phi):
    """Both rocker angles solving K1 cos(psi) - K2 cos(phi) + K3 = cos(phi - psi) at crank angle ``phi`` (closed form).

    (K1 - cos phi) cos psi - sin phi sin psi = K2 cos phi - K3, i.e. R cos(psi - g) = C with
    g = atan2(-sin phi, K1 - cos phi): psi = g +/- arccos(C / R) (Freudenstein 1955, eq. of the four-bar loop).
    """
    K1, K2, K3 = K
    g = np.arctan2(-np.sin(phi), K1 - np.cos(phi))
    R = np.hypot(K1 - np.cos(phi), np.sin(phi))
    h = np.arccos((K2 * np.cos(phi) - K3) / R)
    return np.array([g + h, g - h])


def test_least_squares_fourbar_missing_a_target_by_more_than_a_quarter_turn_is_refused_naming_output():
    # hypothesis found x**1.5 on x 1..4, crank 0..151 deg, rocker 0..-269 deg, 4 Chebyshev points: the
    # least-squares four-bar (a double crank) turns its output the other way and misses target 1 by 122.7 deg,
    # so whether the output is its rocker or the rocker reversed (output_offset) was a guess: the result
    # reported 6.605 rad of structural error and the independent recomputation 9.747 (half a turn apart)
    t = function_targets("x**1.5", (1, 4), np.radians([0, 151]), np.radians([0, -269]), 4)
    phi, psi = t.input_angle, t.target
    # the design equation by least squares, independently, then its rocker at target 1 on both branches
    M = np.column_stack([np.cos(psi), -np.cos(phi), np.ones_like(phi)])
    K = np.linalg.lstsq(M, np.cos(phi - psi), rcond=None)[0]
    both = _freudenstein_rocker(K, phi[0])
    assert np.all(np.isfinite(both))  # it assembles at target 1 ...
    miss = np.abs(np.angle(np.exp(1j * (both - psi[0]))))
    assert miss.min() == pytest.approx(np.radians(122.652), abs=np.radians(0.01))  # ... a quarter turn and more off
    with pytest.raises(GearleverError, match=r"^output: .*misses target 1 by 122\.7 deg .*quarter turn") as exc:
        synthesize_function(phi, psi, target_at=t.target_at, input_range=t.input_range)
    assert "\n" not in str(exc.value)
    # a quarter turn the other way over the same crank range is followed, and its error is the recomputed one
    t = function_targets("x**1.5", (1, 4), np.radians([0, 151]), np.radians([0, 90]), 4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GearleverWarning)
        r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert r.defect == "" and np.abs(r.error).max() < np.pi / 2
    _, sem, _ = _recompute(r)
    assert r.structural_error_max == pytest.approx(sem, abs=RECOMPUTE_TOL)
    # the closed-form rocker agrees with the engine's at every target (one of the two branches)
    for p, a in zip(r.input_angle, r.achieved, strict=True):
        near = np.abs(np.angle(np.exp(1j * (_freudenstein_rocker(r.coefficients, p) - a)))).min()
        assert near < 1e-8


def test_issue_case_x_to_the_1_5_has_the_structural_error_of_its_written_model():
    # issue 25: crank 2.24544, coupler 2.94696, rocker 0.89714 on ground 1 (Freudenstein's a and c negative),
    # structural error 0.619 deg; it was NaN (the engine asked a full turn away, through a dead point)
    t = function_targets("x**1.5", (1, 4), np.radians([30, 90]), np.radians([90, 180]))
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert r.coefficients[0] < 0 and r.coefficients[1] < 0  # K1 = d/a, K2 = d/c: both links reversed
    lengths = [r.lengths[k] for k in ("ground", "crank", "coupler", "rocker")]
    np.testing.assert_allclose(lengths, [1.0, 2.24544, 2.94696, 0.89714], atol=5e-6)
    assert r.defect == "" and np.degrees(r.input_offset) == pytest.approx(-180) and r.output_offset == np.pi
    err_t, sem, _ = _recompute(r)
    assert np.degrees(r.structural_error_max) == pytest.approx(0.619, abs=5e-4)
    assert r.structural_error_max == pytest.approx(sem, abs=RECOMPUTE_TOL)
    assert np.abs(r.error).max() < 1e-9


@pytest.mark.parametrize("ranges", [((10, 70), (90, 180)), ((60, 120), (90, 180)), ((200, 260), (90, 180))])
@pytest.mark.parametrize("points", [3, 5])
def test_issue_ranges_are_checked_on_the_written_model(ranges, points):
    ir, orng = ranges
    t = function_targets("x**1.5", (1, 4), np.radians(ir), np.radians(orng), points)
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert r.defect == ""
    err_t, sem, _ = _recompute(r)
    assert r.structural_error_max == pytest.approx(sem, abs=RECOMPUTE_TOL)
    np.testing.assert_allclose(r.error, err_t, atol=RECOMPUTE_TOL)


def test_dead_point_inside_the_range_is_a_defect_naming_where():
    # x**1.5 with the crank 30 -> 90 deg and the rocker 10 -> 70 deg: the linkage folds flat near 89.2 deg
    t = function_targets("x**1.5", (1, 4), np.radians([30, 90]), np.radians([10, 70]))
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert "dead point between the input angles 89.1" in r.defect
    d, a, b, c = (r.lengths[k] for k in ("ground", "crank", "coupler", "rocker"))
    phi = np.radians(np.linspace(89.0, 89.3, 31))
    valid = fourbar(d, a, b, c, phi + r.input_offset, branch=r.branch).valid
    assert valid[0] and not valid[-1]  # the closed form agrees: it stops closing there


def test_reversed_slider_crank_crank_is_checked_on_the_written_model():
    # the crank pin at phi + pi (Freudenstein's negative a): s = -a cos(phi) + sqrt(b^2 - (e + a sin(phi))^2)
    a, b, e = 2.0, 5.0, 1.0
    phi = np.radians([200.0, 240.0, 280.0, 320.0])
    s = -a * np.cos(phi) + np.sqrt(b * b - (e + a * np.sin(phi)) ** 2)
    r = synthesize_function(phi, s, kind="slider-crank")
    assert r.coefficients[0] < 0 and r.defect == ""
    np.testing.assert_allclose([r.lengths["crank"], r.lengths["rod"], r.lengths["offset"]], [a, b, e], atol=1e-9)
    err_t, sem, _ = _recompute(r)
    np.testing.assert_allclose(r.error, err_t, atol=1e-9)
    assert np.abs(r.error).max() < 1e-8  # the written model: coordinates at 10 digits of its size
    assert r.structural_error_max == pytest.approx(sem, abs=1e-9)


def test_impractical_proportions_warn_with_the_ratio():
    t = function_targets("x**1.5", (1, 4), np.radians([300, 400]), np.radians([90, 180]))
    with pytest.warns(GearleverWarning, match=r"impractical proportions: the coupler is 27.7 times the ground"):
        r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    assert r.link_ratio == pytest.approx(27.716, abs=1e-3)
    lengths = [r.lengths[k] for k in ("ground", "crank", "coupler", "rocker")]
    assert r.link_ratio == pytest.approx(max(lengths) / min(lengths), rel=1e-12)
    # the ratios do not depend on the scale
    with pytest.warns(GearleverWarning, match=r"times the ground"):
        r2 = synthesize_function(t.input_angle, t.target, target_at=t.target_at, ground=0.01, input_range=t.input_range)
    assert r2.link_ratio == pytest.approx(r.link_ratio, rel=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error", GearleverWarning)
        ok = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
        assert synthesize_function(ok.input_angle, ok.target).proportions() == ""


_T = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"ground": True}, "ground must be a positive length (a number), got True: a bool is not a length"),
        ({"ground": "1"}, "ground must be a positive length (a number), got the text '1'"),
        ({"ground": 0.0}, "ground must be a positive"),
        ({"ground": float("inf")}, "ground must be a positive"),
        ({"target_at": "x"}, "target_at must be a callable giving the wanted output"),
        ({"target_at": 3.0}, "target_at must be a callable"),
        ({"target_at": lambda q: q[:2]}, "target_at must give a finite output"),
        ({"target_at": lambda q: 1 / 0}, "target_at must give a number"),
        ({"kind": "crank"}, "kind must be one of"),
        ({"kind": None}, "kind must be one of"),
        ({"input_range": "12"}, "input_range must be two numbers"),
        ({"input_range": (True, 2.0)}, "input_range must be two numbers"),
        ({"input_range": (0.0, 7.0)}, "span must be less than 360 deg"),
        ({"dense_points": 1.5}, "dense_points must be an integer"),
        ({"dense_points": 10**9}, "dense_points must be an integer from 2 to 100000"),
        ({"name": 3}, "name must be text"),
    ],
)
def test_api_bad_parameters_refused_naming_them(kwargs, needle):
    with pytest.raises(GearleverError, match=re.escape(needle)):
        synthesize_function(_T.input_angle, _T.target, **kwargs)


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        ((["1", "2", "3"], [1.0, 2.0, 3.0]), "input_angle must be an array of finite numbers, got text"),
        (([True, False, True], [1.0, 2.0, 3.0]), "input_angle must be an array of finite numbers, got bools"),
        (([0.1, 0.2, 0.3], "abc"), "output must be an array of finite numbers"),
        (([1e300, 0.2, 0.3], [1.0, 2.0, 3.0]), "input_angle must be angles in radians of at most"),
    ],
)
def test_api_bad_targets_refused_naming_them(args, needle):
    with pytest.raises(GearleverError, match=re.escape(needle)):
        synthesize_function(*args)


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"x_range": "12"}, "x_range must be two numbers"),
        ({"output_range": (False, 1.0)}, "output_range must be two numbers"),
        ({"points": 3.0}, "points must be an integer"),
        ({"points": True}, "points must be an integer"),
        ({"spacing": None}, "spacing must be 'chebyshev' or 'even'"),
        ({"expression": 5}, "expression must be text"),
        ({"input_range": (0.0, 2 * np.pi)}, "input_range must span less than a full turn"),
    ],
)
def test_function_targets_bad_parameters_refused_naming_them(kwargs, needle):
    args = {"expression": "log10(x)", "x_range": (1, 2), "input_range": (0.5, 1.5), "output_range": (2.0, 3.0)}
    with pytest.raises(GearleverError, match=re.escape(needle)):
        function_targets(**{**args, **kwargs})


@given(
    lengths=st.tuples(st.floats(0.2, 3), st.floats(0.2, 3), st.floats(0.2, 3)),
    start=st.floats(0, 360),
    span=st.floats(10, 200) | st.floats(-200, -10),
    points=st.integers(3, 5),
    branch=st.sampled_from(["open", "crossed"]),
)
@settings(max_examples=40)
def test_pairs_of_a_known_fourbar_anywhere_are_recovered_and_checked(lengths, start, span, points, branch):
    a, b, c = lengths
    assume(max(1.0, a, b, c) < 0.45 * (1.0 + a + b + c))  # assembles with room to spare
    lens = sorted([1.0, a, b, c])
    assume(abs(lens[0] + lens[3] - lens[1] - lens[2]) > 0.05)  # not Grashof's special case (change points)
    phi = np.radians(start + np.linspace(0.0, span, points))
    dense = np.radians(start + np.linspace(0.0, span, 1441))
    assume(fourbar(1.0, a, b, c, dense, branch=branch).valid.all())
    dyad = np.sqrt((1 - a * np.cos(dense)) ** 2 + (a * np.sin(dense)) ** 2)
    assume(np.min(np.minimum(dyad - abs(b - c), b + c - dyad)) > 1e-2)  # clear of dead points
    psi = fourbar(1.0, a, b, c, phi, branch=branch).theta4
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GearleverWarning)
        r = synthesize_function(phi, psi)
    assert r.defect == ""
    np.testing.assert_allclose([r.lengths[k] for k in ("crank", "coupler", "rocker")], [a, b, c], rtol=1e-6)
    err_t, sem, _ = _recompute(r)
    assert np.abs(r.error).max() < 1e-7 and np.abs(err_t).max() < 1e-7  # wrapped: angles are poses
    assert r.structural_error_max == pytest.approx(sem, abs=RECOMPUTE_TOL)


@given(
    crank=st.floats(0.5, 3) | st.floats(-3, -0.5),
    rod=st.floats(3.5, 8),
    offset=st.floats(-2, 2),
    start=st.floats(0, 360),
    span=st.floats(10, 200) | st.floats(-200, -10),
    points=st.integers(3, 5),
)
@settings(max_examples=40)
def test_slider_crank_pairs_anywhere_are_recovered_and_checked(crank, rod, offset, start, span, points):
    # rod > |crank| + |offset| + 0.5: the crank turns fully, no dead point anywhere
    assume(rod > abs(crank) + abs(offset) + 0.5)
    phi = np.radians(start + np.linspace(0.0, span, points))
    s = crank * np.cos(phi) + np.sqrt(rod**2 - (offset - crank * np.sin(phi)) ** 2)
    r = synthesize_function(phi, s, kind="slider-crank")
    assert r.defect == "" and r.branch == "+"
    got = [r.lengths["crank"], r.lengths["rod"], r.lengths["offset"]]
    np.testing.assert_allclose(got, [abs(crank), rod, offset], atol=1e-6 * rod)
    err_t, sem, _ = _recompute(r)
    assert np.abs(r.error).max() < 1e-7 * rod and np.abs(err_t).max() < 1e-7 * rod
    assert r.structural_error_max == pytest.approx(sem, abs=RECOMPUTE_TOL * rod)
    assert r.input_offset % np.pi == pytest.approx(0, abs=1e-8) or r.input_offset % np.pi == pytest.approx(
        np.pi
    )  # 10 digits written
