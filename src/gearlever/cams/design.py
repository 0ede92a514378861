"""Disc cam design for a motion law: profile, pressure angle, curvature, undercut, sizing.

:func:`design_cam` turns a :class:`~gearlever.laws.MotionLaw` and a follower
kind of :data:`~gearlever.cams.followers.FOLLOWERS` into a :class:`CamDesign`,
batched over the input angles; :func:`size_base_radius` finds the smallest
base radius meeting a maximum pressure angle or a minimum radius of curvature.

Frames and conventions: the cam turns counterclockwise by the input angle
theta; the follower is fixed in space (its displacement s is the law's output
measured from its lowest value, so the follower touches the base circle
there).  The cam's frame coincides with the fixed frame at theta = 0, and a
point x of the fixed frame at input theta is R(-theta) x in the cam's frame.

Roller followers (the centre's path q(s) given by the kind): the pitch curve
P(theta) = R(-theta) q(s(theta)) has, in the fixed frame, tangent w = q' - J q
and second derivative -J w + q'' - J q' (J the quarter turn, ' = d/dtheta);
its outward normal n = J w / norm(w), the cam surface is P - Rr n, the pressure
angle is the angle between n and the roller centre's direction of travel, and
the pitch curve's radius of curvature is rho_p = -norm(w)**3 / (w x P'') (the
curve runs clockwise); the cam surface's is rho_p - Rr, undercut where a
convex rho_p < Rr.  For the translating roller these are R. L. Norton,
*Design of Machinery*, eq. for the pressure angle phi = arctan((v - e) / (s +
sqrt(Rp**2 - e**2))) and the parametric radius of curvature of sec. 8.6.

Flat followers (the face line n_f . x = h with n_f at angle beta, given by
the kind): the cam surface is the envelope of the face lines in the cam's
frame; with alpha = beta - theta its support function is h(alpha), the
contact p = h n + (dh/dalpha) J n and the radius of curvature rho = h +
d2h/dalpha2 (for the translating flat follower rho = Rb + s + s'', Norton,
sec. 8.6).

Imports numpy, the standard library, gearlever.laws, gearlever.errors,
gearlever._result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.cams.followers import FOLLOWERS, FollowerParams
from gearlever.cams.followers._base import Unbuildable, need
from gearlever.errors import GearleverError, a
from gearlever.laws import MotionLaw

__all__ = ["CamDesign", "design_cam", "size_base_radius"]

#: Most profile points of one design.
MAX_POINTS = 2_000_000
#: Points used by the base-radius search.
SEARCH_POINTS = 3600
#: Most points of the search that suggests the smallest workable base radius in a refusal.
SUGGEST_POINTS = 36_000


def _J(x: np.ndarray) -> np.ndarray:
    """Quarter turn counterclockwise of (N, 2) vectors."""
    return np.stack([-x[:, 1], x[:, 0]], axis=-1)


def _rot(x: np.ndarray, ang: np.ndarray) -> np.ndarray:
    """Rotate (N, 2) vectors by the angles ang (rad, counterclockwise)."""
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([c * x[:, 0] - s * x[:, 1], s * x[:, 0] + c * x[:, 1]], axis=-1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


@dataclass(frozen=True)
class CamDesign(Result):
    """A disc cam designed for a law and a follower, sampled over one turn.

    Attributes
    ----------
    theta : ndarray
        Input (cam) angles, rad, 0 .. 2 pi (end excluded).
    s, v, a : ndarray
        Follower displacement from its lowest position and its derivatives per
        radian of cam angle (rad for oscillating followers, lengths otherwise).
    pitch : ndarray, shape (N, 2)
        Pitch curve (roller centre) in the cam's frame; NaN for flat followers.
    surface : ndarray, shape (N, 2)
        Cam surface (the contact point) in the cam's frame.
    contact : ndarray, shape (N, 2)
        The contact point in the fixed frame.
    pressure_angle : ndarray
        Angle (rad) between the contact normal and the follower's direction of travel.
    curvature_radius : ndarray
        Radius of curvature of the cam surface at the contact (> 0 convex,
        < 0 concave).
    follower : str
        Follower kind name.
    base_radius, roller_radius, offset, arm, pivot_distance : float
        Dimensions (NaN where the kind has none).
    stroke : float
        Follower's total travel.
    pressure_angle_max : float
        The largest absolute pressure angle (rad).
    curvature_radius_min : float
        Smallest radius of curvature of the convex cam surface (negative when undercut).
    undercut : bool
        True where the surface would cusp or loop (roller: convex pitch radius
        < roller radius; flat: rho <= 0).
    face_width : float
        Flat followers: the span of the contact along the face (the least face length); NaN for rollers.
    face_contact_min, face_contact_max : float
        Flat followers: the contact's extreme positions along the face
        (from the follower axis, or from the pivot's foot); NaN for rollers.
    units : str
        Length units of the dimensions.

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> cam = design_cam(law, "translating-roller", base_radius=30.0, roller_radius=5.0)
    >>> round(math.degrees(cam.pressure_angle_max), 2), cam.undercut
    (9.1, False)
    """

    theta: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    pitch: np.ndarray
    surface: np.ndarray
    contact: np.ndarray
    pressure_angle: np.ndarray
    curvature_radius: np.ndarray
    follower: str
    base_radius: float
    roller_radius: float
    offset: float
    arm: float
    pivot_distance: float
    stroke: float
    pressure_angle_max: float
    curvature_radius_min: float
    undercut: bool
    face_width: float
    face_contact_min: float
    face_contact_max: float
    units: str = "mm"

    def _frame_columns(self) -> dict:
        u = self.units
        su = "rad" if FOLLOWERS[self.follower].law_output == "angle" else u
        return {
            "theta_rad": self.theta,
            f"s_{su}": self.s,
            f"v_{su}_per_rad": self.v,
            f"a_{su}_per_rad2": self.a,
            f"pitch_x_{u}": self.pitch[:, 0],
            f"pitch_y_{u}": self.pitch[:, 1],
            f"surface_x_{u}": self.surface[:, 0],
            f"surface_y_{u}": self.surface[:, 1],
            "pressure_angle_rad": self.pressure_angle,
            f"curvature_radius_{u}": self.curvature_radius,
        }

    def summary(self) -> dict:
        """The scalar results, degrees in keys ending ``_deg`` (the CLI's report); strict JSON (NaN as None)."""
        i_phi = int(np.argmax(np.abs(self.pressure_angle)))
        rho = self.curvature_radius
        convex = rho > 0
        i_rho = int(np.argmin(np.where(convex, rho, np.inf))) if np.any(convex) else int(np.argmin(rho))
        out = {
            "follower": self.follower,
            "units": self.units,
            "base_radius": self.base_radius,
            "roller_radius": self.roller_radius,
            "offset": self.offset,
            "arm": self.arm,
            "pivot_distance": self.pivot_distance,
            "stroke": self.stroke if FOLLOWERS[self.follower].law_output != "angle" else math.degrees(self.stroke),
            "stroke_units": "deg" if FOLLOWERS[self.follower].law_output == "angle" else self.units,
            "pressure_angle_max_deg": math.degrees(self.pressure_angle_max),
            "pressure_angle_max_at_deg": math.degrees(self.theta[i_phi]),
            "curvature_radius_min": self.curvature_radius_min,
            "curvature_radius_min_at_deg": math.degrees(self.theta[i_rho]),
            "undercut": self.undercut,
            "face_width": self.face_width,
            "face_contact_min": self.face_contact_min,
            "face_contact_max": self.face_contact_max,
            "points": int(self.theta.size),
        }
        return {k: None if isinstance(v, float) and not math.isfinite(v) else v for k, v in out.items()}


def _kind(follower: str):
    if follower not in FOLLOWERS:
        import difflib

        close = difflib.get_close_matches(str(follower), list(FOLLOWERS), n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise GearleverError(f"follower {follower!r} is not known{hint}; known: {', '.join(FOLLOWERS)}")
    return FOLLOWERS[follower]


def _check_law(law: MotionLaw, kind) -> None:
    if not isinstance(law, MotionLaw):
        raise GearleverError(f"law must be a MotionLaw, got {type(law).__name__}")
    if law.output != kind.law_output:
        need = (
            'an angle law (output = "angle")'
            if kind.law_output == "angle"
            else ('a displacement law (output = "displacement")')
        )
        raise GearleverError(f"{law.source}: {a(kind.name)} follower needs {need}, got output = {law.output!r}")
    net = law.net_change()
    if net != 0.0:
        shown = f"{math.degrees(net):g} deg" if law.output == "angle" else f"{net:g} {law.units}"
        raise GearleverError(
            f"{law.source}: the output does not return to its start over a cycle (net change {shown}); "
            "a cam needs a law whose rises and returns add up to zero"
        )


def _law_min(law: MotionLaw) -> float:
    """Lowest output over the turn (exact at segment ends for segment laws, dense for samples)."""
    if law.knots is None:
        return float(law.start + min(0.0, np.min(np.cumsum(law.rises))))
    return float(np.min(law.evaluate(np.linspace(0.0, 2 * math.pi, 36001)).s))


def _core(kind, p: FollowerParams, base_radius: float, theta, s, v, a):
    """Everything of a design at given base radius: arrays in the fixed and cam frames."""
    n = theta.size
    if kind.contact == "roller":
        q, dq, d2q = kind.path(s, p, base_radius)
        q1 = dq * v[:, None]
        q2 = d2q * (v * v)[:, None] + dq * a[:, None]
        w = q1 - _J(q)
        P2 = -_J(w) + q2 - _J(q1)
        wn = np.linalg.norm(w, axis=-1)
        normal = _J(w) / wn[:, None]
        travel = dq / np.linalg.norm(dq, axis=-1, keepdims=True)
        phi = np.arctan2(_cross(travel, normal), np.sum(travel * normal, axis=-1))
        with np.errstate(divide="ignore"):
            rho_p = -(wn**3) / _cross(w, P2)
        contact = q - p.roller_radius * normal
        pitch = _rot(q, -theta)
        surface = _rot(contact, -theta)
        rho = np.where(rho_p > 0, rho_p - p.roller_radius, rho_p - p.roller_radius)
        folded = np.sum(normal * q, axis=-1) <= 0
        undercut_mask = (rho_p > 0) & (rho_p <= p.roller_radius)
        face = (math.nan, math.nan, math.nan)
    else:
        beta, b1, b2, h, h1, h2 = kind.face(s, p, base_radius)
        beta = np.broadcast_to(beta, s.shape)
        be1, be2 = b1 * v, b2 * v * v + b1 * a
        hh1, hh2 = h1 * v, h2 * v * v + h1 * a
        al1 = be1 - 1.0
        nf = np.stack([np.cos(beta), np.sin(beta)], axis=-1)
        nf[np.abs(nf) < 1e-15] = 0.0  # cos(pi/2) is 6e-17, not 0: keep a square face's pressure angle exactly 0
        with np.errstate(divide="ignore", invalid="ignore"):
            dh = hh1 / al1
            rho = h + (hh2 * al1 - hh1 * be2) / al1**3
        contact = h[:, None] * nf + dh[:, None] * _J(nf)
        pitch = np.full((n, 2), math.nan)
        surface = _rot(contact, -theta)
        u = kind.velocity_direction(contact, p)
        phi = np.arctan2(_cross(u, nf), np.sum(u * nf, axis=-1))
        # the angle between the line of the contact force and the path of the contact point: the face's
        # normal may point either way along that line (an oscillating face's normal points against its
        # motion), so the angle is folded into (-90, 90] deg
        phi = np.where(phi > np.pi / 2, phi - np.pi, np.where(phi <= -np.pi / 2, phi + np.pi, phi))
        folded = (al1 >= 0) | (h <= 0)
        undercut_mask = rho <= 0
        pos = kind.face_position(contact, beta, p)
        face = (float(pos.max() - pos.min()), float(pos.min()), float(pos.max()))
    return {
        "pitch": pitch,
        "surface": surface,
        "contact": contact,
        "phi": phi,
        "rho": rho,
        "folded": folded,
        "undercut": undercut_mask,
        "face": face,
    }


def _prepare(law, follower, p, points):
    kind = _kind(follower)
    _check_law(law, kind)
    if isinstance(points, bool) or not isinstance(points, int | np.integer) or not 8 <= points <= MAX_POINTS:
        raise GearleverError(f"points must be an integer in 8 .. {MAX_POINTS:,}, got {points!r}")
    theta = np.linspace(0.0, 2 * math.pi, int(points), endpoint=False)
    step = 2 * math.pi / int(points)
    widths = np.diff(law.breaks)
    for k, name in enumerate(law.motions):
        if name != "dwell" and law.rises[k] != 0 and widths[k] < 4 * step:
            raise GearleverError(
                f"{law.source}: segment {k + 1} spans {math.degrees(widths[k]):.6g} deg, less than 4 profile steps "
                f"of {math.degrees(step):.6g} deg: give more points (or widen the segment)"
            )
    vals = law.evaluate(theta)
    s = vals.s - _law_min(law)
    return kind, theta, s, vals.v, vals.a


def _params(roller_radius, offset, arm, pivot_distance) -> FollowerParams:
    def num(name, x, allow_none=False):
        if x is None and allow_none:
            return None
        if isinstance(x, bool) or not isinstance(x, int | float | np.floating | np.integer) or not math.isfinite(x):
            raise GearleverError(f"{name} must be a finite number, got {x!r}")
        return float(x)

    rr = num("roller_radius", roller_radius)
    if rr < 0:
        raise GearleverError(f"roller_radius must be >= 0, got {rr!r}")
    return FollowerParams(rr, num("offset", offset), num("arm", arm, True), num("pivot_distance", pivot_distance, True))


_FLAGS = {"roller_radius": "--roller-radius", "arm": "--arm", "pivot_distance": "--pivot-distance"}


def _check_needs(kind, p: FollowerParams) -> None:
    """Refuse missing or non-positive dimensions the kind needs (the offset may be any number)."""
    for name in kind.needs:
        if name in _FLAGS:
            need(p, name, _FLAGS[name], kind.name)


def _assess(kind, p, base_radius, theta, s, v, a, stroke, strict: bool = False):
    """(why, arrays): why ``base_radius`` cannot carry the stroke (None when it can), and the design arrays.

    ``strict``: a layout that cannot be built (:class:`Unbuildable`) is raised, not returned as a why.
    """
    if not math.isfinite(base_radius) or base_radius <= 0:
        return f"base radius must be a positive finite length, got {base_radius!r}", None
    try:
        kind.check(p, base_radius, stroke)
    except Unbuildable:
        if strict:
            raise
        return "the follower's pivot lies inside the cam", None
    except GearleverError as exc:
        return str(exc), None
    with np.errstate(invalid="ignore", divide="ignore"):
        r = _core(kind, p, base_radius, theta, s, v, a)
    if np.any(r["folded"]):
        k = int(np.argmax(r["folded"]))
        return f"the cam profile folds back on itself at {math.degrees(theta[k]):.4g} deg", r
    return None, r


def _search(pred, lo: float, hi: float, what: str) -> float:
    """Smallest x in (lo, hi) where pred(x) holds, assuming it holds on [x*, x_top): grid scan then bisection.

    The scan is geometric from ``lo`` (fine near the smallest radii); when it finds nothing, a second scan
    fine near ``hi`` looks for a window just below the upper bound (an oscillating roller's pressure angle
    falls as the base radius grows towards the one at which the cam reaches the pivot).
    """
    span = hi - lo
    unit = np.geomspace(1e-9, 1.0, 91)
    for grid in (lo + span * unit, (hi - span * unit)[::-1]):
        prev = lo
        for x in grid:
            if pred(float(x)):
                break
            prev = float(x)
        else:
            continue
        break
    else:
        raise GearleverError(f"no base radius up to {hi:g} meets {what}")
    a, b = prev, float(x)
    for _ in range(200):
        m = 0.5 * (a + b)
        if m in (a, b) or (b - a) <= 1e-12 * max(1.0, b):
            break
        if pred(m):
            b = m
        else:
            a = m
    return b


def size_base_radius(
    law: MotionLaw,
    follower: str,
    *,
    roller_radius: float = 0.0,
    offset: float = 0.0,
    arm: float | None = None,
    pivot_distance: float | None = None,
    max_pressure_angle: float | None = None,
    min_curvature_radius: float | None = None,
    points: int = SEARCH_POINTS,
) -> float:
    """The smallest base radius meeting a maximum pressure angle and/or a minimum radius of curvature.

    Parameters
    ----------
    law : MotionLaw
        A law returning to its start.
    follower : str
        A name of :data:`~gearlever.cams.followers.FOLLOWERS`.
    roller_radius, offset, arm, pivot_distance : float
        Follower dimensions (see :class:`~gearlever.cams.followers.FollowerParams`).
    max_pressure_angle : float, optional
        Bound on the absolute pressure angle (rad).
    min_curvature_radius : float, optional
        Bound on the convex cam surface's radius of curvature (0 asks only for no undercut).

    Returns
    -------
    float
        The base radius (to 1e-12 relative), found by a geometric grid scan
        from the smallest radius the follower can assemble with, then bisection.

    Notes
    -----
    Larger base circles lower the pressure angle and raise the radius of
    curvature (R. L. Norton, *Design of Machinery*, sec. 8.6 "Sizing the
    cam"); the search returns the first radius of the scan meeting the bounds
    and also free of folding and of undercut.  Evaluated at ``points`` equally spaced angles.

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> rb = size_base_radius(law, "translating-roller", roller_radius=5, max_pressure_angle=math.radians(30))
    >>> round(rb, 3)  # max of arctan(v / (Rb + 5 + s)) is 30 deg
    1.921
    """
    p = _params(roller_radius, offset, arm, pivot_distance)
    kind, theta, s, v, a = _prepare(law, follower, p, points)
    _check_needs(kind, p)
    if max_pressure_angle is None and min_curvature_radius is None:
        raise GearleverError("give max_pressure_angle or min_curvature_radius to size the base radius")
    stroke = float(s.max() - s.min())
    if max_pressure_angle is not None and not 0 < max_pressure_angle < math.pi / 2:
        raise GearleverError(f"max_pressure_angle must lie in (0, 90) deg, got {math.degrees(max_pressure_angle):g}")
    if min_curvature_radius is not None and not (math.isfinite(min_curvature_radius) and min_curvature_radius >= 0):
        raise GearleverError(f"min_curvature_radius must be a non-negative length, got {min_curvature_radius!r}")

    def ok(rb):
        why, r = _assess(kind, p, rb, theta, s, v, a, stroke)
        if why is not None:
            return False
        if np.any(r["undercut"]):  # a radius meeting the bounds but undercut cannot be made
            return False
        if max_pressure_angle is not None and np.max(np.abs(r["phi"])) > max_pressure_angle:
            return False
        if min_curvature_radius is not None:
            rho = r["rho"]
            if np.any((rho > 0) & (rho < min_curvature_radius)):
                return False
        return True

    lo, hi = kind.base_radius_bounds(p, stroke)
    what = []
    if max_pressure_angle is not None:
        what.append(f"a maximum pressure angle of {math.degrees(max_pressure_angle):g} deg")
    if min_curvature_radius is not None:
        what.append(f"a minimum radius of curvature of {min_curvature_radius:g}")
    wanted = " and ".join(what) + f" with the {kind.name} follower"
    try:
        return _search(ok, lo, hi, wanted)
    except GearleverError:
        raise GearleverError(
            _no_radius(kind, p, lo, hi, wanted, (max_pressure_angle, min_curvature_radius), (theta, s, v, a, stroke))
        ) from None


def _no_radius(kind, p, lo: float, hi: float, wanted: str, bounds, arrays) -> str:
    """Why sizing found no radius in ``(lo, hi)``: what the radii that assemble reach, and the flags bounding them."""
    theta, s, v, a, stroke = arrays
    max_phi, min_rho = bounds
    built, undercut, phi, rho = [], [], [], []
    first_why = None
    for rb in lo + (hi - lo) * np.geomspace(1e-6, 1 - 1e-6, 61):
        why, r = _assess(kind, p, float(rb), theta, s, v, a, stroke)
        if why is not None:
            first_why = first_why or why
            continue
        built.append(float(rb))
        undercut.append(bool(np.any(r["undercut"])))
        phi.append(float(np.max(np.abs(r["phi"]))))
        convex = r["rho"][r["rho"] > 0]
        rho.append(float(np.min(convex)) if convex.size else 0.0)
    text = f"no base radius up to {hi:.6g} meets {wanted}: "
    if not built:
        text += first_why or "no base radius assembles"
        text += " (an undercut profile)" if "folds back" in text else ""
    elif all(undercut):
        text += f"every base radius it assembles with ({built[0]:.4g} to {built[-1]:.4g}) undercuts the profile"
    elif max_phi is not None and min(phi) > max_phi:
        k = int(np.argmin(phi))
        text += f"the smallest pressure angle reached is {math.degrees(phi[k]):.4g} deg (base radius {built[k]:.4g})"
    else:
        k = int(np.argmax(rho))
        text += f"the largest radius of curvature reached is {rho[k]:.4g} (base radius {built[k]:.4g}), or it undercuts"
    if kind.bounded_by and "--" not in text:
        flags = " and ".join(f"--{n.replace('_', '-')} {getattr(p, n):g}" for n in kind.bounded_by)
        larger = kind.bounded_by[0].replace("_", "-")
        text += (
            f"; the base radius must stay below {hi:.6g}{kind.bound_note(p, stroke, hi)}, set by {flags}: "
            f"give a larger --{larger}"
        )
    return text


def design_cam(
    law: MotionLaw,
    follower: str,
    *,
    base_radius: float,
    roller_radius: float = 0.0,
    offset: float = 0.0,
    arm: float | None = None,
    pivot_distance: float | None = None,
    points: int = 3600,
    allow_undercut: bool = False,
) -> CamDesign:
    """Design the disc cam giving ``law`` to a ``follower``, at ``points`` cam angles.

    Parameters
    ----------
    law : MotionLaw
        Displacement law for translating followers, angle law for oscillating
        ones; it must return to its start over the turn.
    follower : str
        ``translating-roller``, ``translating-flat``, ``oscillating-roller``, ``oscillating-flat``.
    base_radius : float
        Radius of the base circle (the cam's smallest radius, touched at the law's lowest output).
    roller_radius, offset, arm, pivot_distance : float
        Follower dimensions as the kind needs them.
    points : int
        Equally spaced cam angles over one turn.
    allow_undercut : bool
        Return an undercut design (flagged) instead of refusing it.

    Raises
    ------
    GearleverError
        A law not returning to its start or of the wrong output for the
        follower; dimensions that cannot assemble; a base radius too small
        for the stroke (the profile folds back), or an undercut (unless
        allowed): the message gives the smallest base radius that avoids it.

    Notes
    -----
    Closed forms per point, no iteration: see the module docstring for the
    equations (R. L. Norton, *Design of Machinery*, sec. 8.6).

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 90, "motion": "dwell"},
    ...     {"to": 180, "motion": "345", "rise": 8}, {"to": 360, "motion": "cycloidal", "rise": -8}])
    >>> cam = design_cam(law, "translating-flat", base_radius=25.0)
    >>> round(cam.curvature_radius_min, 3), round(cam.face_width, 3)
    (13.709, 14.642)
    """
    p = _params(roller_radius, offset, arm, pivot_distance)
    kind, theta, s, v, a = _prepare(law, follower, p, points)
    _check_needs(kind, p)
    rb = base_radius
    if isinstance(rb, bool) or not isinstance(rb, int | float | np.floating | np.integer):
        raise GearleverError(f"base_radius must be a positive finite length, got {rb!r}")
    rb = float(rb)
    stroke = float(s.max() - s.min())
    why, r = _assess(kind, p, rb, theta, s, v, a, stroke, strict=True)
    if why is not None:
        if rb > 0 and math.isfinite(rb):
            try:
                least = size_base_radius(
                    law,
                    follower,
                    roller_radius=p.roller_radius,
                    offset=p.offset,
                    arm=p.arm,
                    pivot_distance=p.pivot_distance,
                    min_curvature_radius=0.0,
                    points=min(int(points), SUGGEST_POINTS),
                )
                why += f"; the smallest base radius without it is {least:.6g}"
            except GearleverError:
                pass
        shown = f"{math.degrees(stroke):g} deg" if kind.law_output == "angle" else f"{stroke:g}"
        raise GearleverError(f"base radius {rb:g} too small for the stroke {shown}: {why}")
    rho = r["rho"]
    undercut = bool(np.any(r["undercut"]))
    if undercut and not allow_undercut:
        k = int(np.argmax(r["undercut"]))
        least = size_base_radius(
            law,
            follower,
            roller_radius=p.roller_radius,
            offset=p.offset,
            arm=p.arm,
            pivot_distance=p.pivot_distance,
            min_curvature_radius=0.0,
            points=min(int(points), SUGGEST_POINTS),
        )
        if kind.contact == "roller":
            detail = (
                f"roller radius {p.roller_radius:g} exceeds the smallest convex pitch-curve radius "
                f"{float(np.min(np.where(rho > -p.roller_radius, rho + p.roller_radius, np.inf))):.6g} "
                f"(at {math.degrees(theta[k]):.4g} deg)"
            )
        else:
            detail = (
                f"the cam's radius of curvature {float(rho.min()):.6g} is not positive "
                f"at {math.degrees(theta[k]):.4g} deg"
            )
        raise GearleverError(f"undercut: {detail}; the smallest base radius that avoids it is {least:.6g}")
    convex = rho > 0
    rho_min = (
        float(np.min(rho[convex]))
        if np.any(convex) and not undercut
        else float(np.min(np.where(r["undercut"], rho, np.inf)))
    )
    units = law.units if kind.law_output == "displacement" else "length"
    nan = math.nan
    return CamDesign(
        theta,
        s,
        v,
        a,
        r["pitch"],
        r["surface"],
        r["contact"],
        r["phi"],
        rho,
        kind.name,
        rb,
        p.roller_radius if kind.contact == "roller" else nan,
        p.offset if "offset" in kind.needs else nan,
        p.arm if "arm" in kind.needs else nan,
        p.pivot_distance if "pivot_distance" in kind.needs else nan,
        stroke,
        float(np.max(np.abs(r["phi"]))),
        rho_min,
        undercut,
        *r["face"],
        units,
    )
