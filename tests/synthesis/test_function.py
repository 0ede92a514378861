"""Function generation: Freudenstein four-bar and slider-crank, exact recovery of known linkages, defects, refusals."""

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.loops.fourbar import fourbar
from gearlever.mechanism import Mechanism
from gearlever.synthesis.function import function_targets, precision_points, synthesize_function


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
    r = synthesize_function(t.input_angle, t.output, desired=t.desired)
    K1, K2, K3 = r.coefficients
    phi, psi = r.dense_input, r.dense_generated
    lhs = K1 * np.cos(psi) - K2 * np.cos(phi) + K3
    np.testing.assert_allclose(lhs, np.cos(phi - psi), atol=1e-12)
    d, a, b, c = (r.lengths[k] for k in ("ground", "crank", "coupler", "rocker"))
    # K from the lengths (signs: a negative K is a link pointing the other way)
    assert abs(abs(K1) - d / a) < 1e-12 and abs(abs(K2) - d / c) < 1e-12


def test_log10_three_chebyshev_points_met_exactly_and_structural_error_from_engine():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    np.testing.assert_allclose(np.degrees(t.input_angle), [49.0192378865, 75.0, 100.9807621135], atol=1e-9)
    r = synthesize_function(t.input_angle, t.output, desired=t.desired)
    assert np.abs(r.error).max() < 1e-12
    # the structural error vanishes at the precision points and is the engine's, over the range
    assert 0 < r.structural_error_max < np.radians(0.5)
    at = np.interp(t.input_angle, r.dense_input, np.abs(r.dense_generated - r.dense_desired))
    assert at.max() < 1e-3 * r.structural_error_max + 1e-6
    m = Mechanism.from_dict(r.model)
    res = m.solve(m.sketch_inputs[None, :])
    assert bool(res.closed[0])


def test_more_points_by_least_squares_do_not_meet_every_target():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]), points=7)
    r = synthesize_function(t.input_angle, t.output, desired=t.desired)
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
    inner = synthesize_function(t.input_angle, t.output, desired=t.desired)
    full = synthesize_function(t.input_angle, t.output, desired=t.desired, input_range=t.input_range)
    np.testing.assert_allclose(full.dense_input[[0, -1]], np.radians([45, 105]), rtol=1e-15)
    np.testing.assert_allclose(inner.dense_input[[0, -1]], t.input_angle[[0, -1]], rtol=1e-15)
    np.testing.assert_array_equal(full.lengths["coupler"], inner.lengths["coupler"])
    # the engine's output at the range ends, against the formula: the worst error is at x = 1
    end_err = full.dense_generated[[0, -1]] - t.desired(np.radians([45, 105]))
    assert full.structural_error_max == pytest.approx(np.abs(full.dense_generated - full.dense_desired).max())
    assert full.structural_error_max == pytest.approx(abs(end_err[0]), rel=1e-12)
    assert full.structural_error_max > 1.3 * inner.structural_error_max
    with pytest.raises(GearleverError, match="input_range"):
        synthesize_function(t.input_angle, t.output, input_range=(1.0, 1.0))
