"""Tooth geometry of every mesh of a mechanism model, at its sketch and over its cycle.

:func:`mesh_geometry` gives the involute geometry of one pair at one or many
centre distances (working pressure angle, contact ratios, backlash, tip
diameters, undercut, involute interference); :func:`check_mechanism` applies it
to every ``[[meshes]]`` entry of a model: at the sketch, over the first
input's cycle (solved in one batch, the centre distance of each frame taken
from the solved gear centres), and over an adjusting slide's range of centre
distances when one is given.  A mesh that loses contact (total contact ratio
below 1), jams (no backlash: centre distance below the tight mesh of an
external pair, above it for an internal one), undercuts or interferes is
flagged, with the input angle where it first does.

The basic rack is ISO 53 profile A (addendum 1, dedendum 1.25 module).  The
model's ``module`` is the normal module, its ``pressure_angle`` the normal
pressure angle; helical quantities are taken in the transverse section.
Numeric core: numpy and the model only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.mechanism.schema import MechanismModel, MeshSpec

__all__ = ["ADDENDUM", "DEDENDUM", "MeshGeometry", "MeshCheck", "mesh_geometry", "check_mechanism", "involute"]

#: Addendum and dedendum coefficients of the ISO 53 basic rack (profile A).
ADDENDUM = 1.0
DEDENDUM = 1.25
#: Relative tolerance on a centre distance below which it counts as constant or tight.
_TIGHT = 1e-9


def involute(alpha):
    """``inv alpha = tan alpha - alpha`` (rad).

    >>> round(float(involute(math.radians(20.0))), 9)
    0.014904384
    """
    return np.tan(alpha) - alpha


@dataclass(frozen=True)
class MeshGeometry(Result):
    """Involute geometry of one gear pair at ``N`` centre distances (arrays ``(N,)``; per gear ``(2,)``).

    Attributes
    ----------
    center_distance : ndarray
        The centre distances examined (model units).
    tight_center_distance : float
        Centre distance of the tight (zero-backlash) mesh of the shifts.
    working_pressure_angle : ndarray
        Transverse working pressure angle (rad) at each centre distance.
    contact_ratio_transverse, contact_ratio_overlap, contact_ratio_total : ndarray
        The overlap ratio is 0 for spur gears or when no face width is given.
    backlash : ndarray
        Circumferential backlash on the working pitch circle (transverse, model
        units) of teeth without thickness allowance; negative: the teeth jam.
    reference_diameter, base_diameter, tip_diameter, root_diameter : ndarray
        Per gear ``(2,)``, for a ring its inside tip and root.
    tip_thickness : ndarray
        Per gear, normal tooth thickness at the tip.
    undercut : ndarray of bool
        Per gear: the rack cutting it undercuts (never for a ring).
    interference : ndarray of bool
        ``(N,)``: the involute of a gear's tip acts below the mate's base circle (and, for a ring
        at its tight centre distance, the trochoid interference of
        :func:`gearlever.gears.geometry.internal_interference`).
    """

    center_distance: np.ndarray
    tight_center_distance: float
    working_pressure_angle: np.ndarray
    contact_ratio_transverse: np.ndarray
    contact_ratio_overlap: np.ndarray
    contact_ratio_total: np.ndarray
    backlash: np.ndarray
    reference_diameter: np.ndarray
    base_diameter: np.ndarray
    tip_diameter: np.ndarray
    root_diameter: np.ndarray
    tip_thickness: np.ndarray
    undercut: np.ndarray
    interference: np.ndarray

    @property
    def jammed(self) -> np.ndarray:
        """``(N,)``: the centre distance is on the jamming side of the tight mesh."""
        return self.backlash < -_TIGHT * self.tight_center_distance

    @property
    def lost_contact(self) -> np.ndarray:
        """``(N,)``: total contact ratio below 1 (or no contact at all)."""
        return ~(self.contact_ratio_total >= 1.0)


def mesh_geometry(
    module: float,
    teeth,
    shift=(0.0, 0.0),
    internal=(False, False),
    pressure_angle: float = math.radians(20.0),
    helix: float = 0.0,
    face_width: float | None = None,
    center_distance=None,
    tip_shortening: bool = True,
) -> MeshGeometry:
    """Geometry of a pair of involute gears cut by the ISO 53 rack, at given centre distances.

    Parameters
    ----------
    module : float
        Normal module (> 0).
    teeth, shift, internal : pairs
        Tooth numbers, profile shift coefficients, and which gear is a ring (one at most).
    pressure_angle : float
        Normal pressure angle (rad), in (0, 60 deg).
    helix : float
        Helix angle (rad), in [0, 45 deg).
    face_width : float, optional
        Common face width (the overlap ratio needs it).
    center_distance : float or array, optional
        Default: the tight mesh.
    tip_shortening : bool
        Shorten the tips of an external pair to keep the rack's bottom clearance.

    Returns
    -------
    MeshGeometry

    Notes
    -----
    The tight mesh's diameters, tip thicknesses and undercut are
    :func:`gearlever.gears.geometry.mesh`'s; what changes with the centre
    distance is computed here for every centre distance at once.
    ISO 21771:2007 (KHK, *Gear Technical Reference*, sections 4.3-4.5 and
    5.1): ``cos alpha_wt = a_0 cos alpha_t / a`` with ``a_0 = m_t (z_1 +- z_2)
    / 2``; the transverse contact ratio ``eps_alpha = (sqrt(r_a1^2 - r_b1^2)
    +- sqrt(r_a2^2 - r_b2^2) -+ a sin alpha_wt) / p_bt`` (lower signs: ring
    second), ``eps_beta = b sin beta / (pi m_n)``; backlash on the working
    pitch circle ``j_wt = +-2 a (inv alpha_wt - inv alpha_wt,tight)``
    (from ``s_w = d_w (s / d + inv alpha_t - inv alpha_wt)``); undercut when
    ``h_a* - x > z sin^2 alpha_t / (2 cos beta)``; tip shortening ``k = x_1 +
    x_2 - y``, ``y = (a_tight - a_0) / m_n``.  Involute interference: the tip
    of one gear acts beyond the point where the line of action touches the
    mate's base circle.

    Examples
    --------
    >>> g = mesh_geometry(3.0, (12, 24), shift=(0.6, 0.36))     # KHK's shifted spur example
    >>> round(g.tight_center_distance, 4), round(math.degrees(float(g.working_pressure_angle[0])), 4)
    (56.4999, 26.0886)
    >>> [round(float(d), 4) for d in g.tip_diameter]           # addenda (1 + y - x_mate) m, tip shortened
    [44.8397, 79.3997]
    """
    if not module > 0:
        raise GearleverError(f"module must be positive, got {module!r}")
    z = np.array([int(t) for t in teeth], dtype=float)
    if z.shape != (2,) or (z < 1).any():
        raise GearleverError(f"teeth must be two positive integers, got {teeth!r}")
    x = np.array(shift, dtype=float)
    ring = np.array(internal, dtype=bool)
    if ring.all():
        raise GearleverError("internal: two internal gears cannot mesh")
    if not 0.0 < pressure_angle < math.radians(60.0):
        raise GearleverError(f"pressure_angle must be in (0, 60) deg, got {math.degrees(pressure_angle):g} deg")
    if not 0.0 <= helix < math.radians(45.0):
        raise GearleverError(f"helix must be in [0, 45) deg, got {math.degrees(helix):g} deg")
    is_internal = bool(ring.any())
    cb = math.cos(helix)
    mt = module / cb
    at = math.atan(math.tan(pressure_angle) / cb)
    sign = -1.0 if is_internal else 1.0
    # the tight mesh's per-gear geometry: gears.geometry.mesh (gear 2 is the ring of an internal pair)
    from gearlever.gears.geometry import internal_interference
    from gearlever.gears.geometry import mesh as tight_mesh

    order = [1, 0] if ring[0] else [0, 1]
    k_ring = int(np.argmax(ring)) if is_internal else None
    tight = tight_mesh(
        module,
        int(z[order[0]]),
        int(z[order[1]]),
        float(x[order[0]]),
        float(x[order[1]]),
        kind="internal" if is_internal else "external",
        pressure_angle=pressure_angle,
        helix=helix,
        face_width=face_width,
        tip_shortening=tip_shortening,
        check=False,
    )
    back = np.argsort(order)  # per-gear arrays back in the order given

    def given(arr):
        return np.asarray(arr, dtype=float)[back]

    d, db, da = given(tight.reference_diameter), given(tight.base_diameter), given(tight.tip_diameter)
    df, sa = given(tight.root_diameter), given(tight.tip_thickness)
    undercut = np.asarray(tight.undercut, dtype=bool)[back]
    a_tight = float(tight.center_distance)
    a0 = float(tight.reference_center_distance)
    inv_tight = float(involute(tight.working_pressure_angle))
    trochoid = bool(is_internal and internal_interference(tight)["trochoid"])
    a = np.atleast_1d(np.asarray(a_tight if center_distance is None else center_distance, dtype=float))
    if not (np.isfinite(a) & (a > 0)).all():
        raise GearleverError("center_distance must be positive and finite")
    cos_w = a0 * math.cos(at) / a
    with np.errstate(invalid="ignore"):
        aw = np.arccos(np.clip(cos_w, -1.0, 1.0))
    ra, rb = da / 2, db / 2
    with np.errstate(invalid="ignore"):
        g = np.sqrt(np.maximum(ra**2 - rb**2, 0.0))
    line = a * np.sin(aw)
    if is_internal:
        p, r = 1 - k_ring, k_ring
        approach = g[p] - g[r] + line
        interference = (g[r] < line) | (ra[r] < rb[r])
        if trochoid and np.isclose(a, a_tight, rtol=_TIGHT, atol=0).any():
            interference = interference | np.isclose(a, a_tight, rtol=_TIGHT, atol=0)
    else:
        approach = g[0] + g[1] - line
        interference = (g[0] > line) | (g[1] > line)
    pbt = np.pi * mt * math.cos(at)
    eps_a = np.maximum(approach, 0.0) / pbt
    eps_b = np.full_like(a, 0.0 if face_width is None else face_width * math.sin(helix) / (np.pi * module))
    backlash = sign * 2 * a * (involute(aw) - inv_tight)
    return MeshGeometry(
        center_distance=a,
        tight_center_distance=float(a_tight),
        working_pressure_angle=aw,
        contact_ratio_transverse=eps_a,
        contact_ratio_overlap=eps_b,
        contact_ratio_total=eps_a + eps_b,
        backlash=backlash,
        reference_diameter=d,
        base_diameter=db,
        tip_diameter=da,
        root_diameter=df,
        tip_thickness=sa,
        undercut=undercut,
        interference=np.asarray(interference, dtype=bool),
    )


@dataclass(frozen=True)
class MeshCheck(Result):
    """The check of one mesh of a model.

    Attributes
    ----------
    mesh : str
        The mesh's name (``"a-b"``).
    gears : tuple of str
    teeth, shift : tuple
    internal : bool
    module : float
        The model's module, or (none given) the first mesh's: ``2 a / (z_1 +- z_2)``.
    shift_sum : float
        ``x_1 + x_2`` (ring minus pinion for an internal pair) that makes the
        sketch's centre distance a tight mesh: ISO 21771's ``inv alpha_wt =
        inv alpha_t + 2 tan alpha_n (x_1 + x_2) / (z_1 + z_2)`` solved for the sum.
    sketch : MeshGeometry
        At the sketch's centre distance.
    over : str
        ``"constant"`` (the carrier keeps the centre distance), ``"cycle"`` (it
        changes over the first input's turn) or ``"adjustment"`` (a range given
        for an adjusting slide).
    angle : ndarray
        ``(N,)`` first input (rad) of each frame of the cycle, or NaN for an
        adjustment (empty for a constant distance).
    sweep : MeshGeometry or None
        Over the frames (cycle) or the adjustment's centre distances.
    flags : tuple of str
        Each problem found, with the angle or centre distance where it first appears.
    """

    mesh: str
    gears: tuple
    teeth: tuple
    shift: tuple
    internal: bool
    module: float
    shift_sum: float
    sketch: MeshGeometry
    over: str
    angle: np.ndarray
    sweep: MeshGeometry | None
    flags: tuple

    @property
    def ok(self) -> bool:
        return not self.flags


def _pair_geometry(model: MechanismModel, module: float, mesh: MeshSpec, alpha: float, center_distance) -> MeshGeometry:
    ga, gb = model.gears[mesh.a], model.gears[mesh.b]
    widths = [w for w in (ga.face_width, gb.face_width) if w is not None]
    try:
        return mesh_geometry(
            module,
            (ga.teeth, gb.teeth),
            shift=(ga.shift, gb.shift),
            internal=(ga.internal, gb.internal),
            pressure_angle=alpha,
            helix=ga.helix,
            face_width=min(widths) if widths else None,
            center_distance=center_distance,
        )
    except GearleverError as exc:
        raise GearleverError(f"meshes ({mesh.name}): {exc}") from None


def _shift_sum(model, module, mesh, alpha, a) -> float:
    ga, gb = model.gears[mesh.a], model.gears[mesh.b]
    internal = ga.internal or gb.internal
    zsum = abs(ga.teeth - gb.teeth) if internal else ga.teeth + gb.teeth
    cb = math.cos(ga.helix)
    at = math.atan(math.tan(alpha) / cb)
    cos_w = module * zsum * math.cos(at) / (2 * cb * a)
    if not 0 < cos_w <= 1:
        return math.nan
    return float(zsum * (involute(math.acos(cos_w)) - involute(at)) / (2 * math.tan(alpha)))


def _flags(geo: MeshGeometry, where) -> list:
    """The problems of ``geo``, each with ``where(i)``: the first sample index at which it shows."""
    out = []
    a = geo.center_distance
    for what, mask in (
        ("loses contact (contact ratio {v} < 1)", geo.lost_contact),
        ("jams (centre distance {a} on the tight side of {t})", geo.jammed),
        ("interferes (involute interference: a tip acts past the mate's interference point)", geo.interference),
    ):
        idx = np.flatnonzero(mask)
        if idx.size:
            i = int(idx[0])
            text = what.format(
                v=f"{geo.contact_ratio_total[i]:.4g}", a=f"{a[i]:.6g}", t=f"{geo.tight_center_distance:.6g}"
            )
            out.append(f"{text} {where(i)}")
    return out


def check_mechanism(mech, points: int = 360, adjust: dict | None = None) -> tuple:
    """Check every mesh of a mechanism: tooth geometry at the sketch, over the cycle, over an adjustment.

    Parameters
    ----------
    mech : gearlever.mechanism.Mechanism
        Without a ``module`` in the model, the first mesh's sketch centre
        distance sets it (``2 a / (z_1 +- z_2)``).
    points : int
        Frames of the cycle (the first input turns one turn from its sketch,
        the others held: :func:`gearlever.mechanism.sweep.sweep`'s rule), and
        samples of an adjustment's range.
    adjust : dict, optional
        ``{mesh name: (start, stop)}``: centre distances an adjusting slide
        sets the mesh to (model units), sampled ``points`` times, ends included.

    Returns
    -------
    tuple of MeshCheck
        One per ``[[meshes]]`` entry, in file order.

    Raises
    ------
    GearleverError
        An unknown mesh in ``adjust``, a range not positive.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> (c,) = check_mechanism(Mechanism.load(example_path("geared_fivebar.toml")), points=12)
    >>> c.mesh, c.over, round(float(c.sketch.contact_ratio_total[0]), 4), c.flags
    ('g1-g2', 'constant', 1.6052, ())
    """
    from gearlever.mechanism.loads import pressure_angle_of

    model = mech.model
    module = model.module
    if module is None and model.meshes:
        first = model.meshes[0]
        module = 2.0 * model.pitch_radius(first.a) * math.cos(model.gears[first.a].helix) / model.gears[first.a].teeth
    adjust = dict(adjust or {})
    names = [m.name for m in model.meshes]
    for k, (lo, hi) in adjust.items():
        if k not in names:
            raise GearleverError(f"adjust: unknown mesh {k!r} (meshes: {', '.join(names) or 'none'})")
        if not (lo > 0 and hi > 0 and math.isfinite(lo) and math.isfinite(hi)):
            raise GearleverError(f"adjust: the centre distances of mesh {k!r} must be positive, got {lo:g}, {hi:g}")
    alpha = pressure_angle_of(model)
    moving = any(model.gears[g].link != "ground" for m in model.meshes for g in (m.a, m.b))
    result = None
    if model.meshes and moving and model.inputs[0].kind == "link":
        q = np.broadcast_to(mech.sketch_inputs, (points, len(model.inputs))).copy()
        q[:, 0] += np.linspace(0.0, 2 * np.pi, points, endpoint=False)
        result = mech.solve(q)
    out = []
    for m in model.meshes:
        ga, gb = model.gears[m.a], model.gears[m.b]
        a_sketch = math.dist(model.points[ga.centre], model.points[gb.centre])
        sketch = _pair_geometry(model, module, m, alpha, a_sketch)
        flags = []
        if sketch.undercut.any():
            which = [g for g, u in zip((m.a, m.b), sketch.undercut) if u]
            flags.append(f"undercuts ({', '.join(which)}: fewer teeth than the rack allows at its shift)")
        thin = np.flatnonzero(sketch.tip_thickness < 0.2 * module)
        if thin.size:
            flags.append(f"pointed tip ({', '.join((m.a, m.b)[i] for i in thin)}: tip thickness under 0.2 module)")
        flags += _flags(sketch, lambda i: "at the sketch")
        over, angle, sweep = "constant", np.empty(0), None
        if m.name in adjust:
            lo, hi = adjust[m.name]
            over, angle = "adjustment", np.full(points, np.nan)
            sweep = _pair_geometry(model, module, m, alpha, np.linspace(lo, hi, points))
            flags += _flags(sweep, lambda i, g=sweep: f"at centre distance {g.center_distance[i]:.6g}")
        elif result is not None:
            ca, cb = result.point[ga.centre], result.point[gb.centre]
            dist = np.hypot(*(ca - cb).T)
            ok = result.closed & np.isfinite(dist)
            if ok.any() and np.ptp(dist[ok]) > _TIGHT * max(a_sketch, 1.0):
                over, angle = "cycle", result.q[ok, 0]
                sweep = _pair_geometry(model, module, m, alpha, dist[ok])
                flags += _flags(sweep, lambda i, t=angle: f"at {model.inputs[0].label} = {math.degrees(t[i]):.6g} deg")
        out.append(
            MeshCheck(
                mesh=m.name,
                gears=(m.a, m.b),
                teeth=(ga.teeth, gb.teeth),
                shift=(ga.shift, gb.shift),
                internal=ga.internal or gb.internal,
                module=float(module),
                shift_sum=_shift_sum(model, module, m, alpha, a_sketch),
                sketch=sketch,
                over=over,
                angle=angle,
                sweep=sweep,
                flags=tuple(dict.fromkeys(flags)),
            )
        )
    return tuple(out)
