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
    "MIN_TIP_THICKNESS",
    "involute",
    "inverse_involute",
    "BasicRack",
    "ToothProfile",
    "max_shift_for_tip",
    "tip_thickness",
    "tooth_profile",
    "tooth_outline",
]

#: Largest tooth number accepted (the outline has ~60 points a tooth).
MAX_TEETH = 10000
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
        raise GearleverError("root_radius too large: the cutter's tip fillets overlap")
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
        raise GearleverError("shift makes the internal gear's space pointed at its root")

    def fillet(rho):
        """The fillet arc of radius rho: roll of its flank end, arc points (R, theta), theta of its root end."""
        if rho <= 0:
            return e_root, np.zeros(0), np.zeros(0), point(e_root)[1]

        def centre(e):  # fillet centre inside the space, rho from the involute point of roll e along its normal
            R, th = point(e)
            q = cart(R, th)
            t_pt = cart(rb, th - math.atan(e))  # the involute's normal touches the base circle there
            nrm = (t_pt - q) / np.linalg.norm(t_pt - q)
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
    helix : helix angle ``beta`` (rad, |beta| < 45 deg); the profile is the transverse section.
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
            z, mt, at, sh, rack.addendum * m, rack.dedendum * m, rack.root_radius * m, ra, n, max(4, n // 2), 4
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
            z, mt, at, sh, rack.addendum * m, rack.dedendum * m, rack.root_radius * m, ra, n, max(4, n // 2), 4
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
        st = mt * (math.pi / 2 + 2 * x * math.tan(at))
    else:
        st = mt * (math.pi / 2 - 2 * x * math.tan(at))
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
