"""Tooth strength: root bending and contact stress from a tangential tooth force, over a cycle.

Two levels, each a pure function of arrays (a tooth force ``(N,)`` gives
stresses ``(N,)``):

- Lewis bending stress ``sigma = K_v W_t / (F m Y)`` with the Lewis form
  factor ``Y`` from Shigley's table (:func:`lewis_form_factor`) or from the
  generated tooth itself (:func:`lewis_form_factor_geometry`: Lewis's inscribed
  parabola), and the Hertz contact stress of two cylinders of the flanks'
  radii of curvature at the pitch point (:func:`hertz_contact_stress`).
- AGMA 2001-D04 as presented by R. G. Budynas and J. K. Nisbett, *Shigley's
  Mechanical Engineering Design*, 9th ed., 2011, ch. 14 (eq. 14-15, 14-16):
  the factors ``K_o, K_v, K_s, K_m (K_H), K_B`` and the bending geometry factor
  ``J`` are inputs (``J`` from Shigley's Fig. 14-6 / AGMA 908-B89); the pitting
  geometry factor ``I`` is computed (eq. 14-23), ``K_v`` can be computed from
  the quality number (eq. 14-27), ``K_s`` from Shigley's fit (sec. 14-10) and
  ``K_m`` by AGMA's empirical method (eq. 14-30), in inch units.  The
  strength side gives the allowables the stresses are compared with: the
  stress numbers ``S_t, S_c`` of through-hardened steel (Fig. 14-2, 14-5), the
  stress-cycle factors ``Y_N, Z_N`` (Fig. 14-14, 14-15), ``K_R`` (Table 14-10,
  eq. 14-38) and ``C_H`` (eq. 14-36, 14-37), combined by
  :func:`agma_allowable_stress` (eq. 14-17, 14-18).
- ISO 6336-2 method B's geometry factors of the contact stress: the zone
  factor ``Z_H``, the helix factor ``Z_beta``, the contact ratio factor
  ``Z_eps`` (the elasticity factor ``Z_E`` is :func:`elastic_coefficient`)
  and ISO 6336-3's virtual number of teeth.

:func:`mesh_stresses` turns the tooth forces that
:meth:`~gearlever.mechanism.Mechanism.inverse_dynamics` gives for every mesh
of a mechanism into these stresses per mesh and input angle, with safety
factors against allowables and the worst angle.

Units are whatever the caller's are, consistently: a force in N with lengths
in mm gives MPa; lbf with inches gives psi.

Numeric core: imports numpy, :mod:`tomllib` and the package's own modules;
never pandas or matplotlib.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from functools import cache

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite, nonnegative, positive
from gearlever.errors import GearleverError
from gearlever.gears import geometry as _geo

__all__ = [
    "lewis_form_factor",
    "lewis_form_factor_geometry",
    "lewis_bending_stress",
    "barth_velocity_factor",
    "agma_velocity_factor",
    "elastic_coefficient",
    "hertz_contact_stress",
    "agma_pitting_geometry_factor",
    "agma_size_factor",
    "AGMA_MESH_ALIGNMENT",
    "agma_load_distribution_factor",
    "agma_bending_stress",
    "agma_contact_stress",
    "AGMA_THROUGH_HARDENED",
    "AGMA_RELIABILITY",
    "agma_strength_number",
    "agma_stress_cycle_factor",
    "agma_reliability_factor",
    "agma_hardness_ratio_factor",
    "agma_allowable_stress",
    "iso_zone_factor",
    "iso_helix_factor",
    "iso_contact_ratio_factor",
    "iso_virtual_teeth",
    "safety_factor",
    "MeshStress",
    "mesh_stresses",
]

_DEG20 = math.radians(20.0)


@cache
def _published() -> dict:
    from gearlever.data import read_text

    return tomllib.loads(read_text("gear_published.toml"))


def _force(name: str, values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim > 1 or not np.all(np.isfinite(a)):
        raise GearleverError(f"{name} must be a finite number or a 1-D array of finite numbers")
    return a


def lewis_form_factor(teeth) -> float:
    """Lewis form factor ``Y`` of a 20 deg full-depth spur tooth, interpolated in Shigley's table.

    Parameters
    ----------
    teeth : number of teeth (12 to 400, or ``math.inf`` for a rack).

    Notes
    -----
    Budynas and Nisbett, *Shigley's Mechanical Engineering Design*, 9th ed.,
    Table 14-2 (20 deg, addendum 1/P, dedendum 1.25/P, root fillet 0.300/P;
    load at the tip), linear interpolation between its rows as the book does.
    The table is shipped in ``gear_published.toml``.

    Examples
    --------
    >>> lewis_form_factor(16), lewis_form_factor(23)
    (0.296, 0.334)
    """
    tab = _published()["lewis_form_factor"]
    zs, ys = tab["teeth"], tab["Y"]
    if teeth == math.inf:
        return float(tab["rack"])
    z = finite("teeth", teeth)
    if not zs[0] <= z <= zs[-1]:
        raise GearleverError(f"teeth must be in [{zs[0]}, {zs[-1]}] (or inf for a rack) for the table, got {teeth!r}")
    return round(float(np.interp(z, zs, ys)), 6)


def lewis_form_factor_geometry(
    teeth: int,
    shift: float = 0.0,
    *,
    pressure_angle: float = _DEG20,
    addendum: float = 1.0,
    dedendum: float = 1.25,
    root_radius: float = 0.38,
    tip_diameter: float | None = None,
    points: int = 400,
) -> float:
    """Lewis form factor ``Y`` of the generated tooth (module 1): Lewis's inscribed parabola.

    Notes
    -----
    The normal load at the tip corner meets the tooth's centreline at the
    load point; the parabola with its vertex there touching the root
    profile marks the critical section: ``x = min (s/2)^2 / l`` over the
    profile (``s`` the chordal thickness, ``l`` the height below the load
    point) and ``Y = 2 x / (3 m)`` (W. Lewis, 1892; Budynas and Nisbett,
    *Shigley's*, 9th ed., sec. 14-1, eq. 14-3).  The radial component of the
    load is ignored, as in Lewis's and Shigley's table.  The profile is
    :func:`gearlever.gears.geometry.tooth_profile` (rack-generated involute and
    trochoidal fillet).  With Shigley's fillet 0.300 it lies 1 to 8 % below
    his Table 14-2 (whose teeth were not generated by this rack).

    Examples
    --------
    >>> round(lewis_form_factor_geometry(30, root_radius=0.3), 3)
    0.355
    """
    p = _geo.tooth_profile(
        1.0,
        teeth,
        shift,
        pressure_angle=pressure_angle,
        addendum=addendum,
        dedendum=dedendum,
        root_radius=root_radius,
        tip_diameter=tip_diameter,
        points=points,
    )
    pts = p.points
    i0, i1 = p.flank
    q = pts[i1 - 1]  # tip corner of the flank at negative y
    R = float(np.hypot(q[0], q[1]))
    e = math.sqrt(max((R / p.base_radius) ** 2 - 1.0, 0.0))
    thq = abs(math.atan2(q[1], q[0]))
    tht = thq - math.atan(e)  # the normal at the tip touches the base circle there
    qp = np.array([R * math.cos(thq), R * math.sin(thq)])
    t = np.array([p.base_radius * math.cos(tht), p.base_radius * math.sin(tht)])
    d = t - qp
    u_load = qp[0] - qp[1] / d[1] * d[0]
    half = pts[pts[:, 1] < 0]
    l_arm = u_load - half[:, 0]
    ok = l_arm > 1e-9
    x = float(np.min(half[ok, 1] ** 2 / l_arm[ok]))
    return 2.0 * x / 3.0


def lewis_bending_stress(tangential_force, face_width: float, module: float, form_factor: float, velocity_factor=1.0):
    """Lewis root bending stress ``sigma = K_v W_t / (F m Y)`` for each tooth force.

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-7 (``K_v W_t P / (F
    Y)``; ``P = 1/m``).  Returns the magnitude for each force (the sign of
    ``W_t`` only gives the flank).

    Examples
    --------
    >>> round(float(lewis_bending_stress(364.0, 1.5, 1 / 8, 0.296, 1.524)), 0)
    9995.0
    """
    w = _force("tangential_force", tangential_force)
    b = positive("face_width", face_width)
    m = positive("module", module)
    y = positive("form_factor", form_factor)
    kv = _force("velocity_factor", velocity_factor)
    return kv * np.abs(w) / (b * m * y)


_BARTH = {"cast": 600.0, "cut": 1200.0}


def barth_velocity_factor(pitch_line_velocity, profile: str = "cut", units: str = "ft/min"):
    """Barth's velocity factor of the Lewis equation.

    ``profile``: ``"cast"`` (600 + V)/600, ``"cut"`` (1200 + V)/1200, ``"hobbed"``
    (50 + sqrt V)/50, ``"ground"`` sqrt((78 + sqrt V)/78), V in ft/min; in m/s
    (``units="m/s"``) the constants 3.05, 6.1, 3.56 and 5.56.

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-4 (a)-(d) and 14-5 (a)-(d).

    Examples
    --------
    >>> round(float(barth_velocity_factor(628.3)), 4)
    1.5236
    """
    v = np.abs(_force("pitch_line_velocity", pitch_line_velocity))
    si = {"ft/min": False, "m/s": True}.get(units)
    if si is None:
        raise GearleverError(f"units must be ft/min or m/s, got {units!r}")
    if profile == "cast":
        c = 3.05 if si else 600.0
        return (c + v) / c
    if profile == "cut":
        c = 6.1 if si else 1200.0
        return (c + v) / c
    if profile == "hobbed":
        c = 3.56 if si else 50.0
        return (c + np.sqrt(v)) / c
    if profile == "ground":
        c = 5.56 if si else 78.0
        return np.sqrt((c + np.sqrt(v)) / c)
    raise GearleverError(f"profile must be cast, cut, hobbed or ground, got {profile!r}")


def agma_velocity_factor(pitch_line_velocity, quality: int, units: str = "ft/min"):
    """AGMA dynamic factor ``K_v = ((A + sqrt V)/A)^B``, ``A = 50 + 56 (1 - B)``, ``B = 0.25 (12 - Q_v)^(2/3)``.

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-27 (V in ft/min; in m/s
    ``sqrt(200 V)``), quality numbers ``Q_v`` 6 to 11.

    Examples
    --------
    >>> round(float(agma_velocity_factor(1000.0, 6)), 3)
    1.42
    """
    v = np.abs(_force("pitch_line_velocity", pitch_line_velocity))
    if isinstance(quality, bool) or not isinstance(quality, (int, np.integer)) or not 3 <= quality <= 12:
        raise GearleverError(f"quality must be an integer in [3, 12], got {quality!r}")
    if units not in ("ft/min", "m/s"):
        raise GearleverError(f"units must be ft/min or m/s, got {units!r}")
    b = 0.25 * (12 - quality) ** (2.0 / 3.0)
    a = 50.0 + 56.0 * (1.0 - b)
    sv = np.sqrt(200.0 * v) if units == "m/s" else np.sqrt(v)
    return ((a + sv) / a) ** b


def elastic_coefficient(e1: float, nu1: float, e2: float | None = None, nu2: float | None = None) -> float:
    """Elastic coefficient ``C_p = sqrt(1 / (pi ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)))``.

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-13.  Steel on steel
    (E = 30 Mpsi, nu = 0.3) gives 2290 psi^(1/2) (Table 14-8 prints 2300).

    Examples
    --------
    >>> round(elastic_coefficient(30e6, 0.3))
    2291
    """
    e1 = positive("e1", e1)
    n1 = finite("nu1", nu1)
    e2 = e1 if e2 is None else positive("e2", e2)
    n2 = n1 if nu2 is None else finite("nu2", nu2)
    for name, n in (("nu1", n1), ("nu2", n2)):
        if not 0.0 <= n < 0.5:
            raise GearleverError(f"{name} must be in [0, 0.5), got {n!r}")
    return math.sqrt(1.0 / (math.pi * ((1 - n1 * n1) / e1 + (1 - n2 * n2) / e2)))


def hertz_contact_stress(
    tangential_force,
    face_width: float,
    pinion_diameter: float,
    gear_diameter: float,
    elastic_coefficient: float,
    pressure_angle: float = _DEG20,
    velocity_factor=1.0,
    internal: bool = False,
):
    """Hertz contact stress at the pitch point ``sigma_C = C_p sqrt(K_v W_t/(F cos phi) (1/r_1 +- 1/r_2))``.

    ``r_i = d_i sin(phi) / 2`` are the flanks' radii of curvature at the pitch
    point; an internal gear's curvature is subtracted (``gear_diameter`` the ring's).
    Returns the magnitude (Shigley writes it negative, a compression).

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-14 (Hertz's line contact, eq. 3-74).

    Examples
    --------
    >>> round(float(hertz_contact_stress(380.0, 1.5, 2.0, 6.25, 1817.0, velocity_factor=1.52)))
    72259
    """
    w = _force("tangential_force", tangential_force)
    b = positive("face_width", face_width)
    d1 = positive("pinion_diameter", pinion_diameter)
    d2 = positive("gear_diameter", gear_diameter)
    cp = positive("elastic_coefficient", elastic_coefficient)
    phi = finite("pressure_angle", pressure_angle)
    kv = _force("velocity_factor", velocity_factor)
    r1, r2 = d1 * math.sin(phi) / 2, d2 * math.sin(phi) / 2
    curv = 1 / r1 - 1 / r2 if internal else 1 / r1 + 1 / r2
    if curv <= 0:
        raise GearleverError("gear_diameter must exceed pinion_diameter for an internal pair")
    return cp * np.sqrt(kv * np.abs(w) / (b * math.cos(phi)) * curv)


def agma_pitting_geometry_factor(
    pressure_angle: float, ratio: float, *, internal: bool = False, load_sharing: float = 1.0
) -> float:
    """AGMA surface-strength geometry factor ``I = cos phi_t sin phi_t / (2 m_N) m_G/(m_G +- 1)``.

    ``ratio`` is ``m_G = N_G / N_P``; ``load_sharing`` is ``m_N`` (1 for spur gears;
    ``p_N / (0.95 Z)`` for helical gears, Shigley eq. 14-21).

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-23 (minus sign for internal gears).

    Examples
    --------
    >>> round(agma_pitting_geometry_factor(math.radians(20), 52 / 17), 4)
    0.1211
    """
    phi = finite("pressure_angle", pressure_angle)
    mg = positive("ratio", ratio)
    mn = positive("load_sharing", load_sharing)
    if internal and mg <= 1:
        raise GearleverError(f"ratio must exceed 1 for an internal pair, got {mg!r}")
    return math.cos(phi) * math.sin(phi) / (2 * mn) * mg / (mg - 1 if internal else mg + 1)


def agma_size_factor(face_width: float, form_factor: float, diametral_pitch: float) -> float:
    """AGMA size factor ``K_s = 1.192 (F sqrt(Y) / P)^0.0535``, inch units.

    Parameters
    ----------
    face_width : ``F`` (in).
    form_factor : the Lewis form factor ``Y`` (:func:`lewis_form_factor`).
    diametral_pitch : ``P`` (teeth/in).

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., sec. 14-10, eq. (a) (AGMA
    2001-D04 leaves ``K_s`` to the designer; this is Shigley's fit of it to
    the tooth's size through the Lewis form factor).

    Examples
    --------
    >>> round(agma_size_factor(1.5, 0.303, 10.0), 3)
    1.043
    """
    f = positive("face_width", face_width)
    y = positive("form_factor", form_factor)
    p = positive("diametral_pitch", diametral_pitch)
    return 1.192 * (f * math.sqrt(y) / p) ** 0.0535


#: Mesh alignment constants ``(A, B, C)`` of ``C_ma = A + B F + C F^2`` (F in inches), by gearing condition.
AGMA_MESH_ALIGNMENT = {
    "open": (0.247, 0.0167, -0.765e-4),
    "commercial": (0.127, 0.0158, -0.930e-4),
    "precision": (0.0675, 0.0128, -0.926e-4),
    "extra-precision": (0.00360, 0.0102, -0.822e-4),
}


def agma_load_distribution_factor(
    face_width: float,
    pinion_diameter: float,
    *,
    condition: str = "commercial",
    crowned: bool = False,
    straddle_offset: float = 0.0,
    adjusted: bool = False,
) -> float:
    """AGMA load-distribution factor ``K_m = 1 + C_mc (C_pf C_pm + C_ma C_e)``, inch units.

    Parameters
    ----------
    face_width : ``F`` (in, at most 40).
    pinion_diameter : ``d_P`` (in).
    condition : the gearing's ``C_ma`` row, one of :data:`AGMA_MESH_ALIGNMENT` (open gearing, commercial
        enclosed, precision enclosed, extra-precision enclosed).
    crowned : crowned teeth, ``C_mc = 0.8`` (else 1).
    straddle_offset : ``S_1 / S``, the pinion's offset from the middle of its bearing span over the span;
        ``C_pm = 1.1`` from 0.175 on (else 1).
    adjusted : the mesh adjusted at assembly or lapped, ``C_e = 0.8`` (else 1).

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-30 to 14-35 and Table
    14-9 (AGMA 2001-D04's empirical method, uncrowned or crowned spur gears
    with ``F/d_P <= 2``): ``C_pf = F/(10 d) - 0.025`` (F <= 1 in), ``F/(10 d) -
    0.0375 + 0.0125 F`` (1 < F <= 17), ``F/(10 d) - 0.1109 + 0.0207 F -
    0.000228 F^2`` (17 < F <= 40), with ``F/(10 d)`` at least 0.05; ``C_ma = A
    + B F + C F^2``.

    Examples
    --------
    >>> round(agma_load_distribution_factor(1.5, 1.7), 2)
    1.22
    """
    f = positive("face_width", face_width)
    d = positive("pinion_diameter", pinion_diameter)
    if f > 40.0:
        raise GearleverError(f"face_width must be at most 40 in for the empirical method, got {f!r}")
    if condition not in AGMA_MESH_ALIGNMENT:
        raise GearleverError(f"condition must be one of {', '.join(AGMA_MESH_ALIGNMENT)}, got {condition!r}")
    s = finite("straddle_offset", straddle_offset)
    if not 0.0 <= s < 0.5:
        raise GearleverError(f"straddle_offset must be in [0, 0.5), got {s!r}")
    ratio = max(f / (10.0 * d), 0.05)
    if f <= 1.0:
        cpf = ratio - 0.025
    elif f <= 17.0:
        cpf = ratio - 0.0375 + 0.0125 * f
    else:
        cpf = ratio - 0.1109 + 0.0207 * f - 0.000228 * f * f
    a, b, c = AGMA_MESH_ALIGNMENT[condition]
    cma = a + b * f + c * f * f
    cmc = 0.8 if crowned else 1.0
    cpm = 1.1 if s >= 0.175 else 1.0
    ce = 0.8 if adjusted else 1.0
    return 1.0 + cmc * (cpf * cpm + cma * ce)


def agma_bending_stress(
    tangential_force,
    face_width: float,
    module: float,
    geometry_factor: float,
    *,
    overload: float = 1.0,
    dynamic=1.0,
    size: float = 1.0,
    load_distribution: float = 1.0,
    rim_thickness: float = 1.0,
):
    """AGMA bending stress ``sigma = W_t K_o K_v K_s K_m K_B / (F m J)``.

    ``module`` is the transverse module (``1/P_d`` in inches for US units),
    ``geometry_factor`` is ``J`` (Shigley Fig. 14-6), ``overload, dynamic, size,
    load_distribution, rim_thickness`` are ``K_o, K_v, K_s, K_m (K_H), K_B``.

    Notes
    -----
    AGMA 2001-D04 as in Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-15
    (``W_t K_o K_v K_s (P_d/F) (K_m K_B / J)``; SI ``(1/(b m_t)) (K_H K_B / Y_J)``).

    Examples
    --------
    >>> round(float(agma_bending_stress(1000.0, 1.0, 0.1, 0.3, dynamic=1.2)))
    40000
    """
    w = _force("tangential_force", tangential_force)
    b = positive("face_width", face_width)
    m = positive("module", module)
    j = positive("geometry_factor", geometry_factor)
    kv = _force("dynamic", dynamic)
    k = positive("overload", overload) * positive("size", size) * positive("load_distribution", load_distribution)
    k *= positive("rim_thickness", rim_thickness)
    return np.abs(w) * kv * k / (b * m * j)


def agma_contact_stress(
    tangential_force,
    face_width: float,
    pinion_diameter: float,
    geometry_factor: float,
    elastic_coefficient: float,
    *,
    overload: float = 1.0,
    dynamic=1.0,
    size: float = 1.0,
    load_distribution: float = 1.0,
    surface_condition: float = 1.0,
):
    """AGMA contact stress ``sigma_c = C_p sqrt(W_t K_o K_v K_s K_m C_f / (d_P F I))``.

    Notes
    -----
    AGMA 2001-D04 as in Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-16
    (``I`` from :func:`agma_pitting_geometry_factor`; ``C_f`` the surface condition factor).

    Examples
    --------
    >>> round(float(agma_contact_stress(1000.0, 1.0, 2.0, 0.1, 2300.0)))
    162635
    """
    w = _force("tangential_force", tangential_force)
    b = positive("face_width", face_width)
    d = positive("pinion_diameter", pinion_diameter)
    i = positive("geometry_factor", geometry_factor)
    cp = positive("elastic_coefficient", elastic_coefficient)
    kv = _force("dynamic", dynamic)
    k = positive("overload", overload) * positive("size", size) * positive("load_distribution", load_distribution)
    k *= positive("surface_condition", surface_condition)
    return cp * np.sqrt(np.abs(w) * kv * k / (d * b * i))


#: AGMA allowable stress numbers of through-hardened steel, ``S = a H_B + b`` by metallurgical grade:
#: ``{kind: {grade: ((a, b) in psi, (a, b) in MPa)}}`` (Shigley 9th ed. Fig. 14-2 bending, Fig. 14-5 contact).
AGMA_THROUGH_HARDENED = {
    "bending": {1: ((77.3, 12800.0), (0.533, 88.3)), 2: ((102.0, 16400.0), (0.703, 113.0))},
    "contact": {1: ((322.0, 29100.0), (2.22, 200.0)), 2: ((349.0, 34300.0), (2.41, 237.0))},
}

#: AGMA reliability factor ``K_R`` at the reliabilities of Shigley 9th ed. Table 14-10.
AGMA_RELIABILITY = {0.9999: 1.50, 0.999: 1.25, 0.99: 1.00, 0.90: 0.85, 0.50: 0.70}


def _choice(name: str, value, options) -> None:
    if value not in options:
        raise GearleverError(f"{name} must be one of {', '.join(map(str, options))}, got {value!r}")


def agma_strength_number(hardness: float, *, kind: str = "bending", grade: int = 1, units: str = "psi") -> float:
    """AGMA allowable bending (``S_t``) or contact (``S_c``) stress number of through-hardened steel.

    Parameters
    ----------
    hardness : the Brinell hardness ``H_B`` of the tooth (core for bending, surface for contact), 150 to 450.
    kind : ``"bending"`` (``S_t``) or ``"contact"`` (``S_c``).
    grade : the AGMA metallurgical grade, 1 or 2.
    units : ``"psi"`` or ``"MPa"``.

    Notes
    -----
    AGMA 2001-D04 Figures 3 and 4 as in Budynas and Nisbett, *Shigley's*, 9th
    ed., Fig. 14-2 (``S_t = 77.3 H_B + 12 800`` psi grade 1, ``102 H_B + 16 400``
    grade 2) and Fig. 14-5 (``S_c = 322 H_B + 29 100`` psi grade 1, ``349 H_B +
    34 300`` grade 2), with their MPa forms; for 10^7 cycles and 99 % reliability.

    Examples
    --------
    >>> round(agma_strength_number(240)), round(agma_strength_number(240, kind="contact"))
    (31352, 106380)
    """
    _choice("kind", kind, AGMA_THROUGH_HARDENED)
    _choice("grade", grade, (1, 2))
    _choice("units", units, ("psi", "MPa"))
    hb = finite("hardness", hardness)
    if not 150.0 <= hb <= 450.0:
        raise GearleverError(f"hardness must be a Brinell hardness from 150 to 450 (AGMA's line), got {hb!r}")
    a, b = AGMA_THROUGH_HARDENED[kind][grade][0 if units == "psi" else 1]
    return a * hb + b


def agma_stress_cycle_factor(cycles: float, *, kind: str = "bending", curve: str = "upper") -> float:
    """AGMA stress-cycle factor ``Y_N`` (bending) or ``Z_N`` (pitting) beyond 10^7 load cycles.

    Parameters
    ----------
    cycles : the number of load cycles ``N`` of the tooth, at least 10^7 (where the curves of every hardness
        merge).
    kind : ``"bending"`` (``Y_N``) or ``"contact"`` (``Z_N``).
    curve : bending only: ``"upper"`` (``1.3558 N^-0.0178``, general use) or ``"lower"``
        (``1.6831 N^-0.0323``, critical service).

    Notes
    -----
    AGMA 2001-D04 Figures 18 and 19 as in Budynas and Nisbett, *Shigley's*, 9th
    ed., Fig. 14-14 (``Y_N``) and Fig. 14-15 (``Z_N = 1.4488 N^-0.023``).  Below
    10^7 cycles the curves depend on the hardness and the heat treatment; they
    are not modelled (refused).

    Examples
    --------
    >>> round(agma_stress_cycle_factor(1e8), 3), round(agma_stress_cycle_factor(1e8, kind="contact"), 3)
    (0.977, 0.948)
    """
    _choice("kind", kind, AGMA_THROUGH_HARDENED)
    _choice("curve", curve, ("upper", "lower"))
    n = finite("cycles", cycles)
    if n < 1e7:
        raise GearleverError(f"cycles must be at least 1e7 (the curves below depend on the material), got {n!r}")
    if kind == "contact":
        if curve != "upper":
            raise GearleverError("curve must be 'upper' for the contact factor Z_N (one curve beyond 1e7 cycles)")
        return 1.4488 * n**-0.023
    return 1.3558 * n**-0.0178 if curve == "upper" else 1.6831 * n**-0.0323


def agma_reliability_factor(reliability: float) -> float:
    """AGMA reliability factor ``K_R`` for a reliability ``R`` in [0.5, 0.9999].

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed.: at the reliabilities of Table
    14-10 (0.9999, 0.999, 0.99, 0.90, 0.50) the table's value (1.50, 1.25,
    1.00, 0.85, 0.70), as the book's examples use it; between them the fit of
    eq. 14-38, ``K_R = 0.658 - 0.0759 ln(1 - R)`` (0.5 < R < 0.99) and ``0.50 -
    0.109 ln(1 - R)`` (0.99 <= R <= 0.9999).

    Examples
    --------
    >>> agma_reliability_factor(0.9), round(agma_reliability_factor(0.95), 4)
    (0.85, 0.8854)
    """
    r = finite("reliability", reliability)
    if not 0.5 <= r <= 0.9999:
        raise GearleverError(f"reliability must be in [0.5, 0.9999], got {r!r}")
    if r in AGMA_RELIABILITY:
        return AGMA_RELIABILITY[r]
    return 0.658 - 0.0759 * math.log(1 - r) if r < 0.99 else 0.50 - 0.109 * math.log(1 - r)


def agma_hardness_ratio_factor(hardness_pinion: float, hardness_gear: float, ratio: float) -> float:
    """AGMA hardness-ratio factor ``C_H = 1 + A' (m_G - 1)`` of the gear of a through-hardened pair.

    Parameters
    ----------
    hardness_pinion, hardness_gear : Brinell hardnesses ``H_BP``, ``H_BG``.
    ratio : ``m_G = N_G / N_P``.

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-36 and 14-37:
    ``A' = 8.98e-3 (H_BP/H_BG) - 8.29e-3`` for ``1.2 <= H_BP/H_BG <= 1.7``, 0
    below, 0.00698 above.  The pinion's ``C_H`` is 1.

    Examples
    --------
    >>> round(agma_hardness_ratio_factor(240, 200, 52 / 17), 4)
    1.0051
    """
    h = positive("hardness_pinion", hardness_pinion) / positive("hardness_gear", hardness_gear)
    mg = positive("ratio", ratio)
    if h < 1.2:
        a = 0.0
    elif h <= 1.7:
        a = 8.98e-3 * h - 8.29e-3
    else:
        a = 0.00698
    return 1.0 + a * (mg - 1.0)


def agma_allowable_stress(
    strength: float,
    cycle_factor: float = 1.0,
    *,
    hardness_ratio: float = 1.0,
    temperature: float = 1.0,
    reliability: float = 1.0,
) -> float:
    """AGMA allowable stress ``S Y_N C_H / (K_T K_R)`` (the safety factor is then allowable / stress).

    Parameters
    ----------
    strength : the stress number ``S_t`` or ``S_c`` (:func:`agma_strength_number`).
    cycle_factor : ``Y_N`` or ``Z_N`` (:func:`agma_stress_cycle_factor`).
    hardness_ratio : ``C_H`` for a contact allowable (:func:`agma_hardness_ratio_factor`; 1 for bending).
    temperature : ``K_T`` (1 below 250 F).
    reliability : ``K_R`` (:func:`agma_reliability_factor`).

    Notes
    -----
    AGMA 2001-D04 as in Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-17
    (``S_t Y_N / (S_F K_T K_R)``) and eq. 14-18 (``S_c Z_N C_H / (S_H K_T K_R)``)
    with ``S_F = S_H = 1``: :func:`safety_factor` divides it by the stress
    (eq. 14-41, 14-42).

    Examples
    --------
    >>> round(agma_allowable_stress(31350.0, 0.977, reliability=0.85))
    36034
    """
    s = positive("strength", strength) * positive("cycle_factor", cycle_factor)
    s *= positive("hardness_ratio", hardness_ratio)
    return s / (positive("temperature", temperature) * positive("reliability", reliability))


def iso_zone_factor(pressure_angle: float, helix: float, working_pressure_angle: float) -> float:
    """ISO 6336-2 zone factor ``Z_H = sqrt(2 cos beta_b cos alpha_wt / (cos^2 alpha_t sin alpha_wt))``.

    Parameters
    ----------
    pressure_angle : the normal pressure angle ``alpha_n`` (radians).
    helix : the helix angle ``beta`` (radians).
    working_pressure_angle : the transverse working pressure angle ``alpha_wt`` (radians) at the operating
        centre distance, as :attr:`GearMesh.working_pressure_angle <gearlever.gears.geometry.GearMesh>` gives it.

    Notes
    -----
    ISO 6336-2:2006, eq. 9 (method B), with ``tan alpha_t = tan alpha_n /
    cos beta`` and ``sin beta_b = sin beta cos alpha_n``.  It converts the
    tangential force at the reference circle into the normal force at the
    pitch point and the flanks' curvature there.

    Examples
    --------
    >>> round(iso_zone_factor(math.radians(20), 0.0, math.radians(20)), 4)
    2.4946
    """
    a_n = finite("pressure_angle", pressure_angle)
    beta = finite("helix", helix)
    a_w = finite("working_pressure_angle", working_pressure_angle)
    if not 0 < a_n < math.pi / 2 or not 0 < a_w < math.pi / 2:
        raise GearleverError("pressure_angle and working_pressure_angle must be between 0 and 90 deg")
    if not 0 <= abs(beta) < math.pi / 4:
        raise GearleverError(f"helix must be below 45 deg, got {math.degrees(beta)!r} deg")
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    beta_b = math.asin(math.sin(abs(beta)) * math.cos(a_n))
    return math.sqrt(2 * math.cos(beta_b) * math.cos(a_w) / (math.cos(a_t) ** 2 * math.sin(a_w)))


def iso_helix_factor(helix: float) -> float:
    """ISO 6336-2 helix angle factor for contact stress ``Z_beta = 1 / sqrt(cos beta)``.

    Notes
    -----
    ISO 6336-2:2006, eq. 33.

    Examples
    --------
    >>> round(iso_helix_factor(math.radians(15.8)), 5)
    1.01944
    """
    beta = finite("helix", helix)
    if not abs(beta) < math.pi / 4:
        raise GearleverError(f"helix must be below 45 deg, got {math.degrees(beta)!r} deg")
    return 1.0 / math.sqrt(math.cos(beta))


def iso_contact_ratio_factor(transverse: float, overlap: float = 0.0) -> float:
    """ISO 6336-2 contact ratio factor ``Z_eps`` from the transverse and overlap contact ratios.

    Notes
    -----
    ISO 6336-2:2006, eq. 31 and 32: ``sqrt((4 - eps_a)/3 (1 - eps_b) +
    eps_b/eps_a)`` for ``eps_b < 1`` (spur gears: ``sqrt((4 - eps_a)/3)``) and
    ``sqrt(1/eps_a)`` for ``eps_b >= 1``.

    Examples
    --------
    >>> round(iso_contact_ratio_factor(1.6), 4), round(iso_contact_ratio_factor(1.6, 1.2), 4)
    (0.8944, 0.7906)
    """
    ea = positive("transverse", transverse)
    eb = nonnegative("overlap", overlap)
    if eb >= 1.0:
        return math.sqrt(1.0 / ea)
    return math.sqrt((4.0 - ea) / 3.0 * (1.0 - eb) + eb / ea)


def iso_virtual_teeth(teeth: float, pressure_angle: float, helix: float) -> float:
    """Virtual number of teeth of a helical gear ``z_n = z / (cos^2 beta_b cos beta)`` (ISO 6336-3).

    Notes
    -----
    ISO 6336-3:2006, eq. 9 (``sin beta_b = sin beta cos alpha_n``); a spur gear's is its own.

    Examples
    --------
    >>> round(iso_virtual_teeth(17, math.radians(20), math.radians(15.8)), 3)
    18.905
    """
    z = positive("teeth", teeth)
    a_n = finite("pressure_angle", pressure_angle)
    beta = finite("helix", helix)
    if not abs(beta) < math.pi / 4:
        raise GearleverError(f"helix must be below 45 deg, got {math.degrees(beta)!r} deg")
    beta_b = math.asin(math.sin(abs(beta)) * math.cos(a_n))
    return z / (math.cos(beta_b) ** 2 * math.cos(beta))


def safety_factor(allowable: float, stress):
    """Safety factor ``S = allowable / stress`` (inf where the stress is zero).

    Notes
    -----
    Budynas and Nisbett, *Shigley's*, 9th ed., eq. 14-41 and 14-42 with the
    allowable already corrected (``S_t Y_N / (K_T K_R)``, ``S_c Z_N C_H / (K_T K_R)``).
    Compare a contact factor with a bending one through its square (sec. 14-19).

    Examples
    --------
    >>> safety_factor(30.0, [10.0, 0.0]).tolist()
    [3.0, inf]
    """
    a = positive("allowable", allowable)
    s = np.abs(_force("stress", stress))
    with np.errstate(divide="ignore"):
        return np.where(s > 0, a / np.where(s > 0, s, 1.0), np.inf)


# --------------------------------------------------------------------------- mechanisms


@dataclass(frozen=True)
class MeshStress(Result):
    """Stresses of one mesh over the input rows.

    Attributes
    ----------
    mesh : mesh name; ``gears`` its two gears.
    tangential_force : (N,) tangential tooth force (force unit).
    bending_stress : (N, 2) Lewis root bending stress of each gear.
    contact_stress : (N,) Hertz contact stress at the pitch point.
    bending_safety, contact_safety : (N, 2) and (N,) safety factors (NaN without allowables).
    worst_row : index of the row with the largest tooth force (its angle: ``angle[worst_row]``).
    angle : (N,) the first input's value at each row (rad or length).
    form_factor : (2,) Lewis ``Y`` of each gear (from the generated tooth).
    module, face_width : used.

    Examples
    --------
    >>> ms = MeshStress("m", ("a", "b"), np.array([10.0]), np.array([[1.0, 0.8]]), np.array([50.0]),
    ...                 np.array([[200.0, 250.0]]), np.array([18.0]), 0, np.array([0.0]), np.array([0.3, 0.35]),
    ...                 2.0, 10.0)
    >>> ms.bending_safety[0].tolist()
    [200.0, 250.0]
    """

    mesh: str
    gears: tuple
    tangential_force: np.ndarray
    bending_stress: np.ndarray
    contact_stress: np.ndarray
    bending_safety: np.ndarray
    contact_safety: np.ndarray
    worst_row: int
    angle: np.ndarray
    form_factor: np.ndarray
    module: float
    face_width: float


def _material(allowables, gear, mesh: str) -> tuple[float, float]:
    """(bending, contact) allowables of ``gear`` (a model Gear).

    In order: ``allowables`` given to :func:`mesh_stresses` (one dict
    ``{bending, contact}`` or per gear or mesh name), the gear's own
    ``allowables`` or ``material`` attribute when the model carries one (a
    dict with ``bending`` and ``contact``, read with ``getattr``/``get`` so
    models without them work), else NaN.
    """
    name = gear.name
    a = None
    if allowables is not None:
        if not isinstance(allowables, dict):
            raise GearleverError("allowables must be a dict {bending, contact} or {gear or mesh name: {...}}")
        a = allowables.get(name, allowables.get(mesh, allowables))
    else:
        for attr in ("allowables", "material"):
            v = getattr(gear, attr, None)
            if isinstance(v, dict) and ("bending" in v or "contact" in v):
                a = v
                break
    if a is None:
        return float("nan"), float("nan")
    if not isinstance(a, dict):
        raise GearleverError(f"allowables for {name} must be a dict with bending and contact")
    b = a.get("bending")
    c = a.get("contact")
    b = float("nan") if b is None else positive(f"allowables.{name}.bending", b)
    c = float("nan") if c is None else positive(f"allowables.{name}.contact", c)
    return b, c


def mesh_stresses(
    mech,
    result,
    module: float | None = None,
    face_width: float | None = None,
    allowables: dict | None = None,
    *,
    elastic_coefficient: float = 189.8,
    velocity_factor: float = 1.0,
    root_radius: float = 0.38,
) -> dict:
    """Lewis bending and Hertz contact stress of every mesh of a mechanism over its input rows.

    Parameters
    ----------
    mech : :class:`~gearlever.mechanism.Mechanism`.
    result : its :class:`~gearlever.mechanism.dynamics.InverseDynamics` (``mechanism forces``).
    module : the module; default the model's ``[mechanism] module`` (required one way or the other).
    face_width : default each gear's ``face_width`` in the model (the smaller of the pair), required otherwise.
    allowables : ``{"bending": S_b, "contact": S_c}`` for every gear, or per gear or mesh name
        ``{name: {"bending", "contact"}}``, in the stress unit; default the model's: its extra data's
        ``allowables``, else each gear's ``allowables`` or ``material`` (``{bending, contact}``) when the
        model carries them; NaN safety factors without any.
    elastic_coefficient : ``C_p`` (sqrt of the stress unit; 189.8 sqrt(MPa) for steel on steel).
    velocity_factor : ``K_v`` applied to every row.
    root_radius : the basic rack's root radius (modules) for the Lewis form factor.

    Returns
    -------
    dict mesh name -> :class:`MeshStress`.

    Notes
    -----
    The tangential tooth force of each mesh is the one the inverse dynamics
    computes (:attr:`InverseDynamics.mesh_tangential`, equilibrium of every
    link; its line-of-action force is ``|W_t| / cos phi``).  Bending stress
    per gear by :func:`lewis_bending_stress` with ``Y`` from
    :func:`lewis_form_factor_geometry` of the gear's teeth and shift (a ring's
    ``Y`` is that of an external gear of its teeth, unshifted: conservative,
    a ring's tooth is thicker at its root);
    contact stress by :func:`hertz_contact_stress` on the reference diameters
    at the model's pressure angle.  The worst row is the one of the largest
    ``|W_t|`` (both stresses grow with it).

    Examples
    --------
    >>> import numpy as np, gearlever
    >>> from gearlever.data import example_path
    >>> mech = gearlever.Mechanism.load(example_path("geared_fivebar.toml"))
    >>> res = mech.inverse_dynamics(np.linspace(0, 2 * np.pi, 13), 1.0, 0.0,
    ...                             loads=[{"link": "link4", "point": "C", "force": [0, -100.0]}])
    >>> s = mesh_stresses(mech, res, face_width=10.0)["g1-g2"]
    >>> s.worst_row, round(float(s.bending_stress[s.worst_row, 0]), 3)
    (3, 7.268)
    """
    model = mech.model
    m = module if module is not None else model.module
    if m is None:
        raise GearleverError("module must be given (or [mechanism] module in the model)")
    m = positive("module", m)
    tangential = getattr(result, "mesh_tangential", None)
    if tangential is None:
        raise GearleverError("result must be an InverseDynamics (mechanism forces) with mesh tooth forces")
    phi = float(getattr(result, "pressure_angle", _DEG20))
    extra = getattr(model, "extra", None)
    allow = allowables if allowables is not None else (extra.get("allowables") if isinstance(extra, dict) else None)
    q = np.asarray(result.q, dtype=float)
    angle = q[:, 0] if q.ndim == 2 else q
    out = {}
    for mesh in model.meshes:
        ga, gb = model.gears[mesh.a], model.gears[mesh.b]
        w = np.asarray(tangential[mesh.name], dtype=float)
        if face_width is not None:
            b = positive("face_width", face_width)
        else:
            widths = [getattr(g, "face_width", None) for g in (ga, gb)]
            widths = [v for v in widths if v is not None]
            if not widths:
                raise GearleverError(f"face_width must be given (or [gears] face_width for mesh {mesh.name})")
            b = min(widths)
        ys, sb, sc_allow, sb_allow = [], [], [], []
        for g in (ga, gb):
            y = lewis_form_factor_geometry(
                g.teeth, getattr(g, "shift", 0.0) if not g.internal else 0.0, root_radius=root_radius
            )
            ys.append(y)
            sb.append(lewis_bending_stress(w, b, m, y, velocity_factor))
            ab, ac = _material(allow, g, mesh.name)
            sb_allow.append(ab)
            sc_allow.append(ac)
        internal = ga.internal or gb.internal
        pin, gear = (ga, gb) if (gb.internal or (not ga.internal and ga.teeth <= gb.teeth)) else (gb, ga)
        d1, d2 = m * pin.teeth / math.cos(pin.helix), m * gear.teeth / math.cos(gear.helix)
        sc = hertz_contact_stress(w, b, d1, d2, elastic_coefficient, phi, velocity_factor, internal=internal)
        bending = np.column_stack(sb)
        with np.errstate(divide="ignore", invalid="ignore"):
            bs = np.column_stack([np.where(bending[:, i] > 0, sb_allow[i] / bending[:, i], np.inf) for i in range(2)])
            ac = np.nanmin(sc_allow) if not all(math.isnan(v) for v in sc_allow) else float("nan")
            cs = np.where(sc > 0, ac / np.where(sc > 0, sc, 1.0), np.inf)
        ok = np.asarray(getattr(result, "ok", np.ones(len(w), bool)), bool)
        absw = np.where(ok & np.isfinite(w), np.abs(w), -1.0)
        out[mesh.name] = MeshStress(
            mesh=mesh.name,
            gears=(ga.name, gb.name),
            tangential_force=w,
            bending_stress=bending,
            contact_stress=sc,
            bending_safety=bs,
            contact_safety=cs,
            worst_row=int(np.argmax(absw)),
            angle=angle,
            form_factor=np.array(ys),
            module=m,
            face_width=b,
        )
    return out
