"""Kinetostatics and dynamics of a mechanism model: input torques, joint, guide and tooth forces, motion.

Each moving link ``k`` has the pose ``(x_k, y_k, theta_k)`` of its body frame
(see :mod:`gearlever.mechanism.constraints`).  With ``Q`` the generalized
force of the loads, the weights and the inertia forces (d'Alembert:
``-m a_G`` at the centre of mass, ``-I_G alpha``), the pairs' reactions
``A^T y`` and the drivers' torques or forces, every link is in equilibrium:

    ``A^T y = -Q``,   ``A = [J_pins; J_sliders; J_meshes; D_inputs]``.

Pins and sliders use the rows of
:func:`~gearlever.mechanism.constraints.constraint_jacobian`.  A gear mesh,
whose kinematic row there is Willis' angular relation, is written here as the
equivalent rolling condition at the pitch point ``P`` (equal tangential
velocity of the two pitch circles), so that its multiplier is the tangential
tooth force acting *at the teeth*, and the gears' bearings carry it; the
radial component ``|F_t| tan(pressure angle)`` (workless) is added after.
An input is a row of ones on its coordinate: its multiplier is the torque
(rotary input) or the force along the guide (slider input) the driver gives.

The system is solved point by point by SVD.  Where the constraints are
redundant (statically indeterminate, e.g. three planets sharing a load), the
multipliers that the equations do not fix are reported as NaN and their
labels listed in ``indeterminate``; the input forces are still fixed by
virtual work.  Imports numpy (scipy lazily, in :func:`simulate`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gearlever import _validate as V
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.mechanism.constraints import constraint_jacobian, constraint_labels
from gearlever.mechanism.loads import gravity_of, parse_loads, parse_masses, pressure_angle_of
from gearlever.mechanism.model import GROUND

__all__ = ["InverseDynamics", "Simulation", "inverse_dynamics", "reduced_inertia", "simulate"]

#: Relative singular-value threshold of the equilibrium system (rank decisions).
RANK_RTOL = 1e-10
#: A multiplier counts as undetermined when a null vector has a component above this.
NULL_TOL = 1e-8
#: Largest number of grid points of the reduced-inertia table used by :func:`simulate`.
SIM_GRID = 1440


def _cross(r, f):
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def _rot(theta, rho):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * rho[0] - s * rho[1], s * rho[0] + c * rho[1]], axis=-1)


def _perp(v):
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


class _Assembly:
    """Rows of the equilibrium system and the generalized forces at solved poses."""

    def __init__(self, mech, r):
        self.m = mech.model
        self.r = r
        self.col = {k: 3 * i for i, k in enumerate(self.m.moving)}
        self.n3 = 3 * len(self.m.moving)
        self.N = r.q.shape[0]
        pose = np.nan_to_num(r.pose)
        self.pose = pose
        self.O = pose[..., :2]  # (N, n, 2)
        self.theta = pose[..., 2]

    def origin(self, link):
        if link == GROUND:
            g = self.m.links[GROUND]
            return np.broadcast_to(np.array(g.origin, float), (self.N, 2))
        return self.O[:, self.col[link] // 3]

    def angle(self, link):
        if link == GROUND:
            return np.full(self.N, self.m.links[GROUND].angle0)
        return self.theta[:, self.col[link] // 3]

    def world(self, link, rho):
        """World position (N, 2) of the body-fixed point ``rho`` of ``link``."""
        return self.origin(link) + _rot(self.angle(link), rho)

    def add_force(self, G, link, P, f):
        """Add the generalized force of the force ``f`` (N, 2) at ``P`` (N, 2) on ``link`` to ``G`` (N, 3n)."""
        if link == GROUND:
            return
        c = self.col[link]
        G[:, c] += f[:, 0]
        G[:, c + 1] += f[:, 1]
        G[:, c + 2] += _cross(P - self.origin(link), f)

    def add_torque(self, G, link, tau):
        if link != GROUND:
            G[:, self.col[link] + 2] += tau


def _mesh_geometry(asm, mesh):
    """Pitch point, unit tangent (N, 2), pitch radii and which gear is internal."""
    m = asm.m
    ga, gb = m.gears[mesh.a], m.gears[mesh.b]
    A = asm.world(ga.link, m.links[ga.link].local[ga.centre])
    B = asm.world(gb.link, m.links[gb.link].local[gb.centre])
    d = B - A
    dist = np.linalg.norm(d, axis=1, keepdims=True)
    e = d / np.where(dist > 0, dist, 1.0)
    # operating pitch radii of this pair (profile-shifted pairs roll on them): r_a / r_b = z_a / z_b
    zsum = abs(ga.teeth - gb.teeth) if (ga.internal or gb.internal) else ga.teeth + gb.teeth
    ra, rb = dist * (ga.teeth / zsum), dist * (gb.teeth / zsum)
    if gb.internal:
        P = A - ra * e
    elif ga.internal:
        P = B + rb * e
    else:
        P = A + ra * e
    return A, B, P, _perp(e), ga, gb


@dataclass(frozen=True)
class InverseDynamics(Result):
    """Driver forces and every pair's reaction over the input rows.

    Attributes
    ----------
    q, qdot, qddot : (N, W) inputs and their rates.
    input_force : (N, W) torque (rotary input) or force along the guide (slider input) the drivers give.
    reaction : point -> (N, 2) force on the second link of the pin from the first (links as in
        :attr:`pins`); a point joining k > 2 links has one key per pair, ``"A:first-second"``.
    pins : key of :attr:`reaction` -> (first link, second link).
    slider_force : slider -> (N,) normal force of the guide on the sliding link, along the guide's
        normal ``n = R(90 deg) u`` (``u`` the guide direction turned with its link).
    slider_moment : slider -> (N,) moment of the guide on the sliding link.
    mesh_force : mesh -> (N,) tooth force along the line of action, ``|F_t| / cos(pressure angle)``.
    mesh_tangential : mesh -> (N,) tangential tooth force on the first gear along ``t = R(90 deg) e``,
        ``e`` the unit vector from its centre to the second gear's centre (the second gear gets ``-F_t t``).
    ground_force : (N, 2) total force of the frame on the mechanism (pins, guides, teeth, drivers); fixed
        by equilibrium even where its share among redundant pairs is not.
    ground_moment : (N,) total moment of the frame on the mechanism about the world origin.
    indeterminate : labels of the multipliers the equilibrium does not fix (redundant constraints).
    ok : (N,) rows where the mechanism is closed and the equilibrium system is consistent.
    pressure_angle : rad.
    """

    q: np.ndarray
    qdot: np.ndarray
    qddot: np.ndarray
    input_force: np.ndarray
    reaction: dict
    pins: dict
    slider_force: dict
    slider_moment: dict
    mesh_force: dict
    mesh_tangential: dict
    ground_force: np.ndarray
    ground_moment: np.ndarray
    indeterminate: tuple
    ok: np.ndarray
    pressure_angle: float
    labels: tuple = field(repr=False)
    multipliers: np.ndarray = field(repr=False)
    kinematics: object = field(repr=False, compare=False)

    def _frame_columns(self) -> dict:
        cols = {}
        for i in range(self.q.shape[1]):
            cols[f"q_{i}"] = self.q[:, i]
            cols[f"input_force_{i}"] = self.input_force[:, i]
        for k, v in self.reaction.items():
            cols[f"{k}_x"], cols[f"{k}_y"] = v[:, 0], v[:, 1]
        for k, v in self.slider_force.items():
            cols[f"{k}_normal"] = v
        for k, v in self.mesh_force.items():
            cols[f"{k}_tooth"] = v
        return cols


def _inputs_rows(asm, r):
    """Driver rows (W, N, 3n) and their member links."""
    m = asm.m
    rows, members = [], []
    for spec in m.inputs:
        G = np.zeros((asm.N, asm.n3))
        if spec.kind == "link":
            asm.add_torque(G, spec.name, np.ones(asm.N))
            rel = spec.relative_to or GROUND
            asm.add_torque(G, rel, -np.ones(asm.N))
            members.append({spec.name, rel})
        else:
            s = next(sl for sl in m.sliders if sl.name == spec.name)
            turn = asm.angle(s.on) - m.links[s.on].angle0
            u = _rot(turn, s.direction)
            P = asm.world(s.link, m.links[s.link].local[s.point])
            asm.add_force(G, s.link, P, u)
            asm.add_force(G, s.on, P, -u)
            members.append({s.link, s.on})
        rows.append(G)
    return rows, members


def _solve_equilibrium(A, Q, L, n3):
    """Solve ``A^T y = -Q`` per row by SVD; return y, undetermined mask (N, R), consistent (N,)."""
    N, R, _ = A.shape
    scale = np.ones(n3)
    scale[2::3] = 1.0 / L
    M = np.transpose(A, (0, 2, 1)) * scale[None, :, None]  # (N, 3n, R)
    b = -Q * scale[None, :]
    U, s, Vt = np.linalg.svd(M, full_matrices=True)
    smax = s[:, :1] if s.size else np.zeros((N, 1))
    keep = s > RANK_RTOL * np.maximum(smax, 1e-300)
    rank = keep.sum(axis=1)
    k = s.shape[1]
    c = np.einsum("nij,ni->nj", U[:, :, :k], b)
    c = np.where(keep, c / np.where(keep, s, 1.0), 0.0)
    y = np.einsum("nij,ni->nj", Vt[:, :k, :], c)
    resid = np.linalg.norm(np.einsum("nij,nj->ni", M, y) - b, axis=1)
    consistent = resid <= 1e-8 * np.maximum(np.linalg.norm(b, axis=1), 1e-12 * np.maximum(smax[:, 0], 1.0))
    consistent |= np.linalg.norm(b, axis=1) == 0
    null = np.arange(R)[None, :] >= rank[:, None]  # rows of Vt beyond the rank
    undetermined = np.einsum("nij,ni->nj", np.abs(Vt) > NULL_TOL, null) > 0
    return y, undetermined, consistent


def inverse_dynamics(
    mech, q, qdot=None, qddot=None, loads=None, masses=None, gravity=None, pressure_angle=None
) -> InverseDynamics:
    """Driver torques and joint, guide and tooth forces that produce the prescribed motion.

    Parameters
    ----------
    mech : Mechanism
    q, qdot, qddot : array_like
        Input rows as for :meth:`Mechanism.solve` (``qdot`` default 1, ``qddot`` default 0).
    loads : list of dict, optional
        External loads ``{"link", "point", "force"}`` or ``{"link", "torque"}``; ``force``
        ``(2,)`` or ``(N, 2)``, ``torque`` scalar or ``(N,)``.  Default the model's ``[[loads]]``.
    masses : dict, optional
        ``{link: {"mass", "centre", "inertia"}}``; default the model's ``[masses]``.
    gravity : (2,), optional
        Default the model's ``[mechanism] gravity`` (none if absent).
    pressure_angle : float, optional
        Rad; default the model's ``pressure_angle`` (deg) or 20 deg.

    Returns
    -------
    InverseDynamics

    Examples
    --------
    A crank of length 2 held horizontal against a 10 N downward force at its tip
    needs 20 N m:

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [2, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> d = inverse_dynamics(m, [0.0], loads=[{"link": "crank", "point": "A", "force": [0.0, -10.0]}])
    >>> round(float(d.input_force[0, 0]), 12), (d.reaction["O"] + 0.0).round(12).tolist()
    (20.0, [[0.0, 10.0]])

    Notes
    -----
    Kinetostatic (d'Alembert) equilibrium of each link in absolute
    coordinates with Lagrange multipliers, P. E. Nikravesh, *Computer-Aided
    Analysis of Mechanical Systems*, Prentice Hall, 1988, ch. 6 (inverse
    dynamics: ``M a - Q = -Phi_q^T lambda`` with the accelerations known);
    the input's multiplier is the driving force.  Gear tooth force along the
    line of action ``F_n = F_t / cos(phi)``, radial part ``F_t tan(phi)``
    (J. E. Shigley and J. J. Uicker, *Theory of Machines and Mechanisms*,
    force analysis of spur gears).
    """
    r = mech.solve(q, qdot, qddot)
    m = mech.model
    N = r.q.shape[0]
    masses_ = parse_masses(m, masses)
    loads_ = parse_loads(m, loads, N)
    g = gravity_of(m, gravity)
    phi = pressure_angle_of(m, pressure_angle)
    asm = _Assembly(mech, r)
    n3 = asm.n3

    # generalized applied + inertia forces
    Q = _applied(asm, r, masses_, loads_, g, inertia=True)

    # rows: pins and sliders from the constraint Jacobian, meshes as rolling rows, drivers
    Jfull = constraint_jacobian(m, asm.pose)  # (N, m, 3n)
    labels_all = constraint_labels(m)
    n_ps = 2 * len(m.joints) + 2 * len(m.sliders)
    rows = [Jfull[:, i, :] for i in range(n_ps)]
    labels = list(labels_all[:n_ps])
    members = []
    for _p, a, b in m.joints:
        members += [{a, b}, {a, b}]
    for s in m.sliders:
        members += [{s.link, s.on}, {s.link, s.on}]
    geo = {}
    for mesh in m.meshes:
        A_, B_, P, t, ga, gb = _mesh_geometry(asm, mesh)
        G = np.zeros((N, n3))
        asm.add_force(G, ga.link, P, t)
        asm.add_force(G, gb.link, P, -t)
        rows.append(G)
        labels.append(f"mesh {mesh.name}")
        members.append({ga.link, gb.link})
        geo[mesh.name] = (A_, B_, P, t, ga, gb)
    drv, drv_members = _inputs_rows(asm, r)
    rows += drv
    members += drv_members
    labels += [f"input {spec.label}" for spec in m.inputs]
    A = np.stack(rows, axis=1) if rows else np.zeros((N, 0, n3))

    y, und, consistent = _solve_equilibrium(A, Q, m.length_scale, n3)
    ok = r.closed & np.all(np.isfinite(r.xddot), axis=1) & consistent
    # radial (workless) tooth forces: add them as known forces and re-solve the reactions
    Qg = np.zeros((N, n3))  # radial tooth forces of ground gears on moving gears
    if m.meshes:
        Qr = np.zeros((N, n3))
        base = len(rows) - len(drv) - len(m.meshes)
        for j, mesh in enumerate(m.meshes):
            A_, B_, P, t, ga, gb = geo[mesh.name]
            Ft = np.abs(y[:, base + j])
            ext = gb if ga.internal else ga  # the external gear of the pair
            C = B_ if ga.internal else A_
            u = C - P
            u = u / np.maximum(np.linalg.norm(u, axis=1, keepdims=True), 1e-300)
            fr = (Ft * math.tan(phi))[:, None] * u
            other = ga if ext is gb else gb
            asm.add_force(Qr, ext.link, P, fr)
            asm.add_force(Qr, other.link, P, -fr)
            if ext.link == GROUND:
                asm.add_force(Qg, other.link, P, -fr)
            elif other.link == GROUND:
                asm.add_force(Qg, ext.link, P, fr)
        yr, und_r, _ = _solve_equilibrium(A, Qr, m.length_scale, n3)
        y = y + yr
        und = und | und_r
    y_any = np.where(ok[:, None], y, 0.0)  # one particular solution: the frame's total action is the same for all
    y = np.where(ok[:, None] & ~und, y, np.nan)
    indeterminate = tuple(lab for j, lab in enumerate(labels) if np.any(und[ok, j]))

    reaction, pins = {}, {}
    count = {}
    for p, _a, _b in m.joints:
        count[p] = count.get(p, 0) + 1
    i = 0
    for p, a, b in m.joints:
        key = p if count[p] == 1 else f"{p}:{a}-{b}"
        reaction[key] = -y[:, i : i + 2]
        pins[key] = (a, b)
        i += 2
    slider_force, slider_moment = {}, {}
    for s in m.sliders:
        slider_force[s.name] = y[:, i]
        slider_moment[s.name] = y[:, i + 1]
        i += 2
    mesh_force, mesh_tan = {}, {}
    for mesh in m.meshes:
        mesh_tan[mesh.name] = y[:, i]
        mesh_force[mesh.name] = np.abs(y[:, i]) / math.cos(phi)
        i += 1
    input_force = y[:, i:]

    # the frame's total action: every row that involves ground, as a world wrench on the moving links
    gf = np.zeros((N, 2))
    gm = np.zeros(N)
    yz = y_any
    for j, mem in enumerate(members):
        if GROUND not in mem:
            continue
        Gj = A[:, j, :] * yz[:, j : j + 1]
        f, mo = _wrench(asm, Gj)
        gf += f
        gm += mo
    f, mo = _wrench(asm, Qg)
    gf += f
    gm += mo
    gf[~ok] = np.nan
    gm[~ok] = np.nan
    return InverseDynamics(
        q=r.q,
        qdot=r.qdot,
        qddot=r.qddot,
        input_force=input_force,
        reaction=reaction,
        pins=pins,
        slider_force=slider_force,
        slider_moment=slider_moment,
        mesh_force=mesh_force,
        mesh_tangential=mesh_tan,
        ground_force=gf,
        ground_moment=gm,
        indeterminate=indeterminate,
        ok=ok,
        pressure_angle=phi,
        labels=tuple(labels),
        multipliers=y,
        kinematics=r,
    )


def _wrench(asm, G):
    """World force (N, 2) and moment about the origin (N,) of a generalized force (N, 3n) on the moving links."""
    n = G.shape[1] // 3
    f = G.reshape(G.shape[0], n, 3)
    F = f[..., :2].sum(axis=1)
    M = (f[..., 2] + _cross(asm.O, f[..., :2])).sum(axis=1)
    return F, M


def _point_velocity(asm, r, link, rho, which):
    """Velocity (which=1) or acceleration (which=2) of a body point, from the pose rates."""
    if link == GROUND:
        return np.zeros((asm.N, 2))
    k = asm.col[link] // 3
    th = asm.theta[:, k]
    Rr = _rot(th, rho)
    vel = np.nan_to_num(r.pose_velocity)
    w = vel[:, k, 2]
    if which == 1:
        return vel[:, k, :2] + w[:, None] * _perp(Rr)
    acc = np.nan_to_num(r.pose_acceleration)
    al = acc[:, k, 2]
    return acc[:, k, :2] + al[:, None] * _perp(Rr) - (w * w)[:, None] * Rr


def _applied(asm, r, masses, loads, g, inertia):
    """Generalized force (N, 3n) of loads, weights and (when ``inertia``) d'Alembert inertia forces."""
    Q = np.zeros((asm.N, asm.n3))
    for ld in loads:
        if ld.force is not None:
            P = asm.world(ld.link, ld.point)
            asm.add_force(Q, ld.link, P, ld.force)
        if ld.torque is not None:
            asm.add_torque(Q, ld.link, ld.torque)
    for ms in masses.values():
        Gp = asm.world(ms.link, ms.centre)
        f = np.broadcast_to(ms.mass * g, (asm.N, 2)).copy()
        if inertia:
            f -= ms.mass * _point_velocity(asm, r, ms.link, ms.centre, 2)
            al = np.nan_to_num(r.pose_acceleration)[:, asm.col[ms.link] // 3, 2]
            asm.add_torque(Q, ms.link, -ms.inertia * al)
        asm.add_force(Q, ms.link, Gp, f)
    return Q


# ------------------------------------------------------------------ reduced inertia and motion


def reduced_inertia(mech, q, masses=None) -> np.ndarray:
    """Reduced (generalized) inertia at the input rows: ``(N,)`` for one input, ``(N, W, W)`` otherwise.

    ``J = sum m |v_G / qdot|^2 + I_G (omega / qdot)^2`` over the links with mass
    (the mass matrix ``sum m V_G^T V_G + I_G w^T w`` of the inputs for several).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [2, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> reduced_inertia(m, [0.3], masses={"crank": {"mass": 3.0, "centre": "A", "inertia": 0.5}}).tolist()
    [12.5]

    Notes
    -----
    Kinetic energy ``T = qdot^T M(q) qdot / 2`` of the rigid links
    (e.g. Nikravesh 1988, ch. 6); for one input ``J(q) = M``.
    """
    m = mech.model
    W = len(m.inputs)
    ms = parse_masses(m, masses)
    qa = np.asarray(q, dtype=float)
    vels = []
    for w in range(W):
        e = np.zeros(W)
        e[w] = 1.0
        r = mech.solve(qa, qdot=np.broadcast_to(e, (qa.shape[0], W)) if qa.ndim else e)
        asm = _Assembly(mech, r)
        per = []
        for spec in ms.values():
            v = _point_velocity(asm, r, spec.link, spec.centre, 1)
            om = np.nan_to_num(r.pose_velocity)[:, asm.col[spec.link] // 3, 2]
            per.append((spec, v, om))
        bad = ~r.closed
        vels.append((per, bad))
    N = vels[0][1].shape[0]
    M = np.zeros((N, W, W))
    for a in range(W):
        for b in range(W):
            acc = np.zeros(N)
            for (spec, va, oa), (_, vb, ob) in zip(vels[a][0], vels[b][0]):
                acc += spec.mass * np.sum(va * vb, axis=1) + spec.inertia * oa * ob
            M[:, a, b] = acc
    bad = np.any([v[1] for v in vels], axis=0)
    M[bad] = np.nan
    return M[:, 0, 0] if W == 1 else M


def _load_power(mech, r, masses, loads, g):
    """Generalized force of the (constant) loads and weights per unit input speed, ``(N,)``."""
    asm = _Assembly(mech, r)
    Q = _applied(asm, r, masses, loads, g, inertia=False)
    vel = np.nan_to_num(r.pose_velocity).reshape(asm.N, -1)
    return np.sum(Q * vel, axis=1)


@dataclass(frozen=True)
class Simulation(Result):
    """Motion of a one-input mechanism under a driving torque.

    Attributes
    ----------
    t : (N,) times (s).
    q, qdot, qddot : (N,) input angle (rad), speed (rad/s), acceleration (rad/s^2).
    kinetic_energy : (N,) ``J(q) qdot^2 / 2``.
    inertia : (N,) reduced inertia ``J(q)``.
    """

    t: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    qddot: np.ndarray
    kinetic_energy: np.ndarray
    inertia: np.ndarray


def simulate(
    mech,
    t,
    q0: float,
    qdot0: float,
    torque: float | Callable = 0.0,
    masses=None,
    loads=None,
    gravity=None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    grid: int = SIM_GRID,
) -> Simulation:
    """Integrate ``J(q) q'' + J'(q)/2 q'^2 = Q`` for a mechanism with one rotary input that turns fully.

    Parameters
    ----------
    mech : Mechanism
    t : array_like
        Increasing output times (s); the motion starts at ``t[0]``.
    q0, qdot0 : float
        Input angle (rad) and speed (rad/s) at ``t[0]``.
    torque : float or callable
        Driving torque on the input, a number or ``f(t, q, qdot)``.
    masses, loads, gravity
        As for :func:`inverse_dynamics`; loads must be constant (not arrays over rows).
    rtol, atol : float
        Tolerances of :func:`scipy.integrate.solve_ivp` (method DOP853).
    grid : int
        Points per turn of the periodic tables of ``J`` and of the loads' generalized force.

    Returns
    -------
    Simulation

    Notes
    -----
    Lagrange's equation for one generalized coordinate with the kinetic energy
    ``J(q) qdot^2 / 2`` (the "equation of motion of a machine" of the
    reduced-inertia method, e.g. Nikravesh 1988, ch. 6).  ``J(q)`` and the
    loads' generalized force ``Q_L(q) = sum F . dP/dq + ...`` are tabulated over
    one turn and interpolated by periodic cubic splines, whose derivative is
    used for ``J'``.  The equation is integrated in the variables ``q`` and
    ``u = sqrt(J) q'`` (so that ``J q'^2 / 2 = u^2 / 2``):
    ``q' = u / sqrt(J)``, ``u' = Q / sqrt(J)``, which follows from
    ``J q'' + J' q'^2 / 2 = Q`` and keeps the kinetic energy constant to
    rounding when ``Q = 0``, with no singularity where the motion reverses.
    """
    from scipy.integrate import solve_ivp
    from scipy.interpolate import CubicSpline

    m = mech.model
    if len(m.inputs) != 1 or m.inputs[0].kind != "link":
        raise GearleverError("simulate needs a mechanism with one rotary input (a link angle)")
    tt = V.nonempty_array("t", t)
    if tt.ndim != 1 or (tt.size > 1 and np.any(np.diff(tt) <= 0)):
        raise GearleverError("t must be a 1-D array of increasing times")
    q0 = V.finite("q0", q0)
    qdot0 = V.finite("qdot0", qdot0)
    grid = V.positive_int("grid", grid)
    if grid < 16 or grid > 100_000:
        raise GearleverError(f"grid must be between 16 and 100000, got {grid}")
    ms = parse_masses(m, masses)
    lds = parse_loads(m, loads, 1)
    for ld in lds:
        if (ld.force is not None and ld.force.shape[0] != 1) or (ld.torque is not None and ld.torque.shape[0] != 1):
            raise GearleverError("loads: simulate takes constant loads only")
    g = gravity_of(m, gravity)
    qg = q0 + np.linspace(0.0, 2 * np.pi, grid + 1)
    r = mech.solve(qg, np.ones_like(qg), np.zeros_like(qg))
    if not r.closed.all():
        raise GearleverError("simulate: the input does not turn fully (the mechanism does not close over a turn)")
    J = reduced_inertia(mech, qg, masses)
    if not np.all(np.isfinite(J)) or np.any(J <= 0):
        raise GearleverError("simulate: the reduced inertia must be positive over the turn (give masses)")
    N1 = len(qg)
    loads1 = [
        {
            "link": ld.link,
            **({"point": _sketch_of(m, ld), "force": np.repeat(ld.force, N1, axis=0)} if ld.force is not None else {}),
            **({"torque": np.repeat(ld.torque, N1)} if ld.torque is not None else {}),
        }
        for ld in lds
    ]
    QL = _load_power(mech, r, ms, parse_loads(m, loads1, N1), g)
    scale = max(abs(J).max(), 1e-300)
    if abs(J[-1] - J[0]) > 1e-7 * scale:
        raise GearleverError("simulate: the reduced inertia does not repeat after one input turn")
    J[-1] = J[0]
    QL[-1] = QL[0]
    Js = CubicSpline(qg, J, bc_type="periodic")
    dJs = Js.derivative()
    Qs = CubicSpline(qg, QL, bc_type="periodic")
    period = 2 * np.pi

    def wrap(q):
        return q0 + np.mod(q - q0, period)

    if callable(torque):
        tau = torque
    else:
        tv = V.finite("torque", torque)

        def tau(_t, _q, _qd):
            return tv

    def rhs(time, state):
        q, u = state
        qq = wrap(q)
        sJ = np.sqrt(Js(qq))
        qd = u / sJ
        return [qd, (float(tau(time, q, qd)) + Qs(qq)) / sJ]

    u0 = math.sqrt(Js(wrap(q0))) * qdot0
    sol = solve_ivp(rhs, (tt[0], tt[-1]), [q0, u0], t_eval=tt, method="DOP853", rtol=rtol, atol=atol)
    if not sol.success:  # pragma: no cover - DOP853 on a smooth ODE
        raise GearleverError(f"simulate: the integration failed: {sol.message}")
    q, u = sol.y
    qq = wrap(q)
    Jq = Js(qq)
    qd = u / np.sqrt(Jq)
    Qt = np.array([float(tau(ti, qi, di)) for ti, qi, di in zip(sol.t, q, qd)]) + Qs(qq)
    qdd = (Qt - 0.5 * dJs(qq) * qd * qd) / Jq
    return Simulation(t=sol.t, q=q, qdot=qd, qddot=qdd, kinetic_energy=0.5 * Jq * qd * qd, inertia=Jq)


def _sketch_of(model, ld):
    """Sketch location of a load's body-fixed point."""
    lk = model.links[ld.link]
    c, s = math.cos(lk.angle0), math.sin(lk.angle0)
    x, y = ld.point
    return [lk.origin[0] + c * x - s * y, lk.origin[1] + s * x + c * y]
