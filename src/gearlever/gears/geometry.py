"""Involute tooth geometry: spur and helical, external, internal and rack meshes.

The basic rack is ISO 53 by default (addendum ``1``, dedendum ``1.25``, root
radius ``0.38`` module, pressure angle 20 deg), every value settable.  Helical
gears keep their normal and transverse quantities apart: the module, pressure
angle, profile shift and basic rack are given in the normal section and
converted once, ``m_t = m_n / cos beta``, ``alpha_t = atan(tan alpha_n / cos
beta)``, shift amount ``x_n m_n`` (ISO 21771:2007, 4.2-4.3).

Lengths are in the unit of the module; angles in radians.

Numeric core: imports numpy, :mod:`gearlever.errors`, :mod:`gearlever._result`
and :mod:`gearlever._validate`; never pandas or matplotlib.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite, nonnegative, positive, positive_int
from gearlever.errors import GearleverError

__all__ = [
    "MAX_TEETH",
    "MAX_OUTLINE_POINTS",
    "MIN_TIP_THICKNESS",
    "involute",
    "inverse_involute",
    "BasicRack",
    "ToothProfile",
    "max_shift_for_tip",
    "tip_thickness",
    "ChordalThickness",
    "chordal_thickness",
    "tooth_profile",
    "tooth_outline",
    "KINDS",
    "SPLITS",
    "GearMesh",
    "PlanetaryGeometry",
    "mesh",
    "working_pressure_angle",
    "shifts_for_center_distance",
    "min_teeth_no_undercut",
    "min_shift_no_undercut",
    "internal_interference",
    "max_mating_teeth",
    "min_pinion_teeth",
    "backlash",
    "planetary_geometry",
    "Backlash",
    "InternalInterference",
]

#: Largest tooth number accepted (the outline has ~60 points a tooth).
MAX_TEETH = 10000
#: Most points of a whole gear's outline (teeth times the points of one tooth).
MAX_OUTLINE_POINTS = 2_000_000
#: Least tip thickness, in modules, of a tooth that is not pointed.
MIN_TIP_THICKNESS = 0.2
_DEG20 = math.radians(20.0)


# --------------------------------------------------------------------------- involute function


def involute(alpha):
    """The involute function ``inv alpha = tan alpha - alpha``.

    Examples
    --------
    >>> round(float(involute(math.radians(20))), 9)
    0.014904384
    """
    a = np.asarray(alpha, dtype=float)
    out = np.tan(a) - a
    return float(out) if out.ndim == 0 else out


def inverse_involute(value: float) -> float:
    """The angle ``alpha`` in [0, pi/2) with ``inv alpha = value``, by Newton's method.

    Notes
    -----
    ``d(inv alpha)/d alpha = tan^2 alpha``; Newton from Cheng's start
    ``alpha0 = (3 v)^(1/3)`` (third-order series of the involute) converges
    to 1e-15 within a few steps for every ``v`` of a gear (0 <= v < 1).

    Examples
    --------
    >>> round(math.degrees(inverse_involute(involute(math.radians(26.0886)))), 9)
    26.0886
    """
    v = float(value)
    if not math.isfinite(v) or v < 0:
        raise GearleverError(f"involute value must be a non-negative finite number, got {value!r}")
    if v == 0.0:
        return 0.0
    a = min((3.0 * v) ** (1.0 / 3.0), 1.5)
    for _ in range(60):
        t = math.tan(a)
        step = (t - a - v) / (t * t)
        a_new = a - step
        if a_new <= 0:
            a_new = a / 2
        elif a_new >= math.pi / 2:
            a_new = (a + math.pi / 2) / 2
        if abs(a_new - a) < 1e-16 * max(1.0, a):
            a = a_new
            break
        a = a_new
    return a


# --------------------------------------------------------------------------- checks


def _teeth(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        else:
            raise GearleverError(f"{name} must be a positive integer, got {value!r}")
    z = positive_int(name, value)
    if z > MAX_TEETH:
        raise GearleverError(f"{name} must be at most {MAX_TEETH}, got {z}")
    return z


def _helix(value) -> float:
    b = finite("helix", value)
    if not 0.0 <= abs(b) < math.radians(45.0):
        raise GearleverError(f"helix must be below 45 deg in magnitude, got {math.degrees(b):.6g} deg")
    return b


def _pressure(value) -> float:
    a = finite("pressure_angle", value)
    if not math.radians(5.0) <= a <= math.radians(40.0):
        raise GearleverError(f"pressure_angle must be between 5 and 40 deg, got {math.degrees(a):.6g} deg")
    return a


@dataclass(frozen=True)
class BasicRack(Result):
    """The basic rack in modules of the normal section (ISO 53:1998 profile A by default).

    Attributes
    ----------
    addendum : gear addendum ``h_aP*`` (1).
    dedendum : gear dedendum ``h_fP*`` (1.25), the cutter's addendum.
    root_radius : cutter tip radius ``rho_fP*`` (0.38), the gear's root fillet.

    Examples
    --------
    >>> BasicRack()
    BasicRack(addendum=1.0, dedendum=1.25, root_radius=0.38)
    """

    addendum: float = 1.0
    dedendum: float = 1.25
    root_radius: float = 0.38

    def __post_init__(self):
        ha = positive("addendum", self.addendum)
        hf = positive("dedendum", self.dedendum)
        rho = nonnegative("root_radius", self.root_radius)
        if hf <= ha * 0.5:
            raise GearleverError(f"dedendum must exceed half the addendum, got {hf!r}")
        if rho >= hf:
            raise GearleverError(f"root_radius must be below the dedendum {hf!r}, got {rho!r}")
        object.__setattr__(self, "addendum", ha)
        object.__setattr__(self, "dedendum", hf)
        object.__setattr__(self, "root_radius", rho)


# --------------------------------------------------------------------------- tooth profile


def _transverse(module: float, pressure_angle: float, helix: float) -> tuple[float, float]:
    cb = math.cos(helix)
    return module / cb, math.atan(math.tan(pressure_angle) / cb)


def _half_tooth_polar(
    z: int,
    mt: float,
    alpha_t: float,
    shift_len: float,
    ha_len: float,
    hf_len: float,
    rho: float,
    ra: float,
    n_flank: int,
    n_fillet: int,
    n_arc: int,
    name_shift: str = "shift",
    mn: float = 1.0,
):
    """Half a generated external tooth in polar coordinates ``(R, theta)`` from the tooth centreline.

    Ordered from the tip centre (theta = 0) down the right flank to the middle
    of the space (theta = pi/z).  Returns the points and the index range of the
    involute part.
    """
    r = mt * z / 2.0
    rb = r * math.cos(alpha_t)
    tan_a = math.tan(alpha_t)
    p = math.pi * mt
    yd = r + shift_len  # datum line of the generating rack
    yt = yd - hf_len  # cutter tip line = gear root circle
    rf = yt
    if rf <= 0:
        raise GearleverError(f"{name_shift} gives a root circle of radius {rf:.6g} <= 0")
    psi = (p / 4.0 + shift_len * tan_a) / r  # half tooth thickness angle at the reference circle
    inv_a = math.tan(alpha_t) - alpha_t

    def theta_inv(R):
        e = np.sqrt(np.maximum((np.asarray(R) / rb) ** 2 - 1.0, 0.0))
        return psi + inv_a - (e - np.arctan(e))

    # cutter fillet centre (rack coordinates: u along the pitch line, y radial)
    yc = yt + rho
    uc = p / 4.0 + (yd - yc) * tan_a + rho / math.cos(alpha_t)
    if uc > p / 2.0 + 1e-12 * p:
        rho_max = (p / 4.0 - hf_len * tan_a) / (1.0 / math.cos(alpha_t) - tan_a)
        raise GearleverError(
            f"root_radius too large: the rack's tip rounds overlap (at most {rho_max / mn:.4g} "
            f"module at this pressure angle and dedendum)"
        )
    # fillet envelope: cutter points c + rho*(-cos tau, -sin tau), tau in [alpha_t, pi/2]
    tau = np.linspace(alpha_t, math.pi / 2.0, max(4 * n_fillet, 200))

    def envelope(tau_):
        nx, ny = -np.cos(tau_), -np.sin(tau_)
        u0, y0 = uc + rho * nx, yc + rho * ny
        t = (r - y0) / ny
        phi = (u0 + t * nx) / r
        xr = u0 - r * phi
        gx = xr * np.cos(phi) + y0 * np.sin(phi)
        gy = -xr * np.sin(phi) + y0 * np.cos(phi)
        return np.hypot(gx, gy), np.arctan2(gx, gy)

    # height of the fillet/flank tangent point and the interference point of the line of action
    y_tan = yc - rho * math.sin(alpha_t)
    undercut = (r - y_tan) > r * math.sin(alpha_t) ** 2 + 1e-12 * r
    if not undercut:
        d_tan = (r - y_tan) / math.sin(alpha_t)
        r_form = math.hypot(rb, r * math.sin(alpha_t) - d_tan)
        tau_end = alpha_t
    else:
        R_all, th_all = envelope(tau)
        g = np.where(R_all >= rb, th_all - theta_inv(R_all), -np.inf)
        # tau increases toward the root; g > 0 (involute inside) above the crossing, < 0 below it
        idx = np.nonzero((g[:-1] > 0) & (g[1:] <= 0))[0]
        if idx.size == 0:
            raise GearleverError(f"{name_shift} leaves no involute flank: the tooth is undercut through")
        lo, hi = tau[idx[0]], tau[idx[0] + 1]
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            Rm, tm = envelope(np.array([mid]))
            gm = tm[0] - theta_inv(Rm[0]) if Rm[0] >= rb else -np.inf
            if gm > 0:
                lo = mid
            else:
                hi = mid
        tau_end = 0.5 * (lo + hi)
        r_form = float(envelope(np.array([tau_end]))[0][0])
    if ra <= r_form:
        raise GearleverError(f"tip circle (radius {ra:.6g}) lies below the form circle (radius {r_form:.6g})")
    # involute flank, sampled uniformly in roll angle
    e0 = math.sqrt(max((r_form / rb) ** 2 - 1.0, 0.0))
    e1 = math.sqrt((ra / rb) ** 2 - 1.0)
    e = np.linspace(e1, e0, n_flank)
    R_inv = rb * np.sqrt(1.0 + e * e)
    R_inv[0], R_inv[-1] = ra, r_form
    th_inv = psi + inv_a - (e - np.arctan(e))
    th_tip = float(th_inv[0])
    # tip arc
    th_arc = np.linspace(0.0, th_tip, n_arc + 1)[:-1]
    R_arc = np.full_like(th_arc, ra)
    # fillet from the form point to the root
    R_f, th_f = envelope(np.linspace(tau_end, math.pi / 2.0, n_fillet + 1)[1:])
    # root arc to the middle of the space
    th_root0 = uc / r
    half_pitch = math.pi / z
    th_root = np.linspace(th_root0, half_pitch, n_arc + 1)[1:] if half_pitch - th_root0 > 1e-12 else np.zeros(0)
    R = np.concatenate([R_arc, R_inv, R_f, np.full_like(th_root, rf)])
    th = np.concatenate([th_arc, th_inv, th_f, th_root])
    return R, th, (len(R_arc), len(R_arc) + len(R_inv)), r_form, rf


def _internal_half_space_polar(
    z: int,
    mt: float,
    alpha_t: float,
    shift_len: float,
    ha_len: float,
    hf_len: float,
    rho: float,
    r_tip: float,
    n_flank: int,
    n_fillet: int,
    n_arc: int,
    mn: float = 1.0,
):
    """Half a space of an internal gear in polar coordinates from the space centreline.

    The space of an internal gear is the tooth of an external gear of the
    same teeth and shift: involute from the ring's tip circle (``r_tip``, at
    least the base circle) to its root circle ``r + hf + x m``, the root fillet a
    circular arc of radius ``rho`` tangent to the flank and the root circle (a
    shaper cutter's trochoid depends on the cutter; this arc is its common
    drawing).  Ordered from the space centre (theta = 0, at the root) to the
    middle of the ring's tooth (theta = pi/z, at the tip circle).
    """
    r = mt * z / 2.0
    rb = r * math.cos(alpha_t)
    psi = (math.pi * mt / 4.0 + shift_len * math.tan(alpha_t)) / r  # half space width angle
    inv_a = math.tan(alpha_t) - alpha_t
    r_root = r + hf_len + shift_len
    r_tip = max(r_tip, rb)

    def point(e):  # involute point of roll e: radius, angle and outward unit normal pointing away from the space
        R = rb * math.sqrt(1 + e * e)
        th = psi + inv_a - (e - math.atan(e))
        return R, th

    def cart(R, th):
        return np.array([R * math.sin(th), R * math.cos(th)])

    e_root = math.sqrt((r_root / rb) ** 2 - 1.0)
    e_tip = math.sqrt(max((r_tip / rb) ** 2 - 1.0, 0.0))
    if psi + inv_a - (e_root - math.atan(e_root)) <= 0:
        raise GearleverError(f"shift {shift_len / mn:.6g} makes the internal gear's space pointed at its root")

    def fillet(rho):
        """The fillet arc of radius rho: roll of its flank end, arc points (R, theta), theta of its root end."""
        if rho <= 0:
            return e_root, np.zeros(0), np.zeros(0), point(e_root)[1]

        def centre(e):  # fillet centre inside the space, rho from the involute point of roll e along its normal
            R, th = point(e)
            q = cart(R, th)
            t_pt = cart(rb, th - math.atan(e))  # the involute's normal touches the base circle there
            span = float(np.linalg.norm(t_pt - q))
            # on the base circle (e = 0) the normal is the circle's tangent, toward smaller theta
            nrm = (t_pt - q) / span if span > 1e-12 * rb else np.array([-math.cos(th), math.sin(th)])
            c = q + rho * nrm
            if math.atan2(c[0], c[1]) > th:
                c = q - rho * nrm
            return c, q

        def h(e):
            return float(np.linalg.norm(centre(e)[0])) - (r_root - rho)

        lo, hi = e_tip, e_root
        if h(lo) > 0 or h(hi) < 0:
            return None
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            if h(mid) < 0:
                lo = mid
            else:
                hi = mid
        e_f = 0.5 * (lo + hi)
        c, q = centre(e_f)
        a_q = math.atan2(q[1] - c[1], q[0] - c[0])
        a_r = math.atan2(c[1], c[0])  # direction of the root tangency point from the centre
        da = (a_q - a_r + math.pi) % (2 * math.pi) - math.pi
        ang = a_r + da * np.linspace(0.0, 1.0, n_fillet + 1)
        fil = c[None, :] + rho * np.column_stack([np.cos(ang), np.sin(ang)])
        th_fil = np.arctan2(fil[:, 0], fil[:, 1])
        return e_f, np.hypot(fil[:, 0], fil[:, 1]), th_fil, float(th_fil[0])

    res = fillet(rho)
    if res is None or res[3] < 0:
        # the space's root is narrower than two fillets: the largest radius that fits (bisection)
        lo, hi = 0.0, rho
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            rr = fillet(mid)
            if rr is None or rr[3] < 0:
                hi = mid
            else:
                lo = mid
        rho = lo
        res = fillet(rho)
    e_f, R_fil, th_fil, th_root_end = res
    th_arc = np.linspace(0.0, th_root_end, n_arc + 1)[:-1]
    e = np.linspace(e_f, e_tip, n_flank)
    R_inv = rb * np.sqrt(1 + e * e)
    th_inv = psi + inv_a - (e - np.arctan(e))
    if rho > 0:
        R_inv, th_inv = R_inv[1:], th_inv[1:]
    half_pitch = math.pi / z
    th_tip0 = float(th_inv[-1])
    if th_tip0 >= half_pitch:
        raise GearleverError("shift points the internal gear's teeth")
    th_t = np.linspace(th_tip0, half_pitch, n_arc + 1)[1:]
    R = np.concatenate([np.full_like(th_arc, r_root), R_fil, R_inv, np.full_like(th_t, r_tip)])
    th = np.concatenate([th_arc, th_fil, th_inv, th_t])
    i0 = len(th_arc) + len(R_fil) - (1 if rho > 0 else 0)
    return R, th, (i0, i0 + len(R_inv) + (1 if rho > 0 else 0)), r_tip, r_root


@dataclass(frozen=True)
class ToothProfile(Result):
    """One tooth (external) or one space (internal) of a generated gear, transverse section.

    Attributes
    ----------
    points : (N, 2) from the middle of one space (external) or tooth (internal) to the next,
        symmetric about the +x axis, which is the tooth's (external) or space's (internal) centreline.
    flank : (2,) index range ``[i0, i1)`` of the involute points of the flank at negative y
        (the one at positive y is its mirror).
    reference_radius, base_radius, tip_radius, root_radius, form_radius : radii of the gear.

    Examples
    --------
    >>> p = tooth_profile(2.0, 20)
    >>> p.points.shape[1], round(p.tip_radius, 6), round(p.form_radius, 4)
    (2, 22.0, 18.8201)
    """

    points: np.ndarray
    flank: tuple[int, int]
    reference_radius: float
    base_radius: float
    tip_radius: float
    root_radius: float
    form_radius: float


def tooth_profile(
    module: float,
    teeth: int,
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
    internal: bool = False,
    tip_diameter: float | None = None,
    points: int = 24,
) -> ToothProfile:
    """One tooth of a gear cut by the basic rack: involute flanks and trochoidal root fillets.

    Parameters
    ----------
    module : normal module (> 0).
    teeth : number of teeth (positive integer, at most :data:`MAX_TEETH`).
    shift : profile shift coefficient ``x`` (normal section, in modules).
    pressure_angle : normal pressure angle of the basic rack (rad).
    helix : helix angle ``beta`` (rad, ``|beta| < 45 deg``); the profile is the transverse section.
    addendum, dedendum, root_radius : basic rack in modules (ISO 53: 1, 1.25, 0.38).
    internal : an internal gear (ring): the space is the external tooth of the same shift.
    tip_diameter : tip diameter (default ``d + 2 (addendum + x) m``; internal ``d - 2 (addendum - x) m``),
        e.g. a shortened tip from :func:`mesh`.
    points : points along each involute flank (the fillet gets half as many, >= 4).

    Returns
    -------
    ToothProfile

    Notes
    -----
    The involute is the analytic one: at radius ``R`` its angle from the tooth
    centreline is ``s/(2r) + inv alpha_t - inv alpha_R`` with ``cos alpha_R =
    r_b/R`` and ``s = m_t (pi/2 + 2 x tan alpha_t)`` (ISO 21771:2007, eq. 54).
    The root fillet is the envelope of the rack's tip round rolled on the
    reference circle: each point of the round touches the gear where its normal
    passes through the pitch point (the law of gearing; F. L. Litvin and A.
    Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 6, 8).
    When the rack's tip round reaches past the interference point the fillet
    cuts the involute (undercut) and the flank starts at their intersection.

    Examples
    --------
    >>> p = tooth_profile(3.0, 12, 0.6)
    >>> round(p.tip_radius, 6), round(p.root_radius, 6)
    (22.8, 16.05)
    """
    m = positive("module", module)
    z = _teeth("teeth", teeth)
    x = finite("shift", shift)
    a_n = _pressure(pressure_angle)
    beta = _helix(helix)
    rack = BasicRack(addendum, dedendum, root_radius)
    n = positive_int("points", points)
    if n < 4 or n > 2000:
        raise GearleverError(f"points must be in [4, 2000], got {n}")
    mt, at = _transverse(m, a_n, beta)
    r = mt * z / 2.0
    rb = r * math.cos(at)
    sh = x * m
    if not internal:
        ra = r + (rack.addendum + x) * m if tip_diameter is None else positive("tip_diameter", tip_diameter) / 2
        s_tip = _tip_thickness_at(m, z, x, a_n, beta, 2 * ra, internal=False)
        if not s_tip >= MIN_TIP_THICKNESS * m - 1e-12:
            largest = max_shift_for_tip(m, z, pressure_angle=a_n, helix=beta, addendum=rack.addendum)
            raise GearleverError(
                f"shift {x:.6g} points the tooth: tip thickness {s_tip / m:.4g} module < {MIN_TIP_THICKNESS}; "
                f"largest shift {largest:.4g}"
            )
        R, th, fl, r_form, rf = _half_tooth_polar(
            z, mt, at, sh, rack.addendum * m, rack.dedendum * m, rack.root_radius * m, ra, n, max(4, n // 2), 4, mn=m
        )
        tip_r = ra
        # right half: theta from 0 (tooth centre) to pi/z; the profile runs from the space at -pi/z to +pi/z
        th_full = np.concatenate([-th[::-1], th[1:]])
        R_full = np.concatenate([R[::-1], R[1:]])
        k = len(R) - 1
        flank = (k - fl[1] + 1, k - fl[0] + 1)
    else:
        ra = r - (rack.addendum - x) * m if tip_diameter is None else positive("tip_diameter", tip_diameter) / 2
        R, th, fl, tip_r, rf = _internal_half_space_polar(
            z, mt, at, sh, rack.addendum * m, rack.dedendum * m, rack.root_radius * m, ra, n, max(4, n // 2), 4, mn=m
        )
        r_form = tip_r
        th_full = np.concatenate([-th[::-1], th[1:]])
        R_full = np.concatenate([R[::-1], R[1:]])
        k = len(R) - 1
        flank = (k - fl[1] + 1, k - fl[0] + 1)
    # polar angle from the +x axis: theta measured from the centreline, positive toward +y
    pts = np.column_stack([R_full * np.cos(th_full), R_full * np.sin(th_full)])
    return ToothProfile(pts, flank, r, rb, tip_r, rf, r_form)


def tooth_outline(
    module: float,
    teeth: int,
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
    internal: bool = False,
    tip_diameter: float | None = None,
    points: int = 24,
) -> np.ndarray:
    """The closed outline of a whole gear, centred at the origin, as an (N, 2) array.

    Parameters as for :func:`tooth_profile`.  A tooth (external) or a space
    (internal) is centred on the +x axis; the outline runs counter-clockwise
    and closes from its last point back to its first (the first point is not
    repeated).  For an internal gear the outline is the ring's toothed inner
    boundary (its outer rim is the drawer's choice).

    Notes
    -----
    The teeth are :func:`tooth_profile` rotated by ``2 pi k / z``; see there
    for the equations and sources.

    Examples
    --------
    >>> xy = tooth_outline(2.0, 20)
    >>> r = np.hypot(xy[:, 0], xy[:, 1])
    >>> round(float(r.max()), 9), round(float(r.min()), 9)
    (22.0, 17.5)
    """
    prof = tooth_profile(
        module,
        teeth,
        shift,
        pressure_angle=pressure_angle,
        helix=helix,
        addendum=addendum,
        dedendum=dedendum,
        root_radius=root_radius,
        internal=internal,
        tip_diameter=tip_diameter,
        points=points,
    )
    z = int(teeth)
    one = prof.points[:-1]  # the last point is the next tooth's first
    if z * len(one) > MAX_OUTLINE_POINTS:
        raise GearleverError(
            f"points {points} with {z} teeth gives {z * len(one)} outline points, at most {MAX_OUTLINE_POINTS}"
        )
    out = []
    for k in range(z):
        a = 2 * math.pi * k / z
        c, s = math.cos(a), math.sin(a)
        out.append(one @ np.array([[c, s], [-s, c]]))
    return np.concatenate(out)


def max_shift_for_tip(
    module: float,
    teeth: int,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    min_tip_thickness: float = MIN_TIP_THICKNESS,
    tip_shortening: float = 0.0,
) -> float:
    """The largest profile shift whose tip thickness is ``min_tip_thickness`` modules (normal section).

    Notes
    -----
    Bisection on :func:`tip_thickness`, which falls monotonically with the
    shift (the tip circle grows faster than the tooth thickens).

    Examples
    --------
    >>> round(max_shift_for_tip(1.0, 12), 4)
    0.6021
    """
    z = _teeth("teeth", teeth)
    lo, hi = -1.0, 3.0

    def f(x):
        return (
            tip_thickness(
                1.0,
                z,
                x,
                pressure_angle=pressure_angle,
                helix=helix,
                addendum=addendum,
                tip_shortening=tip_shortening,
            )
            - min_tip_thickness
        )

    if f(lo) < 0:
        return lo
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def tip_thickness(
    module: float,
    teeth: int,
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    tip_shortening: float = 0.0,
    internal: bool = False,
) -> float:
    """Normal tooth thickness at the tip circle (length), ``s_an``.

    Notes
    -----
    Transverse ``s_at = d_a (s_t/d + inv alpha_t - inv alpha_at)``, ``cos
    alpha_at = d_b/d_a``; normal ``s_an = s_at cos beta_a`` with ``tan beta_a
    = tan beta d_a/d`` (ISO 21771:2007, eq. 66-70; KHK, *Gear Technical
    Reference*, tooth thickness at the tip).  Tip diameter ``d + 2 (h_a* + x -
    k) m_n``; an internal gear's ``d - 2 (h_a* - x - k) m_n`` with its
    thickness ``s_t = m_t (pi/2 - 2 x tan alpha_t)``.

    Examples
    --------
    >>> round(tip_thickness(1.0, 20), 4)
    0.6949
    """
    m = positive("module", module)
    z = _teeth("teeth", teeth)
    x = finite("shift", shift)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    mt = m / math.cos(beta)
    d = mt * z
    if not internal:
        da = d + 2 * (addendum + x - tip_shortening) * m
    else:
        da = d - 2 * (addendum - x - tip_shortening) * m
    return _tip_thickness_at(m, z, x, a_n, beta, da, internal=internal)


def _tip_thickness_at(m: float, z: int, x: float, a_n: float, beta: float, da: float, internal: bool) -> float:
    """Normal tooth thickness at the diameter ``da`` (NaN where ``da`` is inside an external gear's base circle)."""
    mt, at = _transverse(m, a_n, beta)
    d = mt * z
    db = d * math.cos(at)
    if not internal:
        st = mt * math.pi / 2 + 2 * x * m * math.tan(at)
    else:
        st = mt * math.pi / 2 - 2 * x * m * math.tan(at)
    if da <= db:
        if internal:
            da = db
        else:
            return float("nan")
    a_a = math.acos(db / da)
    sign = 1.0 if not internal else -1.0
    sat = da * (st / d + sign * (involute(at) - involute(a_a)))
    beta_a = math.atan(math.tan(beta) * da / d)
    return sat * math.cos(beta_a)


@dataclass(frozen=True)
class ChordalThickness(Result):
    """Chordal tooth thickness of an external gear at its reference circle, as a gear-tooth caliper reads it.

    ``circular_thickness`` ``s_n`` (normal section, arc on the reference circle), ``virtual_teeth`` ``z_v``,
    ``half_angle`` ``theta_v`` (radians, half the tooth's angle on the virtual gear's reference circle),
    ``chordal_thickness`` ``s_j`` and ``chordal_addendum`` ``h_j`` (the caliper's depth from the tip), lengths
    in the unit of the module.

    Examples
    --------
    >>> round(chordal_thickness(10.0, 12, 0.3).chordal_thickness, 4)
    17.8256
    """

    circular_thickness: float
    virtual_teeth: float
    half_angle: float
    chordal_thickness: float
    chordal_addendum: float


def chordal_thickness(
    module: float,
    teeth: int,
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    tip_shortening: float = 0.0,
) -> ChordalThickness:
    """Chordal thickness and chordal addendum of an external spur or helical gear (normal section).

    Parameters
    ----------
    module, pressure_angle, shift : the normal module, pressure angle (radians) and profile shift ``x_n``.
    teeth : the number of teeth ``z``.
    helix : the helix angle ``beta`` (radians).
    addendum, tip_shortening : ``h_a*`` and ``k`` (modules): the addendum ``h_a = (h_a* + x_n - k) m_n`` from
        which the caliper is set.

    Notes
    -----
    Stock Drive Products / Sterling Instrument, *Elements of Metric Gear
    Technology* (D785), sec. 10.1, Tables 10-1 (spur), 10-3 (helical, normal
    system) and 10-4 (transverse system), the tables of KHK's *Gear Technical
    Reference*: ``s_n = (pi/2 + 2 x_n tan alpha_n) m_n``, ``z_v = z /
    cos^3 beta``, ``theta_v = pi/(2 z_v) + 2 x_n tan alpha_n / z_v``, ``s_j =
    z_v m_n sin theta_v``, ``h_j = z_v m_n (1 - cos theta_v)/2 + h_a``.  A
    transverse-system gear (``m_t, alpha_t, x_t``) is the same gear with ``m_n
    = m_t cos beta``, ``tan alpha_n = tan alpha_t cos beta`` and ``x_n m_n =
    x_t m_t`` (its ``theta_v`` term ``x_t tan alpha_t`` equals ``x_n tan
    alpha_n m_n / (m_t cos beta)``).

    Examples
    --------
    >>> c = chordal_thickness(10.0, 12, 0.3)
    >>> round(c.circular_thickness, 4), round(math.degrees(c.half_angle), 5), round(c.chordal_addendum, 4)
    (17.8918, 8.5427, 13.6657)
    """
    m = positive("module", module)
    z = _teeth("teeth", teeth)
    x = finite("shift", shift)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    ha = (finite("addendum", addendum) + x - finite("tip_shortening", tip_shortening)) * m
    s_n = (math.pi / 2 + 2 * x * math.tan(a_n)) * m
    if s_n <= 0:
        raise GearleverError(f"shift {x!r} leaves no tooth at the reference circle (thickness {s_n:.6g})")
    zv = z / math.cos(beta) ** 3
    theta = math.pi / (2 * zv) + 2 * x * math.tan(a_n) / zv
    return ChordalThickness(
        circular_thickness=s_n,
        virtual_teeth=zv,
        half_angle=theta,
        chordal_thickness=zv * m * math.sin(theta),
        chordal_addendum=zv * m * (1 - math.cos(theta)) / 2 + ha,
    )


# --------------------------------------------------------------------------- meshes

KINDS = ("external", "internal", "rack")
#: Rules that split a sum of profile shifts between the two gears (:func:`shifts_for_center_distance`).
SPLITS = ("inverse", "proportional", "equal", "pinion")
#: Least transverse contact ratio of a mesh (below it the teeth lose contact).
MIN_CONTACT_RATIO = 1.0


def _generating_addendum(rack: BasicRack, alpha_n: float) -> float:
    """The rack's straight-flank addendum that cuts the flank: ``h_fP* - rho_fP* (1 - sin alpha_n)``."""
    return rack.dedendum - rack.root_radius * (1.0 - math.sin(alpha_n))


def min_teeth_no_undercut(
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
) -> int:
    """The fewest teeth a gear of profile shift ``shift`` can have without undercut.

    Notes
    -----
    The straight flank of the generating rack must end (at its tip round)
    inside the interference point of the line of action: ``(h_a0 - x) m_n <=
    r sin^2 alpha_t``, ``h_a0 = h_fP* - rho_fP* (1 - sin alpha_n)``, i.e. ``z
    >= 2 (h_a0 - x) cos beta / sin^2 alpha_t`` (ISO 21771:2007, 5.5; KHK,
    *Gear Technical Reference*, undercut; Niemann/Winter, *Maschinenelemente*
    II, eq. 21.20).  ISO 53 profile A gives ``h_a0 = 0.99997``, ``z_min = 17.097``, so
    18 teeth (KHK's and Niemann's "17" rounds down, accepting a trace of undercut).

    Examples
    --------
    >>> min_teeth_no_undercut(), min_teeth_no_undercut(0.5)
    (18, 9)
    """
    x = finite("shift", shift)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    rack = BasicRack(1.0, dedendum, root_radius)
    at = math.atan(math.tan(a_n) / math.cos(beta))
    zmin = 2.0 * (_generating_addendum(rack, a_n) - x) * math.cos(beta) / math.sin(at) ** 2
    return max(1, math.ceil(zmin - 1e-9))


def min_shift_no_undercut(
    teeth: int,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
) -> float:
    """The least profile shift that avoids undercut: ``x_min = h_a0 - z sin^2 alpha_t / (2 cos beta)``.

    Notes
    -----
    The condition of :func:`min_teeth_no_undercut` solved for ``x``.

    Examples
    --------
    >>> round(min_shift_no_undercut(12), 4)
    0.2981
    """
    z = _teeth("teeth", teeth)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    rack = BasicRack(1.0, dedendum, root_radius)
    at = math.atan(math.tan(a_n) / math.cos(beta))
    return _generating_addendum(rack, a_n) - z * math.sin(at) ** 2 / (2.0 * math.cos(beta))


def working_pressure_angle(
    teeth1: int, teeth2: int, shift1: float, shift2: float, *, pressure_angle=_DEG20, helix=0.0, internal: bool = False
) -> float:
    """Transverse working pressure angle ``alpha_wt`` of a pair from its profile shifts.

    Notes
    -----
    ``inv alpha_wt = inv alpha_t + 2 tan alpha_n (x_1 + x_2)/(z_1 + z_2)``
    (external), ``... (x_2 - x_1)/(z_2 - z_1)`` (internal; gear 2 the ring),
    solved by Newton's method on the involute function (:func:`inverse_involute`;
    ISO 21771:2007, eq. 61; KHK, *Gear Technical Reference*, Table 4-6 and 4-15).

    Examples
    --------
    >>> round(math.degrees(working_pressure_angle(12, 24, 0.6, 0.36)), 4)
    26.0886
    """
    z1, z2 = _teeth("teeth1", teeth1), _teeth("teeth2", teeth2)
    x1, x2 = finite("shift1", shift1), finite("shift2", shift2)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    at = math.atan(math.tan(a_n) / math.cos(beta))
    if internal:
        if z2 <= z1:
            raise GearleverError(f"teeth2 (the ring) must exceed teeth1, got {z1} and {z2}")
        v = involute(at) + 2 * math.tan(a_n) * (x2 - x1) / (z2 - z1)
    else:
        v = involute(at) + 2 * math.tan(a_n) * (x1 + x2) / (z1 + z2)
    if v <= 0:
        raise GearleverError(f"shift {x1:.6g}, {x2:.6g} gives no working pressure angle (inv alpha_wt = {v:.6g} <= 0)")
    return inverse_involute(v)


def shifts_for_center_distance(
    center_distance: float,
    module: float,
    teeth1: int,
    teeth2: int,
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    internal: bool = False,
    split: str = "inverse",
) -> tuple[float, float]:
    """Profile shifts ``(x_1, x_2)`` that give a pair the centre distance ``center_distance``.

    The sum follows from the working pressure angle ``cos alpha_wt = a_0 cos
    alpha_t / a`` and the involute equation (ISO 21771:2007, eq. 61-62); the
    standard fixes only the sum.  It is split by ``split``:

    ``"inverse"`` (default)
        in inverse proportion to the tooth numbers, ``x_1 = sum z_2/(z_1 +
        z_2)``: the smaller gear, the one that undercuts first and is weaker
        at the root, takes the larger share (the direction of the DIN 3992 /
        Niemann recommendation, whose split is read from charts and is not
        reproduced here).
    ``"proportional"``
        in proportion to the tooth numbers, ``x_i = sum z_i/(z_1 + z_2)``:
        each profile moves by the same fraction of its reference radius.
    ``"equal"``
        ``x_1 = x_2 = sum / 2``.
    ``"pinion"``
        all on gear 1 (``x_2 = 0``).

    For an internal pair the difference ``x_2 - x_1`` is fixed: ``"equal"``
    gives ``(-d/2, d/2)``, every other rule puts it on the ring (``x_1 = 0``,
    ``x_2 = d``), where it does not thin the pinion.

    Examples
    --------
    KHK's shifted pair back from its centre distance (the sum 0.96):

    >>> x1, x2 = shifts_for_center_distance(56.4999, 3.0, 12, 24)
    >>> round(x1 + x2, 4), round(x1, 4)
    (0.96, 0.64)
    """
    a = positive("center_distance", center_distance)
    m = positive("module", module)
    z1, z2 = _teeth("teeth1", teeth1), _teeth("teeth2", teeth2)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    if split not in SPLITS:
        raise GearleverError(f"split must be one of {', '.join(SPLITS)}, got {split!r}")
    mt, at = _transverse(m, a_n, beta)
    zs = (z2 - z1) if internal else (z1 + z2)
    if internal and z2 <= z1:
        raise GearleverError(f"teeth2 (the ring) must exceed teeth1, got {z1} and {z2}")
    a0 = zs * mt / 2.0
    c = a0 * math.cos(at) / a
    if not 0.0 < c < 1.0:
        raise GearleverError(f"center_distance {a:.6g} cannot be reached by profile shifts (reference {a0:.6g})")
    awt = math.acos(c)
    total = (involute(awt) - involute(at)) * zs / (2 * math.tan(a_n))
    if internal:
        if split == "equal":
            return -total / 2, total / 2
        return 0.0, total
    if split == "equal":
        return total / 2, total / 2
    if split == "pinion":
        return total, 0.0
    if split == "proportional":
        return total * z1 / (z1 + z2), total * z2 / (z1 + z2)
    return total * z2 / (z1 + z2), total * z1 / (z1 + z2)


@dataclass(frozen=True)
class GearMesh(Result):
    """Geometry of a gear pair (gear 1 the pinion; gear 2 the mating gear, the ring or the rack).

    Per-gear fields are arrays of two, in the order (gear 1, gear 2); a rack's
    diameters are NaN.  Lengths in the module's unit, angles in radians.

    Attributes
    ----------
    kind : ``"external"``, ``"internal"`` or ``"rack"``.
    module, pressure_angle, helix : normal module, normal pressure angle, helix angle.
    transverse_module, transverse_pressure_angle : ``m_t``, ``alpha_t``.
    teeth : (2,) tooth numbers (a rack's is 0).
    shift : (2,) profile shift coefficients (normal section).
    working_pressure_angle : transverse working pressure angle ``alpha_wt``.
    center_distance, reference_center_distance : ``a``, ``a_0`` (a rack's: gear centre to the rack's reference line).
    center_distance_modification : ``y = (a - a_0) / m_n``.
    tip_shortening : ``k = x_1 + x_2 - y`` by which both tips are shortened (0 when off, internal or rack).
    reference_diameter, base_diameter, tip_diameter, root_diameter, working_diameter : (2,).
    tooth_thickness : (2,) normal tooth thickness at the reference circle.
    tip_thickness : (2,) normal tooth thickness at the tip circle.
    contact_ratio_transverse, contact_ratio_overlap, contact_ratio_total : ``eps_alpha, eps_beta, eps_gamma``.
    face_width : ``b`` (NaN when not given; then the overlap ratio is NaN).
    undercut : (2,) whether the generating rack undercuts the gear.
    min_teeth_no_undercut : (2,) the fewest teeth without undercut at each gear's shift (0: a ring or rack,
        which the rack does not cut).
    min_shift_no_undercut : (2,) the least shift without undercut at each gear's teeth.
    interference : (2,) whether the mate's tip reaches below this gear's base circle (involute interference).

    Examples
    --------
    >>> g = mesh(2.0, 20, 40, helix=math.radians(15), face_width=20.0)
    >>> round(g.transverse_module, 6), round(g.contact_ratio_total, 4)
    (2.070552, 2.3848)
    """

    kind: str
    module: float
    pressure_angle: float
    helix: float
    transverse_module: float
    transverse_pressure_angle: float
    teeth: np.ndarray
    shift: np.ndarray
    working_pressure_angle: float
    center_distance: float
    reference_center_distance: float
    center_distance_modification: float
    tip_shortening: float
    reference_diameter: np.ndarray
    base_diameter: np.ndarray
    tip_diameter: np.ndarray
    root_diameter: np.ndarray
    working_diameter: np.ndarray
    tooth_thickness: np.ndarray
    tip_thickness: np.ndarray
    contact_ratio_transverse: float
    contact_ratio_overlap: float
    contact_ratio_total: float
    face_width: float
    undercut: np.ndarray
    min_teeth_no_undercut: np.ndarray
    min_shift_no_undercut: np.ndarray
    interference: np.ndarray
    addendum: float = 1.0
    dedendum: float = 1.25
    root_radius: float = 0.38

    def record(self) -> dict:
        """The ``gearlever gear mesh --json`` keys: angles in degrees, per-gear values as two-element lists."""

        def lst(a):
            return [None if (isinstance(v, float) and not math.isfinite(v)) else v for v in np.asarray(a).tolist()]

        def num(v):
            return None if not math.isfinite(v) else float(v)

        return {
            "working_pressure_angle_deg": math.degrees(self.working_pressure_angle),
            "center_distance": self.center_distance,
            "center_distance_modification": self.center_distance_modification,
            "tip_shortening": self.tip_shortening,
            "shift": lst(self.shift),
            "reference_diameter": lst(self.reference_diameter),
            "base_diameter": lst(self.base_diameter),
            "tip_diameter": lst(self.tip_diameter),
            "root_diameter": lst(self.root_diameter),
            "contact_ratio_transverse": self.contact_ratio_transverse,
            "contact_ratio_overlap": num(self.contact_ratio_overlap),
            "contact_ratio_total": num(self.contact_ratio_total),
            "undercut": [bool(v) for v in self.undercut],
            "min_teeth_no_undercut": [int(v) if v > 0 else None for v in self.min_teeth_no_undercut],
            "interference": [bool(v) for v in self.interference],
            "tip_thickness": lst(self.tip_thickness),
        }


def mesh(
    module: float,
    teeth1: int,
    teeth2: int | None,
    shift1: float = 0.0,
    shift2: float = 0.0,
    *,
    kind: str = "external",
    center_distance: float | None = None,
    split: str = "inverse",
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    face_width: float | None = None,
    addendum: float = 1.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
    tip_shortening: bool = True,
    check: bool = True,
) -> GearMesh:
    """The geometry of a spur or helical pair: external, internal (gear 2 the ring) or rack (``teeth2=None``).

    Parameters
    ----------
    module : normal module ``m_n`` (> 0).
    teeth1, teeth2 : tooth numbers; ``teeth2`` is None (or ignored) for a rack.
    shift1, shift2 : profile shift coefficients (normal section); ignored when ``center_distance`` is given.
    kind : ``"external"``, ``"internal"`` or ``"rack"``.
    center_distance : a wanted centre distance: the shifts are found by
        :func:`shifts_for_center_distance` with ``split``.
    pressure_angle, helix : normal pressure angle and helix angle (rad).
    face_width : ``b`` for the overlap ratio (> 0).
    addendum, dedendum, root_radius : the basic rack in modules.
    tip_shortening : shorten both tips by ``k = x_1 + x_2 - y`` to keep the
        standard bottom clearance (external pairs; on by default).
    check : refuse a mesh with a pointed tooth (tip thickness < 0.2 module), a
        transverse contact ratio below 1, or an internal pair whose tips interfere.

    Notes
    -----
    Normal and transverse quantities kept apart: ``m_t = m_n/cos beta``,
    ``tan alpha_t = tan alpha_n / cos beta``, shifts in the normal section.
    External: ``inv alpha_wt = inv alpha_t + 2 tan alpha_n (x_1+x_2)/(z_1+z_2)``,
    ``a = (z_1+z_2) m_t cos alpha_t / (2 cos alpha_wt)``, ``y = (a - a_0)/m_n``,
    ``k = x_1 + x_2 - y``, ``d_a = d + 2 (h_a* + x - k) m_n``, ``d_f = d - 2
    (h_f* - x) m_n``; transverse contact ratio ``eps_alpha = (sqrt(r_a1^2 -
    r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin alpha_wt)/(pi m_t cos alpha_t)``,
    overlap ``eps_beta = b sin beta / (pi m_n)`` (ISO 21771:2007, eq. 12-24,
    61-64, 84-88; KHK, *Gear Technical Reference*, Tables 4-6, 4-15, 4-20).
    Internal (KHK Table 4-15): ``inv alpha_wt = inv alpha_t + 2 tan alpha_n
    (x_2 - x_1)/(z_2 - z_1)``, ``d_a2 = d_2 - 2 (h_a* - x_2) m_n``, ``d_f2 =
    d_a2 + 2 (h_a* + h_f*) m_n``, ``eps_alpha = (sqrt(r_a1^2 - r_b1^2) -
    sqrt(r_a2^2 - r_b2^2) + a sin alpha_wt)/(pi m_t cos alpha_t)``.  Rack:
    ``eps_alpha = (sqrt(r_a1^2 - r_b1^2) - r_1 sin alpha_t + (h_a* - x_1)
    m_n / sin alpha_t)/(pi m_t cos alpha_t)``.

    Examples
    --------
    KHK's profile-shifted spur pair (m = 3, z = 12/24, x = 0.6/0.36):

    >>> g = mesh(3.0, 12, 24, 0.6, 0.36)
    >>> round(math.degrees(g.working_pressure_angle), 4), round(g.center_distance, 4)
    (26.0886, 56.4999)
    >>> [round(float(v), 2) for v in g.tip_diameter]
    [44.84, 79.4]
    """
    if kind not in KINDS:
        raise GearleverError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    m = positive("module", module)
    z1 = _teeth("teeth1", teeth1)
    internal, rack_mesh = kind == "internal", kind == "rack"
    z2 = 0 if rack_mesh else _teeth("teeth2", teeth2)
    a_n, beta = _pressure(pressure_angle), _helix(helix)
    rack = BasicRack(addendum, dedendum, root_radius)
    b = float("nan") if face_width is None else positive("face_width", face_width)
    mt, at = _transverse(m, a_n, beta)
    if internal and z2 <= z1:
        raise GearleverError(f"teeth2 (the ring) must exceed teeth1, got {z1} and {z2}")
    if center_distance is not None:
        if rack_mesh:
            a_w = positive("center_distance", center_distance)
            x1, x2 = (a_w - z1 * mt / 2) / m, 0.0
        else:
            x1, x2 = shifts_for_center_distance(
                center_distance, m, z1, z2, pressure_angle=a_n, helix=beta, internal=internal, split=split
            )
    else:
        x1 = finite("shift1", shift1)
        x2 = 0.0 if rack_mesh else finite("shift2", shift2)
    ha, hf = rack.addendum, rack.dedendum
    d1 = z1 * mt
    db1 = d1 * math.cos(at)
    if rack_mesh:
        awt = at
        a0 = d1 / 2
        a = d1 / 2 + x1 * m
        y, k = x1, 0.0
        d2 = db2 = da2 = df2 = dw2 = float("nan")
        dw1 = d1
        da1 = d1 + 2 * (ha + x1) * m
    else:
        d2 = z2 * mt
        db2 = d2 * math.cos(at)
        awt = working_pressure_angle(z1, z2, x1, x2, pressure_angle=a_n, helix=beta, internal=internal)
        zs = (z2 - z1) if internal else (z1 + z2)
        a0 = zs * mt / 2
        a = a0 * math.cos(at) / math.cos(awt)
        y = (a - a0) / m
        if internal:
            k = 0.0
            da1 = d1 + 2 * (ha + x1) * m
            da2 = d2 - 2 * (ha - x2) * m
            df2 = da2 + 2 * (ha + hf) * m
            dw1, dw2 = 2 * a * z1 / zs, 2 * a * z2 / zs
        else:
            k = (x1 + x2 - y) if tip_shortening else 0.0
            da1 = d1 + 2 * (ha + x1 - k) * m
            da2 = d2 + 2 * (ha + x2 - k) * m
            df2 = d2 - 2 * (hf - x2) * m
            dw1, dw2 = 2 * a * z1 / zs, 2 * a * z2 / zs
    df1 = d1 - 2 * (hf - x1) * m
    # contact ratios
    ga1 = math.sqrt(max(da1 * da1 - db1 * db1, 0.0)) / 2
    pbt = math.pi * mt * math.cos(at)
    if rack_mesh:
        g_len = ga1 - d1 / 2 * math.sin(at) + (ha - x1) * m / math.sin(at)
    else:
        ga2 = math.sqrt(max(da2 * da2 - db2 * db2, 0.0)) / 2
        g_len = (ga1 - ga2 + a * math.sin(awt)) if internal else (ga1 + ga2 - a * math.sin(awt))
    eps_a = g_len / pbt
    eps_b = b * math.sin(abs(beta)) / (math.pi * m)
    # thickness
    s1 = m * (math.pi / 2 + 2 * x1 * math.tan(a_n))
    s2 = m * (math.pi / 2 + (-2 if internal else 2) * x2 * math.tan(a_n))
    st1 = _tip_thickness_at(m, z1, x1, a_n, beta, da1, internal=False)
    if rack_mesh:
        st2 = m * (math.pi / 2 - 2 * ha * math.tan(a_n))
        s2 = m * math.pi / 2
    else:
        st2 = _tip_thickness_at(m, z2, x2, a_n, beta, da2, internal=internal)
    # undercut (a rack does not undercut; an internal gear is not cut by a rack: reported False)
    kw = {"pressure_angle": a_n, "helix": beta, "dedendum": hf, "root_radius": rack.root_radius}
    zmin1 = min_teeth_no_undercut(x1, **kw)
    xmin1 = min_shift_no_undercut(z1, **kw)
    if rack_mesh or internal:
        zmin2, xmin2, uc2 = 0, float("nan"), False
    else:
        zmin2, xmin2 = min_teeth_no_undercut(x2, **kw), min_shift_no_undercut(z2, **kw)
        uc2 = x2 < xmin2 - 1e-12
    uc1 = x1 < xmin1 - 1e-12
    # interference: the mate's tip past this gear's interference point T on the line of action
    t1 = d1 / 2 * math.sin(at) if rack_mesh else None
    if rack_mesh:
        int1 = (ha - x1) * m > d1 / 2 * math.sin(at) ** 2 + 1e-12 * m
        int2 = False
    elif internal:
        # pinion root: ring tip beyond T1 (ring tip inside the pinion's interference point)
        ga2_len = math.sqrt(max(da2 * da2 - db2 * db2, 0.0)) / 2
        int1 = ga2_len - a * math.sin(awt) < -1e-12 * m
        int2 = ga1 > ga2_len + 1e-12 * m  # pinion tip beyond the ring's interference point... see tip interference
        int2 = bool(da2 < db2 - 1e-12)
    else:
        ga2_len = math.sqrt(max(da2 * da2 - db2 * db2, 0.0)) / 2
        int1 = ga2_len > a * math.sin(awt) + 1e-12 * m
        int2 = ga1 > a * math.sin(awt) + 1e-12 * m
    del t1
    result = GearMesh(
        kind=kind,
        module=m,
        pressure_angle=a_n,
        helix=beta,
        transverse_module=mt,
        transverse_pressure_angle=at,
        teeth=np.array([z1, z2]),
        shift=np.array([x1, x2]),
        working_pressure_angle=awt,
        center_distance=a,
        reference_center_distance=a0,
        center_distance_modification=y,
        tip_shortening=k,
        reference_diameter=np.array([d1, d2]),
        base_diameter=np.array([db1, db2]),
        tip_diameter=np.array([da1, da2]),
        root_diameter=np.array([df1, df2]),
        working_diameter=np.array([dw1, dw2]),
        tooth_thickness=np.array([s1, s2]),
        tip_thickness=np.array([st1, st2]),
        contact_ratio_transverse=eps_a,
        contact_ratio_overlap=eps_b,
        contact_ratio_total=eps_a + eps_b,
        face_width=b,
        undercut=np.array([uc1, uc2]),
        min_teeth_no_undercut=np.array([zmin1, zmin2]),
        min_shift_no_undercut=np.array([xmin1, xmin2]),
        interference=np.array([bool(int1), bool(int2)]),
        addendum=ha,
        dedendum=hf,
        root_radius=rack.root_radius,
    )
    if check:
        if center_distance is None:
            _check_mesh(result)
        else:
            try:
                _check_mesh(result, largest=False)
            except GearleverError as exc:
                raise GearleverError(
                    f"center_distance {float(center_distance):.6g} is not a sound mesh with the shifts "
                    f"{x1:.4g}, {x2:.4g} that reach it ({split} split): {exc}"
                ) from None
    return result


def _tip_text(st: float, m: float) -> str:
    """The tip thickness in modules, or why there is none (the tip circle inside the base circle)."""
    if math.isfinite(st):
        return f"tip thickness {st / m:.4g} module < {MIN_TIP_THICKNESS}"
    return "no tip left (the tip circle lies inside the base circle)"


def _check_mesh(g: GearMesh, largest: bool = True) -> None:
    m = g.module
    for i in range(1 if g.kind == "rack" else 2):
        st = float(g.tip_thickness[i])
        if not st >= MIN_TIP_THICKNESS * m - 1e-12:
            internal = g.kind == "internal" and i == 1
            if internal:
                raise GearleverError(f"shift {g.shift[i]:.6g} points the ring's teeth: {_tip_text(st, m)}")
            if not largest:
                raise GearleverError(f"shift {g.shift[i]:.6g} points the tooth of gear {i + 1}: {_tip_text(st, m)}")
            largest = max_shift_for_tip(
                m,
                int(g.teeth[i]),
                pressure_angle=g.pressure_angle,
                helix=g.helix,
                addendum=g.addendum,
                tip_shortening=g.tip_shortening,
            )
            raise GearleverError(
                f"shift {g.shift[i]:.6g} points the tooth of gear {i + 1}: {_tip_text(st, m)}; "
                f"largest shift {largest:.4g}"
            )
    if not g.contact_ratio_transverse >= MIN_CONTACT_RATIO:
        teeth = f"{int(g.teeth[0])}" if g.kind == "rack" else f"{int(g.teeth[0])} and {int(g.teeth[1])}"
        shifts = f"{g.shift[0]:.4g}" if g.kind == "rack" else f"{g.shift[0]:.4g} and {g.shift[1]:.4g}"
        raise GearleverError(
            f"teeth {teeth} with shift {shifts} and addendum {g.addendum:.4g}: contact ratio "
            f"{g.contact_ratio_transverse:.4g} < 1, not a mesh"
        )
    if g.kind == "internal":
        tip = internal_interference(g)
        if tip.tip:
            kinds = " and ".join(k for k in ("involute", "trochoid") if getattr(tip, k))
            raise GearleverError(
                f"teeth {int(g.teeth[0])} and {int(g.teeth[1])}: the internal pair's tips interfere "
                f"({kinds} interference; margins {tip.involute_margin:.4g}, {tip.trochoid_margin:.4g})"
            )


@dataclass(frozen=True)
class InternalInterference(Result):
    """Tip interference of an internal pair: ``involute``, ``trochoid``, ``tip`` (either), margins (>= 0 clear).

    Examples
    --------
    >>> internal_interference(mesh(1.0, 20, 26, kind="internal", check=False)).tip
    True
    """

    involute: bool
    trochoid: bool
    tip: bool
    involute_margin: float
    trochoid_margin: float

    def __getitem__(self, key: str):
        """``r["tip"]`` as ``r.tip`` (the dict this function returned before it was a Result)."""
        return getattr(self, key)


@dataclass(frozen=True)
class Backlash(Result):
    """Backlash of a mesh: ``normal`` (along the line of action, normal section), ``circumferential``
    (transverse, on the working circle) and the ``working_pressure_angle`` at the changed centre distance.

    Examples
    --------
    >>> round(backlash(mesh(2.0, 20, 40), (0.05, 0.05)).circumferential, 6)
    0.1
    """

    normal: float
    circumferential: float
    working_pressure_angle: float

    def __getitem__(self, key: str):
        """``b["normal"]`` as ``b.normal`` (the dict this function returned before it was a Result)."""
        return getattr(self, key)


def internal_interference(g: GearMesh) -> InternalInterference:
    """Involute and trochoid interference of an internal pair (gear 2 the ring).

    Returns an :class:`InternalInterference`: ``involute``, ``trochoid`` and
    ``tip`` (either) and the margins ``involute_margin`` and ``trochoid_margin``
    (>= 0 is clear).

    Notes
    -----
    Involute interference: the ring's tip must not reach past the pinion's
    interference point, ``z_1/z_2 >= 1 - tan alpha_a2 / tan alpha_w``, and the
    ring's tip circle must lie outside its base circle.  Trochoid interference
    (the pinion tip hits the ring tip as it leaves the mesh): ``theta_1 z_1/z_2
    + inv alpha_w - inv alpha_a2 >= theta_2`` with ``cos theta_1 = (r_a2^2 -
    r_a1^2 - a^2)/(2 a r_a1) + inv alpha_a1 - inv alpha_w``... (the arc cosine
    plus ``inv alpha_a1 - inv alpha_w``), ``cos theta_2 = (a^2 + r_a2^2 - r_a1^2)/(2 a
    r_a2)`` (KHK, *Gear Technical Reference*, internal gears, interference;
    G. Niemann and H. Winter, *Maschinenelemente* II, 1983, 22.2).

    Examples
    --------
    >>> g = mesh(3.0, 16, 24, 0.0, 0.5, kind="internal", check=False)
    >>> internal_interference(g).trochoid
    False
    """
    if g.kind != "internal":
        raise GearleverError(f"kind must be internal, got {g.kind!r}")
    z1, z2 = int(g.teeth[0]), int(g.teeth[1])
    ra1, ra2 = g.tip_diameter / 2
    rb1, rb2 = g.base_diameter / 2
    a, aw = g.center_distance, g.working_pressure_angle
    below_base = ra2 < rb2
    aa2 = math.acos(min(1.0, rb2 / ra2))
    aa1 = math.acos(min(1.0, rb1 / ra1))
    inv_margin = z1 / z2 - (1 - math.tan(aa2) / math.tan(aw))
    c1 = (ra2 * ra2 - ra1 * ra1 - a * a) / (2 * a * ra1)
    c2 = (a * a + ra2 * ra2 - ra1 * ra1) / (2 * a * ra2)
    if abs(c1) > 1 or abs(c2) > 1:
        troch_margin = float("inf")  # the tip circles do not cross: the tips never meet
    else:
        th1 = math.acos(c1) + involute(aa1) - involute(aw)
        th2 = math.acos(c2)
        troch_margin = th1 * z1 / z2 + involute(aw) - involute(aa2) - th2
    involute_i = bool(below_base or inv_margin < -1e-12)
    trochoid_i = bool(troch_margin < -1e-12)
    return InternalInterference(involute_i, trochoid_i, involute_i or trochoid_i, inv_margin, troch_margin)


def max_mating_teeth(teeth: int, *, pressure_angle: float = _DEG20, addendum: float = 1.0) -> int | None:
    """The largest gear that meshes with a standard pinion of ``teeth`` without interference (None: any, a rack too).

    Notes
    -----
    The gear's tip must not pass the pinion's interference point:
    ``N_G <= (N_P^2 sin^2 phi - 4 k^2)/(4 k - 2 N_P sin^2 phi)`` (k the addendum
    in modules), R. G. Budynas and J. K. Nisbett, *Shigley's Mechanical
    Engineering Design*, 9th ed., 2011, eq. (13-12).  When ``N_P >= 2k/sin^2
    phi`` every gear and the rack fit (eq. 13-13).

    Examples
    --------
    >>> max_mating_teeth(13), max_mating_teeth(16), max_mating_teeth(18)
    (16, 101, None)
    """
    n = _teeth("teeth", teeth)
    phi = _pressure(pressure_angle)
    k = positive("addendum", addendum)
    s2 = math.sin(phi) ** 2
    den = 4 * k - 2 * n * s2
    if den <= 0:
        return None
    ng = (n * n * s2 - 4 * k * k) / den
    return int(math.floor(ng + 1e-9)) if ng >= 1 else 0


def min_pinion_teeth(ratio: float = 1.0, *, pressure_angle: float = _DEG20, addendum: float = 1.0) -> int:
    """The fewest pinion teeth without interference for a gear ratio ``ratio`` = N_G/N_P (inf: a rack).

    Notes
    -----
    ``N_P = 2k/((1 + 2m) sin^2 phi) (m + sqrt(m^2 + (1 + 2m) sin^2 phi))``,
    rounded up (Budynas and Nisbett, *Shigley's*, 9th ed., eq. 13-11; eq.
    13-10 is its ``m = 1`` case; the rack ``N_P = 2k/sin^2 phi``, eq. 13-13).

    Examples
    --------
    >>> min_pinion_teeth(1), min_pinion_teeth(4), min_pinion_teeth(math.inf)
    (13, 16, 18)
    """
    phi = _pressure(pressure_angle)
    k = positive("addendum", addendum)
    s2 = math.sin(phi) ** 2
    if ratio == math.inf:
        npn = 2 * k / s2
    else:
        mg = positive("ratio", ratio)
        npn = 2 * k / ((1 + 2 * mg) * s2) * (mg + math.sqrt(mg * mg + (1 + 2 * mg) * s2))
    return math.ceil(npn - 1e-9)


def backlash(
    g: GearMesh, thickness_allowance: tuple[float, float] = (0.0, 0.0), center_distance_change: float = 0.0
) -> Backlash:
    """Backlash of a mesh from tooth-thickness allowances and a centre-distance change.

    Parameters
    ----------
    g : the mesh (:func:`mesh`).
    thickness_allowance : (2,) reduction of each gear's normal tooth thickness (length, >= 0 thins the tooth).
    center_distance_change : ``delta a`` from the mesh's centre distance (length; > 0 opens an external mesh).

    Returns
    -------
    Backlash
        ``circumferential`` (transverse, on the working circle), ``normal`` (along the line of action,
        normal section) and ``working_pressure_angle`` at the changed centre distance.

    Notes
    -----
    With the pair at ``a + delta a`` the working pressure angle is ``cos
    alpha_wt' = a_0 cos alpha_t / (a + delta a)`` and the transverse
    circumferential backlash on the working circle of gear 1 is ``j_wt = d_w1'
    (inv alpha_wt' - inv alpha_wt0) (z_1 + z_2)/z_1 + (E_1 + E_2)/cos beta *
    d_w1'/d_1``... in closed form ``j_bt = (inv alpha_wt' - inv alpha_t) z_s
    m_t cos alpha_t - (s_bt1 + s_bt2 - p_bt)`` along the base tangent, where the
    tooth thicknesses are the generated ones less the allowances (ISO
    21771:2007, 5.7; ISO/TR 10064-2; KHK, *Gear Technical Reference*, backlash,
    ``j_n = 2 delta a sin alpha`` for a small change).

    Examples
    --------
    >>> g = mesh(2.0, 20, 40)
    >>> round(backlash(g, center_distance_change=0.1).normal, 6)
    0.068832
    """
    e1, e2 = (finite("thickness_allowance", v) for v in thickness_allowance)
    da = finite("center_distance_change", center_distance_change)
    mt, at, m, beta = g.transverse_module, g.transverse_pressure_angle, g.module, g.helix
    cbb = math.cos(math.atan(math.tan(beta) * math.cos(at)))  # cos beta_b
    allowance = (e1 + e2) * math.cos(at) / math.cos(beta)  # normal thinning -> transverse arc on the base circle
    if g.kind == "rack":
        awt = at
        jbt = 2 * da * math.sin(at) + allowance
    else:
        z1, z2 = (int(v) for v in g.teeth)
        x1, x2 = (float(v) for v in g.shift)
        a_new = g.center_distance + da
        c = g.reference_center_distance * math.cos(at) / a_new if a_new > 0 else 2.0
        if not 0 < c < 1:
            raise GearleverError(f"center_distance_change {da:.6g} leaves no working pressure angle")
        awt = math.acos(c)
        pbt = math.pi * mt * math.cos(at)
        tan_n = math.tan(at)  # x m_n tan alpha_t: the shift's share of the transverse thickness
        sbt1 = g.base_diameter[0] * ((math.pi / 2 * mt + 2 * x1 * m * tan_n) / g.reference_diameter[0] + involute(at))
        if g.kind == "internal":
            # the ring's space is the external tooth of the same shift
            ebt2 = g.base_diameter[1] * (
                (math.pi / 2 * mt + 2 * x2 * m * tan_n) / g.reference_diameter[1] + involute(at)
            )
            jbt = ebt2 - sbt1 - (z2 - z1) * mt * math.cos(at) * involute(awt)
        else:
            sbt2 = g.base_diameter[1] * (
                (math.pi / 2 * mt + 2 * x2 * m * tan_n) / g.reference_diameter[1] + involute(at)
            )
            jbt = (z1 + z2) * mt * math.cos(at) * involute(awt) + pbt - sbt1 - sbt2
        jbt += allowance
    return Backlash(float(jbt * cbb), float(jbt / math.cos(awt)), awt)


# --------------------------------------------------------------------------- planetary sets


@dataclass(frozen=True)
class PlanetaryGeometry(Result):
    """Assembly conditions of a simple planetary set with shifted gears (sun, planet, ring).

    Attributes
    ----------
    sun_planet, planet_ring : the two meshes (:class:`GearMesh`, unchecked).
    center_distance : (2,) working centre distances of sun-planet and planet-ring.
    coaxial : the two agree (to 1e-9 of the module).
    ring_shift_for_coaxial : the ring shift that makes them agree with the sun's and planet's shifts.
    equal_spacing : ``(z_s + z_r) / N`` is an integer.
    adjacency_clearance : ``2 a sin(pi/N) - d_a,planet`` (> 0: neighbouring planets clear).
    adjacent : ``adjacency_clearance > 0``.
    ok : all three hold.

    Examples
    --------
    >>> planetary_geometry(1.0, 12, 15, 42, 3).ok
    True
    """

    sun_planet: GearMesh
    planet_ring: GearMesh
    center_distance: np.ndarray
    coaxial: bool
    ring_shift_for_coaxial: float
    equal_spacing: bool
    adjacency_clearance: float
    adjacent: bool
    ok: bool


def planetary_geometry(
    module: float,
    sun: int,
    planet: int,
    ring: int,
    planets: int,
    shifts: tuple[float, float, float] = (0.0, 0.0, 0.0),
    *,
    pressure_angle: float = _DEG20,
    helix: float = 0.0,
    addendum: float = 1.0,
    dedendum: float = 1.25,
) -> PlanetaryGeometry:
    """Coaxial centre distances, equal spacing and adjacency of a simple planetary set with shifted gears.

    Notes
    -----
    Coaxial: the sun-planet (external) and planet-ring (internal) working
    centre distances are equal, each from its working pressure angle
    (:func:`mesh`); with unshifted gears this is ``z_r = z_s + 2 z_p``.  Equal
    spacing: ``(z_s + z_r)/N`` integer.  Adjacency: the planets' tip circles
    clear, ``2 a sin(pi/N) > d_a,p`` (J. E. Shigley and J. J. Uicker, *Theory
    of Machines and Mechanisms*, planetary trains; KHK, *Gear Technical
    Reference*, planetary gear assembly conditions; H. W. Mueller, *Epicyclic
    Drive Trains*, 1982, ch. 2).  These are the conditions
    :func:`gearlever.gears.planetary.design_planetary` checks for unshifted
    gears, here with the shifted geometry.

    Examples
    --------
    >>> p = planetary_geometry(1.0, 12, 15, 42, 3)
    >>> p.coaxial, p.equal_spacing, p.adjacent
    (True, True, True)
    >>> p = planetary_geometry(1.0, 12, 15, 43, 3)   # one tooth more on the ring: shift it to stay coaxial
    >>> round(p.ring_shift_for_coaxial, 4)
    -0.4215
    """
    zs, zp, zr = _teeth("sun", sun), _teeth("planet", planet), _teeth("ring", ring)
    n = positive_int("planets", planets)
    if n < 1 or n > 64:
        raise GearleverError(f"planets must be in [1, 64], got {n}")
    xs, xp, xr = (finite(k, v) for k, v in zip(("sun shift", "planet shift", "ring shift"), shifts))
    kw = {"pressure_angle": pressure_angle, "helix": helix, "addendum": addendum, "dedendum": dedendum, "check": False}
    sp = mesh(module, zs, zp, xs, xp, **kw)
    pr = mesh(module, zp, zr, xp, xr, kind="internal", **kw)
    a1, a2 = sp.center_distance, pr.center_distance
    coax = abs(a1 - a2) <= 1e-9 * sp.module
    # ring shift for coaxial: internal pair at the sun-planet centre distance, the planet's shift kept
    mt, at = sp.transverse_module, sp.transverse_pressure_angle
    c = (zr - zp) * mt / 2 * math.cos(at) / a1
    if 0 < c < 1:
        d = (involute(math.acos(c)) - involute(at)) * (zr - zp) / (2 * math.tan(sp.pressure_angle))
        xr_co = xp + d
    else:
        xr_co = float("nan")
    clearance = 2 * a1 * math.sin(math.pi / n) - float(sp.tip_diameter[1]) if n > 1 else float("inf")
    spacing = (zs + zr) % n == 0
    return PlanetaryGeometry(
        sun_planet=sp,
        planet_ring=pr,
        center_distance=np.array([a1, a2]),
        coaxial=bool(coax),
        ring_shift_for_coaxial=xr_co,
        equal_spacing=bool(spacing),
        adjacency_clearance=clearance,
        adjacent=bool(clearance > 0),
        ok=bool(coax and spacing and clearance > 0),
    )
