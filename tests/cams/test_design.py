"""Disc cam design checked by independent contact computations on the profile polygon,
finite differences of the profile, and Norton's closed forms (Design of Machinery, sec. 8.6)."""

import math

import numpy as np
import pytest

from gearlever.cams import FOLLOWERS, design_cam, size_base_radius
from gearlever.errors import GearleverError
from gearlever.laws import law_from_segments

SEGS = [
    {"to": 60, "motion": "dwell"},
    {"to": 150, "motion": "cycloidal", "rise": 1},
    {"to": 200, "motion": "dwell"},
    {"to": 320, "motion": "345", "rise": -1},
    {"to": 360, "motion": "dwell"},
]


def law(output="displacement", stroke=20.0):
    segs = [dict(s, rise=s["rise"] * stroke) if "rise" in s else s for s in SEGS]
    return law_from_segments(output, "mm" if output == "displacement" else "deg", segs)


def law_s(lw, theta):
    """The law's follower displacement from its lowest value (independent of the cam code)."""
    return lw.evaluate(theta).s - np.min(lw.evaluate(np.linspace(0, 2 * math.pi, 36001)).s)


def rotate(pts, ang):
    c, s = math.cos(ang), math.sin(ang)
    return pts @ np.array([[c, s], [-s, c]])


def dist_to_polygon(pts, centre, window=None):
    """Distance from ``centre`` to the closed polygon ``pts`` (segments, not only vertices).

    With ``window``, only the segments starting within that distance of ``centre`` count.
    """
    idx = np.arange(len(pts))
    if window is not None:
        idx = idx[np.linalg.norm(pts - centre, axis=1) < window]
    a, b = pts[idx], pts[(idx + 1) % len(pts)]
    ab = b - a
    t = np.clip(np.sum((centre - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0, 1)
    return float(np.min(np.linalg.norm(a + t[:, None] * ab - centre, axis=1)))


TEST_ANGLES = np.radians(np.arange(0.5, 360, 3.0)) + 1e-3  # off the design grid


@pytest.mark.parametrize("offset", [0.0, 6.0, -4.0])
def test_translating_roller_surface_stays_one_roller_radius_from_the_roller_centre(offset):
    lw = law()
    rb, rr = 40.0, 8.0
    cam = design_cam(lw, "translating-roller", base_radius=rb, roller_radius=rr, offset=offset, points=40000)
    d = math.sqrt((rb + rr) ** 2 - offset**2)
    s = law_s(lw, TEST_ANGLES)
    err = [
        dist_to_polygon(rotate(cam.surface, th), np.array([offset, d + si])) - rr
        for th, si in zip(TEST_ANGLES, s, strict=True)
    ]
    assert np.max(np.abs(err)) < 1e-6 * 20.0


def test_translating_roller_displacement_recovered_by_a_contact_computation():
    """Rotate the profile, lift the roller along its axis until it touches: the law comes back."""
    lw = law()
    rb, rr, e = 40.0, 8.0, 5.0
    cam = design_cam(lw, "translating-roller", base_radius=rb, roller_radius=rr, offset=e, points=40000)
    d = math.sqrt((rb + rr) ** 2 - e**2)
    rec = []
    for th in TEST_ANGLES:
        pts = rotate(cam.surface, th)
        near = np.abs(pts[:, 0] - e) <= rr
        rec.append(np.max(pts[near, 1] + np.sqrt(rr**2 - (pts[near, 0] - e) ** 2)) - d)
    np.testing.assert_allclose(rec, law_s(lw, TEST_ANGLES), atol=1e-6 * 20.0)


def test_translating_flat_displacement_recovered_by_a_contact_computation():
    lw = law()
    rb = 45.0
    cam = design_cam(lw, "translating-flat", base_radius=rb, points=40000)
    rec = [np.max(rotate(cam.surface, th)[:, 1]) - rb for th in TEST_ANGLES]
    np.testing.assert_allclose(rec, law_s(lw, TEST_ANGLES), atol=1e-6 * 20.0)
    # the contact lies at x = v (Norton: flat-faced follower), within the face span reported
    np.testing.assert_allclose(cam.contact[:, 0], cam.v, atol=1e-12)
    assert cam.face_width == pytest.approx(np.max(cam.v) - np.min(cam.v))


def _bisect(f, lo, hi, n=60):
    """Vectorised bisection for f(x) = 0 with f(lo) < 0 < f(hi)."""
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        neg = f(mid) < 0
        lo, hi = np.where(neg, mid, lo), np.where(neg, hi, mid)
    return 0.5 * (lo + hi)


def test_oscillating_roller_arm_angle_recovered_by_a_contact_computation():
    lw = law("angle", stroke=20.0)
    rb, rr, L, D = 30.0, 6.0, 50.0, 70.0
    cam = design_cam(lw, "oscillating-roller", base_radius=rb, roller_radius=rr, arm=L, pivot_distance=D, points=40000)
    g0 = math.acos((D**2 + L**2 - (rb + rr) ** 2) / (2 * D * L))
    angles = TEST_ANGLES[::3]
    polys = [rotate(cam.surface, th) for th in angles]

    def gap(g):
        return np.array(
            [
                dist_to_polygon(p, np.array([D - L * math.cos(gi), L * math.sin(gi)]), window=3 * rr) - rr
                for p, gi in zip(polys, g, strict=True)
            ]
        )

    want = g0 + law_s(lw, angles)
    got = _bisect(gap, want - 0.02, want + 0.02, n=32)
    np.testing.assert_allclose(got - g0, law_s(lw, angles), atol=1e-6 * math.radians(20))


def test_oscillating_flat_face_angle_recovered_by_a_contact_computation():
    lw = law("angle", stroke=15.0)
    rb, D, e = 25.0, 80.0, 3.0
    cam = design_cam(lw, "oscillating-flat", base_radius=rb, pivot_distance=D, offset=e, points=40000)
    g0 = math.asin((rb + e) / D)
    angles = TEST_ANGLES[::3]
    polys = [rotate(cam.surface, th) for th in angles]

    def reach(g):  # how far the cam pokes through the face line turned to g (0 at contact)
        return np.array(
            [
                np.max(p @ np.array([math.sin(gi), math.cos(gi)])) - (D * math.sin(gi) - e)
                for p, gi in zip(polys, g, strict=True)
            ]
        )

    want = g0 + law_s(lw, angles)
    got = _bisect(lambda g: -reach(g), want - 0.02, want + 0.02, n=40)
    np.testing.assert_allclose(got - g0, law_s(lw, angles), atol=1e-6 * math.radians(15))


def _fd_radius(pts, h):
    x, y = pts[:, 0], pts[:, 1]
    x1, y1 = (np.roll(x, -1) - np.roll(x, 1)) / (2 * h), (np.roll(y, -1) - np.roll(y, 1)) / (2 * h)
    x2 = (np.roll(x, -1) - 2 * x + np.roll(x, 1)) / h**2
    y2 = (np.roll(y, -1) - 2 * y + np.roll(y, 1)) / h**2
    return -((x1**2 + y1**2) ** 1.5) / (x1 * y2 - y1 * x2)  # the profile runs clockwise


@pytest.mark.parametrize(
    ("follower", "kw", "output"),
    [
        ("translating-roller", {"roller_radius": 8.0, "offset": 5.0}, "displacement"),
        ("translating-flat", {}, "displacement"),
        ("oscillating-roller", {"roller_radius": 6.0, "arm": 50.0, "pivot_distance": 70.0}, "angle"),
        ("oscillating-flat", {"pivot_distance": 80.0, "offset": 3.0}, "angle"),
    ],
)
def test_radius_of_curvature_matches_finite_differences_of_the_profile(follower, kw, output):
    cam = design_cam(law(output, 15.0), follower, base_radius=35.0, points=36000, **kw)
    fd = _fd_radius(cam.surface, 2 * math.pi / 36000)
    breaks = np.radians([0, 60, 150, 200, 320, 360])  # jerk jumps there: FD second differences are O(h) off
    ok = (np.abs(cam.curvature_radius) < 1e3) & (np.min(np.abs(cam.theta[:, None] - breaks), axis=1) > 1e-3)
    np.testing.assert_allclose(fd[ok], cam.curvature_radius[ok], rtol=1e-4, atol=1e-6)


def test_translating_roller_pressure_angle_and_flat_radius_match_nortons_closed_forms():
    lw = law()
    rb, rr, e = 30.0, 5.0, 4.0
    cam = design_cam(lw, "translating-roller", base_radius=rb, roller_radius=rr, offset=e)
    want = np.arctan((cam.v - e) / (cam.s + math.sqrt((rb + rr) ** 2 - e**2)))
    np.testing.assert_allclose(cam.pressure_angle, want, atol=1e-13)
    flat = design_cam(lw, "translating-flat", base_radius=rb + 10)
    np.testing.assert_allclose(flat.curvature_radius, rb + 10 + flat.s + flat.a, rtol=1e-12)
    np.testing.assert_allclose(flat.pressure_angle, 0.0, atol=1e-15)


def test_profile_starts_on_the_base_circle_during_the_first_dwell():
    cam = design_cam(law(), "translating-roller", base_radius=30.0, roller_radius=5.0)
    dwell = cam.theta < math.radians(60)
    np.testing.assert_allclose(np.hypot(*cam.surface[dwell].T), 30.0, atol=1e-12)
    np.testing.assert_allclose(np.hypot(*cam.pitch[dwell].T), 35.0, atol=1e-12)


def test_size_base_radius_for_a_pressure_angle_is_the_smallest_meeting_it():
    lw = law()
    bound = math.radians(30)
    rb = size_base_radius(lw, "translating-roller", roller_radius=5.0, offset=2.0, max_pressure_angle=bound)
    at = design_cam(lw, "translating-roller", base_radius=rb, roller_radius=5.0, offset=2.0, points=3600)
    below = design_cam(lw, "translating-roller", base_radius=rb * (1 - 1e-6), roller_radius=5.0, offset=2.0)
    assert at.pressure_angle_max <= bound < below.pressure_angle_max


def test_size_base_radius_for_a_curvature_radius_flat_follower_is_closed_form():
    lw = law()
    rb = size_base_radius(lw, "translating-flat", min_curvature_radius=10.0)
    cam = design_cam(lw, "translating-flat", base_radius=50.0)
    assert rb == pytest.approx(10.0 - np.min(cam.s + cam.a), rel=1e-9)  # Norton: rho = Rb + s + s''


def test_undercut_roller_is_refused_with_the_smallest_base_radius_that_avoids_it():
    lw = law_from_segments(
        "displacement", "mm", [{"to": 60, "motion": "345", "rise": 30}, {"to": 360, "motion": "cycloidal", "rise": -30}]
    )
    with pytest.raises(
        GearleverError, match="undercut: roller radius 20 exceeds .* smallest base radius that avoids it is ([0-9.]+)"
    ) as exc:
        design_cam(lw, "translating-roller", base_radius=5.0, roller_radius=20.0)
    least = float(str(exc.value).rsplit(" ", 1)[1])
    ok = design_cam(lw, "translating-roller", base_radius=least * 1.001, roller_radius=20.0)
    assert not ok.undercut and ok.curvature_radius_min > 0
    flagged = design_cam(lw, "translating-roller", base_radius=5.0, roller_radius=20.0, allow_undercut=True)
    assert flagged.undercut and flagged.curvature_radius_min < 0


def test_undercut_flat_follower_is_refused():
    lw = law_from_segments(
        "displacement", "mm", [{"to": 60, "motion": "345", "rise": 30}, {"to": 360, "motion": "cycloidal", "rise": -30}]
    )
    with pytest.raises(GearleverError, match="undercut: the cam's radius of curvature .* smallest base radius"):
        design_cam(lw, "translating-flat", base_radius=20.0)


@pytest.mark.parametrize(
    ("lw", "follower", "kw", "match"),
    [
        (
            law_from_segments("angle", "deg", [{"to": 360, "motion": "linear", "rise": 30}]),
            "oscillating-flat",
            {"pivot_distance": 50},
            "does not return to its start",
        ),
        (law(), "oscillating-roller", {"roller_radius": 5, "arm": 40, "pivot_distance": 60}, "needs an angle law"),
        (law("angle"), "translating-roller", {"roller_radius": 5}, "needs a displacement law"),
        (law(), "translating-roler", {"roller_radius": 5}, "did you mean 'translating-roller'"),
        (law(), "translating-roller", {"roller_radius": 5, "offset": 50}, "--offset 50 must be smaller"),
        (law(), "translating-roller", {}, "--roller-radius must be a positive length"),
        (law("angle"), "oscillating-roller", {"roller_radius": 5, "arm": 10, "pivot_distance": 100}, "cannot reach"),
        (law("angle"), "oscillating-roller", {"roller_radius": 5, "pivot_distance": 100}, "--arm must be"),
    ],
)
def test_bad_designs_are_refused_naming_the_problem(lw, follower, kw, match):
    with pytest.raises(GearleverError, match=match):
        design_cam(lw, follower, base_radius=30.0, **kw)


def test_every_registered_follower_designs_a_cam_and_a_frame():
    for name, kind in FOLLOWERS.items():
        kw = {"roller_radius": 5.0} if kind.contact == "roller" else {}
        if kind.law_output == "angle":
            kw.update(pivot_distance=90.0, **({"arm": 60.0} if kind.contact == "roller" else {}))
        cam = design_cam(law(kind.law_output, 10.0), name, base_radius=30.0, points=720, **kw)
        assert cam.to_frame().shape[0] == 720 and cam.summary()["follower"] == name


def test_a_rise_narrower_than_four_profile_steps_is_refused_naming_the_segment():
    lw = law_from_segments(
        "displacement", "mm", [{"to": 0.2, "motion": "cycloidal", "rise": 5}, {"to": 360, "motion": "345", "rise": -5}]
    )
    with pytest.raises(GearleverError, match="segment 1 spans 0.2 deg, less than 4 profile steps"):
        design_cam(lw, "translating-flat", base_radius=30.0, points=3600)
    assert design_cam(lw, "translating-flat", base_radius=300.0, points=72000, allow_undercut=True).theta.size == 72000


@pytest.mark.parametrize("e", [0.0, 3.0, -4.0])
def test_oscillating_flat_pressure_angle_is_the_face_offset_seen_from_the_contact(e):
    """The contact point moves at right angles to the line from the pivot and pushes along the face's normal,
    so the pressure angle is the angle between that line and the face: atan(|e| / l), l the distance along the
    face from the foot of the pivot's perpendicular to the contact (zero for a face through the pivot;
    Uicker, Pennock and Shigley, *Theory of Machines and Mechanisms*, ch. 6).  The contact is found here as the
    cam vertex farthest along the face's normal, independently of the design's own contact points."""
    lw = law("angle", stroke=15.0)
    rb, D = 25.0, 80.0
    cam = design_cam(lw, "oscillating-flat", base_radius=rb, pivot_distance=D, offset=e, points=7200)
    phi = cam.pressure_angle
    assert np.all(np.abs(phi) < math.pi / 2)
    g = math.asin((rb + e) / D) + cam.s
    idx = np.arange(0, cam.theta.size, 90)
    ell = []
    for k in idx:
        n = np.array([math.sin(g[k]), math.cos(g[k])])
        c = rotate(cam.surface, cam.theta[k])
        contact = c[np.argmax(c @ n)]
        r = contact - np.array([D, 0.0])
        ell.append(abs(r @ np.array([n[1], -n[0]])))
    want = np.arctan2(abs(e), np.array(ell))
    np.testing.assert_allclose(np.abs(phi[idx]), want, atol=2e-3)
    assert cam.pressure_angle_max == pytest.approx(np.abs(phi).max())


# --- an oscillating roller's pivot, the arm's shaft, must lie outside the disc the turning cam sweeps (issue 33 §5)


def _shipped(name):
    from gearlever.data import example_path
    from gearlever.laws import load_law

    return load_law(example_path(f"{name}.toml"))


ROCK45 = _shipped("law_dwell_rocker")  # a 120 deg dwell, a 45 deg cycloidal rise, a 3-4-5 return


@pytest.mark.parametrize(
    "rb, rr, L, D", [(30.0, 6.0, 50.0, 70.0), (40.0, 8.0, 60.0, 90.0), (119.0, 20.0, 100.0, 200.0)]
)
def test_oscillating_roller_largest_cam_radius_is_the_farthest_roller_centre_less_the_roller(rb, rr, L, D):
    """cam_radius_max (law of cosines at the arm's farthest swing) against the designed surface's sampled radius."""
    from gearlever.cams.followers import FollowerParams
    from gearlever.cams.followers.oscillating_roller import cam_radius_max

    cam = design_cam(
        ROCK45, "oscillating-roller", base_radius=rb, roller_radius=rr, arm=L, pivot_distance=D, points=36000
    )
    r_max = cam_radius_max(FollowerParams(rr, 0.0, L, D), rb, cam.stroke)
    assert float(np.max(np.hypot(*cam.surface.T))) == pytest.approx(r_max, rel=1e-7)
    assert D > r_max  # these layouts are buildable


def test_an_oscillating_roller_whose_pivot_lies_inside_the_cam_is_refused_naming_pivot_distance():
    """Before: pivot distance 30 with arm 40 was accepted (pressure angle 83.6 deg), the cam cutting the pivot."""
    kw = {"roller_radius": 5.0, "arm": 40.0, "base_radius": 30.0}
    with pytest.raises(GearleverError, match=r"^pivot_distance 30: the follower's pivot lies inside the cam") as exc:
        design_cam(ROCK45, "oscillating-roller", pivot_distance=30.0, **kw)
    text = str(exc.value)
    assert "--" not in text and "arm 40" in text
    # the pivot distance it names clears the cam, just below it does not
    least = float(text.split("a pivot_distance above ")[1].split()[0])
    design_cam(ROCK45, "oscillating-roller", pivot_distance=least * (1 + 1e-5), **kw)
    with pytest.raises(GearleverError, match="pivot lies inside the cam"):
        design_cam(ROCK45, "oscillating-roller", pivot_distance=least * (1 - 1e-3), **kw)


def test_sizing_an_oscillating_roller_returns_only_layouts_whose_pivot_clears_the_cam():
    from gearlever.cams.followers import FollowerParams
    from gearlever.cams.followers.oscillating_roller import cam_radius_max

    dims = {"roller_radius": 20.0, "arm": 100.0, "pivot_distance": 200.0}
    rb = size_base_radius(ROCK45, "oscillating-roller", max_pressure_angle=math.radians(30), **dims)
    cam = design_cam(ROCK45, "oscillating-roller", base_radius=rb, **dims)
    assert cam.pressure_angle_max <= math.radians(30) * (1 + 1e-9)
    assert dims["pivot_distance"] > cam_radius_max(FollowerParams(**dims), rb, cam.stroke)
    # with a roller of 10 the 30 deg is met only at base radii whose cam reaches the pivot: refused, saying why
    dims["roller_radius"] = 10.0
    with pytest.raises(GearleverError, match=r"smallest pressure angle reached is 3\d.*\(above it the cam reaches"):
        size_base_radius(ROCK45, "oscillating-roller", max_pressure_angle=math.radians(30), **dims)
    # a stroke swinging the arm out so far that no base radius keeps the pivot outside
    wide = law_from_segments(
        "angle",
        "deg",
        [{"to": 180, "motion": "cycloidal", "rise": 120}, {"to": 360, "motion": "cycloidal", "rise": -120}],
    )
    with pytest.raises(GearleverError, match=r"no base radius keeps the follower's pivot outside the cam"):
        size_base_radius(wide, "oscillating-roller", min_curvature_radius=0.0, **dims)


def test_the_law_synthesis_reference_cam_is_buildable_for_every_shipped_law():
    """cam_comparison's layout: the pivot outside the cam, the pressure angle it is sized for, no undercut."""
    from gearlever.data import example_path
    from gearlever.laws import load_law
    from gearlever.synthesis.law.measure import CAM_PRESSURE_ANGLE_DEG, cam_comparison

    names = sorted(p.stem for p in example_path("fourbar.toml").parent.glob("law_*.toml"))
    assert {"law_dwell_rocker", "law_lift", "law_quick_return"} <= set(names)
    angle_laws = 0
    for name in names:
        lw = load_law(example_path(f"{name}.toml"))
        c = cam_comparison(lw)
        assert c["available"], (name, c["note"])
        assert c["pressure_angle_max_deg"] == pytest.approx(CAM_PRESSURE_ANGLE_DEG, abs=1e-6) and not c["undercut"]
        kw = {k: c[k] for k in ("roller_radius", "arm", "pivot_distance") if k in c}
        design_cam(lw, c["follower"], base_radius=c["base_radius"], **kw)  # designs again without refusal
        if lw.output == "angle":
            angle_laws += 1
            assert c["pivot_distance"] > c["cam_radius_max"] and c["pivot_clearance"] > 0
    assert angle_laws >= 1
