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
from dataclasses import dataclass, field, replace

import numpy as np

from gearlever import _validate as V
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.torques import MAX_PASSES
from gearlever.mechanism.constraints import constraint_jacobian, constraint_labels
from gearlever.mechanism.loads import (
    LoadSpec,
    force_units,
    gravity_of,
    mesh_efficiency_of,
    parse_loads,
    parse_masses,
    pressure_angle_of,
)
from gearlever.mechanism.model import GROUND

__all__ = [
    "InverseDynamics",
    "Simulation",
    "dynamic_terms",
    "force_units",
    "inverse_dynamics",
    "reduced_inertia",
    "simulate",
]

#: Relative singular-value threshold of the equilibrium system (rank decisions).
RANK_RTOL = 1e-10
#: A multiplier counts as undetermined when a null vector has a component above this.
NULL_TOL = 1e-8
#: Largest number of grid points of the reduced-inertia table used by :func:`simulate`.
SIM_GRID = 1440
#: Default cap on the right-hand-side evaluations of :func:`simulate` with several inputs (each one
#: kinematic solve of ``W + 1`` rows, about 0.4 ms measured for the two-crank five-bar on a loaded
#: 2-core machine: the cap bounds a run to about 10-20 s, never a hang; a longer simulation passes
#: ``max_evals`` explicitly).
MAX_EVALS = 40_000
#: :func:`simulate` checks its progress after this many evaluations (and after each doubling): when the
#: time reached so far projects more than ``max_evals`` evaluations for the whole run, it refuses at
#: once (in seconds) rather than at the cap (a minute or more).
PROBE_EVALS = 500


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
    mesh_loss : mesh -> (N,) power the mesh dissipates (>= 0; zero for efficiency 1):
        ``sum tau_i qdot_i + power of loads, weights and inertia forces = sum of mesh_loss``.
    mesh_driven : mesh -> (N,) which gear the mesh drives relative to its carrier (1 the first, 2 the
        second, 0 none or no loss); the losses are charged on that side.
    indeterminate : labels of the multipliers the equilibrium does not fix (redundant constraints).
    friction_torque : key of :attr:`reaction` -> (N,) friction torque of the pin on its second link
        (the first gets the opposite); pins with friction only.
    friction_force : slider -> (N,) friction force of the guide on the sliding link, along the guide.
    friction_loss : pin key or slider -> (N,) power the joint's friction dissipates (>= 0).
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
    mesh_loss: dict
    mesh_driven: dict
    indeterminate: tuple
    ok: np.ndarray
    pressure_angle: float
    labels: tuple = field(repr=False)
    multipliers: np.ndarray = field(repr=False)
    kinematics: object = field(repr=False, compare=False)
    friction_torque: dict = field(default_factory=dict)
    friction_force: dict = field(default_factory=dict)
    friction_loss: dict = field(default_factory=dict)

    def _frame_columns(self) -> dict:
        cols = {}
        spec = self.kinematics.system.model.inputs if self.kinematics is not None else ()
        names = [s.label for s in spec] if len(spec) == self.q.shape[1] else [str(i) for i in range(self.q.shape[1])]
        for i, name in enumerate(names):
            cols[f"{name}_q"] = self.q[:, i]
            cols[f"{name}_qdot"] = self.qdot[:, i]
            cols[f"{name}_force"] = self.input_force[:, i]
        for k, v in self.reaction.items():
            cols[f"{k}_x"], cols[f"{k}_y"] = v[:, 0], v[:, 1]
        for k, v in self.slider_force.items():
            cols[f"{k}_normal"] = v
        for k, v in self.mesh_force.items():
            cols[f"{k}_tooth"] = v
        for k, v in self.mesh_loss.items():
            cols[f"{k}_loss"] = v
        for k, v in self.friction_loss.items():
            cols[f"{k}_friction_loss"] = v
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


def _solve_equilibrium(A, Q, L, n3, cache=None):
    """Solve ``A^T y = -Q`` per row by SVD; return y, undetermined mask (N, R), consistent (N,).

    ``cache`` (a dict) keeps the SVD of each ``A`` met, for the friction passes that solve again with another ``Q``.
    """
    N, R, _ = A.shape
    scale = np.ones(n3)
    scale[2::3] = 1.0 / L
    M = np.transpose(A, (0, 2, 1)) * scale[None, :, None]  # (N, 3n, R)
    b = -Q * scale[None, :]
    key = ("svd", A.shape, hash(A.tobytes())) if cache is not None else None
    if key is not None and key in cache:
        U, s, Vt = cache[key]
    else:
        U, s, Vt = np.linalg.svd(M, full_matrices=True)
        if key is not None:
            cache[key] = (U, s, Vt)
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


def _rows_of(mech, q, qdot, qddot):
    """Input rows ``(N, W)`` and their rates broadcast to them (a scalar, ``(W,)``, ``(N,)`` or ``(N, W)``)."""
    from gearlever._validate import finite_array, speed

    W = len(mech.model.inputs)
    qa = finite_array("q", q)
    if qa.ndim == 0 or (qa.ndim == 1 and W == 1):
        qa = qa.reshape(-1, 1)
    elif qa.ndim == 1 and qa.shape[0] == W:
        qa = qa[None, :]
    if qa.ndim != 2 or qa.shape[1] != W:
        raise GearleverError(f"q must have shape (N,) for one input or (N, {W}) for {W} inputs, got {np.shape(q)}")
    N = qa.shape[0]

    def rate(name, v, default):
        if v is None:
            return np.full((N, W), default)
        a = speed(name, v) if name == "qdot" else finite_array(name, v)
        if a.ndim == 0:
            return np.full((N, W), float(a))
        if a.ndim == 1 and a.shape[0] == W and (W > 1 or N == 1):
            return np.broadcast_to(a, (N, W)).copy()
        if a.ndim == 1 and W == 1 and a.shape[0] == N:
            return a[:, None].copy()
        if a.shape == (N, W):
            return a
        raise GearleverError(f"{name} must be a number, ({W},), or ({N}, {W}) like q, got shape {a.shape}")

    return qa, rate("qdot", qdot, 1.0), rate("qddot", qddot, 0.0)


def inverse_dynamics(
    mech,
    q,
    qdot=None,
    qddot=None,
    loads=None,
    masses=None,
    gravity=None,
    pressure_angle=None,
    efficiency=None,
    friction=None,
    _driven=None,
    branch: str = "continue",
) -> InverseDynamics:
    """Driver torques and joint, guide and tooth forces that produce the prescribed motion.

    Parameters
    ----------
    mech : Mechanism
    q, qdot, qddot : array_like
        Input rows as for :meth:`Mechanism.solve`, ``(N,)`` for one input or
        ``(N, W)``; the rates may also be a number or one row ``(W,)`` for
        every row (``qdot`` default 1, ``qddot`` default 0).
    loads : list of dict, optional
        External loads ``{"link", "point", "force"}`` or ``{"link", "torque"}``; ``force``
        ``(2,)`` or ``(N, 2)``, ``torque`` scalar or ``(N,)``.  Default the model's ``[[loads]]``.
    masses : dict, optional
        ``{link: {"mass", "centre", "inertia"}}``; default the model's ``[masses]``.
    gravity : (2,), optional
        Default the model's ``[mechanism] gravity`` (none if absent).
    pressure_angle : float, optional
        Rad; default the model's ``pressure_angle`` (deg) or 20 deg.
    efficiency : float or dict, optional
        Tooth efficiency of the meshes, one number or ``{mesh: number}``
        (:func:`~gearlever.mechanism.loads.mesh_efficiency_of`); default the model's, else 1.
    friction : dict, optional
        Coulomb friction at the pins and sliders, a table as the model's
        ``[friction]`` (:mod:`gearlever.mechanism.friction`); default the
        model's, else none.
    branch : {"continue", "keep", "stop"}
        The policy at branch points of the motion (:meth:`Mechanism.solve`).
        A row exactly at a branch point has its kinematics (the limit of the
        branch continued either side) but NaN forces and torques: the
        constraint Jacobian loses rank there, so a rigid model's pin forces
        are not unique (a state of self-stress can be added: at the square-rod
        slider-crank's square pose, a force along the line of crank, rod and
        guide normal), and the equilibrium is solved only where it has one
        answer; the rows beside it carry the limit.

    Returns
    -------
    InverseDynamics

    Raises
    ------
    GearleverError
        ``"self-locking: ..."`` when, with mesh losses, no direction of the
        power flow through the meshes is consistent at some row (the train
        cannot be driven that way, e.g. a high-ratio train driven from its
        output); also for losses on a mesh whose force is statically indeterminate.

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

    Mesh losses as for gear trains (:func:`gearlever.gears.torques.network_torques`,
    after E. Pennestri and F. Freudenstein, "The mechanical efficiency of
    epicyclic gear trains", ASME J. Mech. Des. 115 (1993) 645-651): in the
    frame of the mesh's carrier (the link that holds both gear centres) the
    torque the teeth give the *driven* gear (the one the mesh passes power
    to, relative to the carrier) is ``eta`` times the ideal one, the carrier
    takes the difference, so every link stays in equilibrium and the mesh
    dissipates ``(1 - eta)`` times the power it passes relative to its
    carrier (:attr:`InverseDynamics.mesh_loss`).  The driven side depends on
    the solution: it is found by fixed-point passes, as in the train code.

    Forces beyond the float range (a huge mass, load or speed) are refused,
    naming the element (``masses.crank.mass``, ``loads[0].force``), never
    returned as ``inf`` or ``nan``.

    Joint friction (Coulomb, :mod:`gearlever.mechanism.friction`): a pin's
    friction torque ``rho |R|`` and a slider's friction force ``mu |N|``
    depend on the reactions they change, so the equilibrium is implicit.  It
    is solved by fixed-point passes: the friction of the reactions of the
    last pass is applied as a known load and the equilibrium solved again,
    until the reactions agree to 1e-12 of their size; each pass changes the
    reactions by about ``rho / L`` (friction-circle radius over link length)
    times the last change, so a few passes suffice.  Where the passes do not
    settle (friction circles as large as the links) the row is refused as
    self-locking.  The friction's dissipated power is
    :attr:`InverseDynamics.friction_loss`, and
    ``sum tau_i qdot_i + power of loads, weights and inertia forces = sum of mesh_loss + sum of friction_loss``.
    """
    from gearlever.mechanism.friction import parse_friction

    spec = parse_friction(mech.model, friction)
    # overflow is not warned about here: the final check refuses it, naming the input
    with np.errstate(over="ignore", invalid="ignore"):
        kin = None
        if branch != "continue":
            from gearlever.mechanism.branch import check_branch

            qa, qd_, qdd_ = _rows_of(mech, q, qdot, qddot)
            kin = mech.solve(qa, qd_, qdd_, branch=check_branch(branch))
        d = _inverse_dynamics(
            mech, q, qdot, qddot, loads, masses, gravity, pressure_angle, efficiency, _driven=_driven, _kin=kin
        )
        if spec:
            d = _with_friction(mech, d, spec, (loads, masses, gravity, pressure_angle, efficiency), _driven)
        return d


#: Largest number of fixed-point passes of the friction equilibrium.
FRICTION_PASSES = 200
#: The passes end when no multiplier changes by more than this fraction of the largest.
FRICTION_RTOL = 1e-12


def _friction_terms(mech, d, spec):
    """Generalized friction forces (N, 3n) of the reactions of ``d``, and the friction torques, forces, losses."""
    r = d.kinematics
    m = mech.model
    asm = _Assembly(mech, r)
    N = asm.N
    spin = np.nan_to_num(r.pose_velocity)[..., 2]

    def omega(link):
        return np.zeros(N) if link == GROUND else spin[:, asm.col[link] // 3]

    Qf = np.zeros((N, asm.n3))
    torque, force, loss = {}, {}, {}
    scale = max(float(np.max(np.abs(np.nan_to_num(r.qdot)), initial=0.0)), 1e-300)
    for key, (a, b) in d.pins.items():
        p = key.split(":")[0]
        if p not in spec.pins:
            continue
        rho = spec.pins[p][2]
        R = np.linalg.norm(np.nan_to_num(d.reaction[key]), axis=1)
        w = omega(b) - omega(a)
        sgn = np.where(np.abs(w) > 1e-12 * scale, np.sign(w), 0.0)
        Tb = -rho * R * sgn  # on the second link, opposing its turning relative to the first
        asm.add_torque(Qf, b, Tb)
        asm.add_torque(Qf, a, -Tb)
        torque[key] = Tb
        loss[key] = rho * R * np.abs(w) * (sgn != 0)
    for s in m.sliders:
        if s.name not in spec.sliders:
            continue
        mu = spec.sliders[s.name]
        Nn = np.abs(np.nan_to_num(d.slider_force[s.name]))
        v = np.nan_to_num(r.slider_velocity[s.name])
        vs = max(float(np.max(np.abs(v), initial=0.0)), 1e-300)
        sgn = np.where(np.abs(v) > 1e-12 * vs, np.sign(v), 0.0)
        turn = asm.angle(s.on) - m.links[s.on].angle0
        u = _rot(turn, s.direction)
        P = asm.world(s.link, m.links[s.link].local[s.point])
        F = -mu * Nn * sgn  # along the guide, on the sliding link
        asm.add_force(Qf, s.link, P, F[:, None] * u)
        asm.add_force(Qf, s.on, P, -F[:, None] * u)
        force[s.name] = F
        loss[s.name] = mu * Nn * np.abs(v) * (sgn != 0)
    return Qf, torque, force, loss


def _with_friction(mech, d0, spec, args, _driven):
    """The equilibrium with joint friction: fixed-point passes from the frictionless one ``d0``."""
    loads, masses, gravity, pressure_angle, efficiency = args
    r = d0.kinematics
    for key in d0.pins:
        if key.split(":")[0] in spec.pins and np.any(np.isnan(d0.reaction[key][d0.ok])):
            raise GearleverError(
                f"friction.pins.{key.split(':')[0]}: the pin's reaction is statically indeterminate (redundant "
                "constraints), so its friction is not determined: give it no friction"
            )
    for name in spec.sliders:
        if np.any(np.isnan(d0.slider_force[name][d0.ok])):
            raise GearleverError(
                f"friction.sliders.{name}: the guide's normal force is statically indeterminate, so its friction is "
                "not determined: give it no friction"
            )
    d = d0
    cache: dict = {}
    ref = max(float(np.max(np.abs(np.nan_to_num(d0.multipliers)), initial=0.0)), 1e-300)
    prev, growth = None, np.zeros(r.q.shape[0], dtype=int)
    tol = FRICTION_RTOL * ref
    for _ in range(FRICTION_PASSES):
        Qf, torque, force, loss = _friction_terms(mech, d, spec)
        new = _inverse_dynamics(
            mech, r.q, r.qdot, r.qddot, loads, masses, gravity, pressure_angle, efficiency,
            _driven=_driven, _extra=Qf, _kin=r, _cache=cache,
        )  # fmt: skip
        y_new, y_old = np.nan_to_num(new.multipliers), np.nan_to_num(d.multipliers)
        change = np.max(np.abs(y_new - y_old), axis=1) if y_new.size else np.zeros(r.q.shape[0])
        d = new
        if np.all(change <= tol):
            Qf, torque, force, loss = _friction_terms(mech, d, spec)
            return replace(d, friction_torque=torque, friction_force=force, friction_loss=loss)
        if prev is not None:  # diverging: the change grew by half again, three passes running
            growth = np.where((change > tol) & (change > 1.5 * prev), growth + 1, 0)
            if np.any((growth >= 3) & d.ok):
                break
        prev = change
    i = int(np.argmax(change))
    raise GearleverError(
        f"self-locking: at input row {i} (q = {np.round(r.q[i], 9).tolist()}) the joint friction admits no "
        "equilibrium (the friction circles are too large for the links: the mechanism locks)"
    )


def _inverse_dynamics(
    mech,
    q,
    qdot,
    qddot,
    loads,
    masses,
    gravity,
    pressure_angle,
    efficiency,
    _driven=None,
    _extra=None,
    _kin=None,
    _cache=None,
) -> InverseDynamics:
    if _kin is None:
        qa, qd_, qdd_ = _rows_of(mech, q, qdot, qddot)
        r = mech.solve(qa, qd_, qdd_)
    else:
        r = _kin
    m = mech.model
    N = r.q.shape[0]
    masses_ = parse_masses(m, masses)
    loads_ = parse_loads(m, loads, N)
    g = gravity_of(m, gravity)
    phi = pressure_angle_of(m, pressure_angle)
    effs = mesh_efficiency_of(m, efficiency)
    asm = _Assembly(mech, r)
    Q = _generalized_forces(asm, r, masses_, loads_, g, _extra, _cache)
    A, labels, members, geo, loss, base = _equilibrium_rows(asm, r, effs, _cache)
    y, und, consistent = _solve_equilibrium(A, Q, m.length_scale, asm.n3, _cache)
    ok = r.closed & np.all(np.isfinite(r.xddot), axis=1) & consistent
    A, y, und, driven = _settle_mesh_losses(asm, r, A, Q, y, und, ok, loss, base, effs, _driven, _cache)
    mesh_loss = _mesh_losses(m, loss, y, driven, base)
    y, und, Qg = _with_radial_tooth_forces(asm, A, y, und, geo, base, phi, _cache)
    y_any = np.where(ok[:, None], y, 0.0)  # one particular solution: the frame's total action is the same for all
    y = np.where(ok[:, None] & ~und, y, np.nan)
    indeterminate = tuple(lab for j, lab in enumerate(labels) if np.any(und[ok, j]))
    reaction, pins, slider_force, slider_moment, mesh_force, mesh_tan, input_force = _named_forces(m, y, phi)
    gf, gm = _frame_action(asm, A, y_any, members, Qg, ok)
    kin = r.closed & np.all(np.isfinite(r.xddot), axis=1)
    _refuse_overflow(asm, r, masses_, loads_, g, kin, [Q])
    _refuse_overflow(asm, r, masses_, loads_, g, ok, [y_any, gf, gm, *mesh_loss.values()])
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
        mesh_loss={k: np.where(ok, v, np.nan) for k, v in mesh_loss.items()},
        mesh_driven={mesh.name: driven[:, j].copy() for j, mesh in enumerate(m.meshes)},
        indeterminate=indeterminate,
        ok=ok,
        pressure_angle=phi,
        labels=tuple(labels),
        multipliers=y,
        kinematics=r,
    )


def _generalized_forces(asm, r, masses, loads, g, extra, cache):
    """Generalized applied and inertia forces (N, 3n), plus ``extra`` (the joint friction of the last pass)."""
    if cache is not None and "Q" in cache:
        Q = cache["Q"]
    else:
        Q = _applied(asm, r, masses, loads, g, inertia=True)
        if cache is not None:
            cache["Q"] = Q
    if extra is not None:
        Q = Q + extra
    return Q


def _equilibrium_rows(asm, r, effs, cache) -> tuple:
    """The equilibrium's rows: pins and sliders (constraint Jacobian), meshes as rolling rows, the drivers.

    Returns ``(A (N, rows, 3n), labels, members, mesh geometry, mesh loss terms, index of the first mesh row)``;
    a mesh's loss terms are ``(eta, loss row if gear a is driven, if gear b is driven, power into a, into b per
    unit multiplier)``.
    """
    m = asm.m
    N, n3 = r.q.shape[0], asm.n3
    if cache is not None and "J" in cache:
        Jfull = cache["J"]
    else:
        Jfull = constraint_jacobian(m, asm.pose)  # (N, m, 3n)
        if cache is not None:
            cache["J"] = Jfull
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
    loss = []
    spin = np.nan_to_num(r.pose_velocity)[..., 2]

    def omega(link):
        return np.zeros(N) if link == GROUND else spin[:, asm.col[link] // 3]

    for mesh in m.meshes:
        A_, B_, P, t, ga, gb = _mesh_geometry(asm, mesh)
        G = np.zeros((N, n3))
        asm.add_force(G, ga.link, P, t)
        asm.add_force(G, gb.link, P, -t)
        rows.append(G)
        labels.append(f"mesh {mesh.name}")
        members.append({ga.link, gb.link})
        geo[mesh.name] = (A_, B_, P, t, ga, gb)
        eta = effs[mesh.name]
        ma, mb = _cross(P - A_, t), _cross(P - B_, -t)  # moments of the unit tooth force about the centres
        wc = omega(mesh.carrier)
        La, Lb = np.zeros((N, n3)), np.zeros((N, n3))
        asm.add_torque(La, ga.link, -(1.0 - eta) * ma)
        asm.add_torque(La, mesh.carrier, (1.0 - eta) * ma)
        asm.add_torque(Lb, gb.link, -(1.0 - eta) * mb)
        asm.add_torque(Lb, mesh.carrier, (1.0 - eta) * mb)
        loss.append((eta, La, Lb, ma * (omega(ga.link) - wc), mb * (omega(gb.link) - wc)))
    drv, drv_members = _inputs_rows(asm, r)
    rows += drv
    members += drv_members
    labels += [f"input {spec.label}" for spec in m.inputs]
    A = np.stack(rows, axis=1) if rows else np.zeros((N, 0, n3))
    return A, labels, members, geo, loss, n_ps


def _settle_mesh_losses(asm, r, A0, Q, y, und, ok, loss, base, effs, given, cache) -> tuple:
    """``(A, y, und, driven)``: the equilibrium with each lossy mesh charged on its driven gear.

    ``driven`` (N, meshes) is 0 (no loss), 1 (gear a driven) or 2 (gear b);
    ``given`` fixes it (forward dynamics: the map from accelerations to forces
    is then linear), else it is found by re-solving until the directions of
    the power flow settle.
    """
    m = asm.m
    N, n3 = r.q.shape[0], asm.n3
    lossy = [j for j, lo in enumerate(loss) if lo[0] < 1.0]
    driven = np.zeros((N, len(m.meshes)), dtype=np.int8)  # 0 no loss, 1 gear a driven, 2 gear b driven
    A = A0

    def with_losses(driven):
        A = A0.copy()
        for j in lossy:
            A[:, base + j] += np.where(driven[:, j, None] == 1, loss[j][1], 0.0)
            A[:, base + j] += np.where(driven[:, j, None] == 2, loss[j][2], 0.0)
        y, und, consistent = _solve_equilibrium(A, Q, m.length_scale, n3, cache)
        lost = ok & ~consistent
        if lost.any():
            i = int(np.argmax(lost))
            raise GearleverError(
                f"self-locking: at input row {i} (q = {np.round(r.q[i], 9).tolist()}) the lossy meshes admit "
                "no equilibrium: the train cannot be driven this way"
            )
        return A, y, und

    if lossy:
        bad = [m.meshes[j].name for j in lossy if np.any(und[ok, base + j])]
        if bad:
            raise GearleverError(
                f"self-locking: cannot decide, mesh losses need determined tooth forces, and those of {bad} are "
                "statically indeterminate (redundant pairs); give them efficiency = 1"
            )
    if lossy and given is not None:  # directions given (forward dynamics): the map qddot -> forces is linear
        driven = np.where(ok[:, None], np.broadcast_to(np.asarray(given, dtype=np.int8), driven.shape), 0)
        A, y, und = with_losses(driven)
    elif lossy:
        history = [driven.copy()]
        for _ in range(MAX_PASSES):
            new = np.zeros_like(driven)
            for j in lossy:
                pa = y[:, base + j] * loss[j][3]  # power the mesh passes into gear a relative to the carrier
                tol = 1e-9 * max(float(np.max(np.abs(pa[ok]), initial=0.0)), 1e-300)
                new[:, j] = np.where(pa > tol, 1, np.where(pa < -tol, 2, 0))
            new[~ok] = 0
            if np.array_equal(new, driven):
                break
            changed = np.any(new != driven, axis=1)
            seen = np.any([np.all(h == new, axis=1) for h in history], axis=0) & changed
            if seen.any():
                i = int(np.argmax(seen))
                raise GearleverError(
                    f"self-locking: at input row {i} (q = {np.round(r.q[i], 9).tolist()}) no direction of the power "
                    f"flow through the meshes is consistent with efficiency {[effs[n] for n in effs]}: the train "
                    "cannot be driven this way"
                )
            history.append(new.copy())
            driven = new
            A, y, und = with_losses(driven)
        else:  # pragma: no cover - bounded by the finite number of direction sets
            raise GearleverError("self-locking: the power-flow directions through the meshes do not settle")
    return A, y, und, driven


def _mesh_losses(m, loss, y, driven, base) -> dict:
    """Power lost in each mesh per row: ``(1 - eta)`` times the rolling power of its driven gear."""
    mesh_loss = {}
    for j, mesh in enumerate(m.meshes):
        eta, _, _, pa, pb = loss[j]
        yj = y[:, base + j]
        mesh_loss[mesh.name] = np.where(
            driven[:, j] == 1, (1.0 - eta) * yj * pa, np.where(driven[:, j] == 2, (1.0 - eta) * yj * pb, 0.0)
        )
    return mesh_loss


def _with_radial_tooth_forces(asm, A, y, und, geo, base, phi, cache) -> tuple:
    """``(y, und, Qg)``: the radial (workless) tooth forces added as known forces and the reactions re-solved.

    ``Qg`` holds the radial forces of ground gears on moving gears (part of the frame's action).
    """
    m = asm.m
    N, n3 = y.shape[0], asm.n3
    Qg = np.zeros((N, n3))  # radial tooth forces of ground gears on moving gears
    if not m.meshes:
        return y, und, Qg
    Qr = np.zeros((N, n3))
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
    yr, und_r, _ = _solve_equilibrium(A, Qr, m.length_scale, n3, cache)
    return y + yr, und | und_r, Qg


def _named_forces(m, y, phi) -> tuple:
    """The multipliers ``y`` by name: pin reactions (and their links), slider forces and moments, meshes, inputs."""
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
    return reaction, pins, slider_force, slider_moment, mesh_force, mesh_tan, y[:, i:]


def _frame_action(asm, A, y_any, members, Qg, ok) -> tuple:
    """``(force (N, 2), moment (N,))``: the frame's total action, every row that involves ground, as a world wrench."""
    N = y_any.shape[0]
    gf = np.zeros((N, 2))
    gm = np.zeros(N)
    for j, mem in enumerate(members):
        if GROUND not in mem:
            continue
        Gj = A[:, j, :] * y_any[:, j : j + 1]
        f, mo = _wrench(asm, Gj)
        gf += f
        gm += mo
    f, mo = _wrench(asm, Qg)
    gf += f
    gm += mo
    gf[~ok] = np.nan
    gm[~ok] = np.nan
    return gf, gm


def _contributions(asm, r, masses, loads, g):
    """Each element's share of the generalized applied force: ``[(element, value, (N, 3n))]`` (failure path only)."""
    from gearlever.mechanism.loads import metres_per_unit

    k = metres_per_unit(asm.m)
    out = []
    for i, ld in enumerate(loads):
        for what, arr in (("force", ld.force), ("torque", ld.torque)):
            if arr is None:
                continue
            G = np.zeros((asm.N, asm.n3))
            if what == "force":
                asm.add_force(G, ld.link, asm.world(ld.link, ld.point), arr)
            else:
                asm.add_torque(G, ld.link, arr)
            out.append((f"loads[{i}].{what}", float(np.max(np.abs(arr))), G))
    for ms in masses.values():
        Gm = _applied(asm, r, {ms.link: replace(ms, inertia=0.0)}, [], g, inertia=True)
        Gi = _applied(asm, r, {ms.link: replace(ms, mass=0.0)}, [], np.zeros(2), inertia=True)
        out.append((f"masses.{ms.link}.mass", ms.mass / k, Gm))
        out.append((f"masses.{ms.link}.inertia", ms.inertia / k, Gi))
    return out


def _refuse_overflow(asm, r, masses, loads, g, ok, arrays) -> None:
    """Refuse results that overflow floating point at closed rows, naming the input element that causes it.

    A mass, load or speed so large that the forces exceed the float range
    would otherwise come out as ``inf`` and ``nan`` (every force ``nan``)
    and be passed off as a result.  The element named is the one whose own
    forces overflow, else the one with the largest forces.
    """
    bad = np.zeros(asm.N, dtype=bool)
    for a in arrays:
        a = np.asarray(a, dtype=float).reshape(asm.N, -1)
        bad |= ~np.all(np.isfinite(a), axis=1)
    bad &= ok
    if not bad.any():
        return
    i = int(np.argmax(bad))
    parts = _contributions(asm, r, masses, loads, g)
    with np.errstate(all="ignore"):
        size = [
            (not np.all(np.isfinite(G[i])), float(np.max(np.abs(np.nan_to_num(G[i], nan=np.inf))))) for *_, G in parts
        ]
    speeds = ", ".join(f"{v:.6g}" for v in r.qdot[i])
    if parts:
        j = max(range(len(parts)), key=lambda j: size[j])
        where, value, _ = parts[j]
        raise GearleverError(
            f"{where} = {value:g}: the forces it gives overflow floating point (beyond {np.finfo(float).max:.4g}) "
            f"at input row {i} (speeds {speeds}); it must be smaller (or the speeds lower)"
        )
    raise GearleverError(  # pragma: no cover - no load and no mass: every force is zero
        f"qdot: the forces overflow floating point at input row {i} (speeds {speeds}); the speeds must be lower"
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


def _const_loads(lds, N):
    """Constant loads (parsed with one row) broadcast to ``N`` rows."""
    return [
        LoadSpec(
            ld.label,
            ld.link,
            ld.point,
            None if ld.force is None else np.broadcast_to(ld.force[0], (N, 2)),
            None if ld.torque is None else np.broadcast_to(ld.torque[0], (N,)),
        )
        for ld in lds
    ]


def _terms(mech, q, qd, ms, lds, g):
    """``M (N, W, W)``, ``b (N, W)``, power of loads and weights ``(N,)``, closed ``(N,)`` (parsed inputs)."""
    N, W = q.shape
    eye = np.eye(W)
    rows_q = np.concatenate([q] * (W + 1))
    rows_qd = np.concatenate([qd] + [np.broadcast_to(eye[i], (N, W)) for i in range(W)])
    r = mech.solve(rows_q, rows_qd, np.zeros_like(rows_q))
    asm = _Assembly(mech, r)
    NN = rows_q.shape[0]
    big = _const_loads(lds, NN)
    Q = _applied(asm, r, ms, big, g, inertia=True)[:N]
    QL = _applied(asm, r, ms, big, g, inertia=False)[:N]
    vel = np.nan_to_num(r.pose_velocity).reshape(NN, -1)
    V = [vel[N * (i + 1) : N * (i + 2)] for i in range(W)]
    b = np.stack([-np.sum(Q * V[i], axis=1) for i in range(W)], axis=1)
    PL = np.sum(QL * vel[:N], axis=1)
    M = np.zeros((N, W, W))
    spin = np.nan_to_num(r.pose_velocity)[..., 2]
    for spec in ms.values():
        v = _point_velocity(asm, r, spec.link, spec.centre, 1)
        om = spin[:, asm.col[spec.link] // 3]
        vs = [v[N * (i + 1) : N * (i + 2)] for i in range(W)]
        oms = [om[N * (i + 1) : N * (i + 2)] for i in range(W)]
        for i in range(W):
            for j in range(i, W):
                add = spec.mass * np.sum(vs[i] * vs[j], axis=1) + spec.inertia * oms[i] * oms[j]
                M[:, i, j] += add
                if j != i:
                    M[:, j, i] += add
    closed = np.all(r.closed.reshape(W + 1, N), axis=0) & np.all(np.isfinite(r.xddot), axis=1).reshape(W + 1, N).all(0)
    return M, b, PL, closed


def dynamic_terms(mech, q, qdot=None, masses=None, loads=None, gravity=None):
    """Mass matrix and velocity/load terms of the equations of motion in the inputs: ``tau = M(q) q'' + b(q, q')``.

    Parameters
    ----------
    mech : Mechanism
    q, qdot : array_like
        Input rows ``(N,)`` or ``(N, W)`` and their speeds (default 1).
    masses, loads, gravity
        As for :func:`inverse_dynamics`; loads constant (one value for every row).

    Returns
    -------
    M : (N, W, W) mass matrix ``sum m V_G^T V_G + I_G w^T w`` (``V_G``, ``w``: velocity of the centre
        of mass and angular velocity per unit speed of each input).
    b : (N, W) driver forces needed at ``q'' = 0``: convective (centripetal, Coriolis) terms
        minus the generalized forces of the loads and weights.
    load_power : (N,) power of the loads and weights at ``qdot``.
    closed : (N,) rows where the mechanism closes.

    Examples
    --------
    A crank with a 3 kg mass at radius 2 and a 0.5 kg m^2 inertia: ``M = 3 * 4 + 0.5``, ``b = 0``:

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [2, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> M, b, P, ok = dynamic_terms(m, [0.3], 5.0, masses={"crank": {"mass": 3.0, "centre": "A", "inertia": 0.5}})
    >>> M.tolist(), (np.round(b, 9) + 0.0).tolist()
    ([[[12.5]]], [[0.0]])

    Notes
    -----
    Lagrange's equations in the independent coordinates (the inputs),
    obtained by projecting the d'Alembert forces of the links on the
    velocities per unit input speed (Kane's method / virtual work,
    T. R. Kane and D. A. Levinson, *Dynamics: Theory and Applications*,
    McGraw-Hill, 1985, ch. 6; Nikravesh 1988, ch. 6): ``tau_i = -V_i^T Q``
    with ``Q`` the loads, weights and inertia forces.  The accelerations are
    linear in ``q''``: ``M`` comes from the partial velocities and ``b`` from
    the kinematic solver's analytic accelerations at ``q'' = 0``, so
    :func:`inverse_dynamics` (ideal meshes) gives ``M q'' + b``.
    """
    qa, qd, _ = _rows_of(mech, q, qdot, None)
    m = mech.model
    ms = parse_masses(m, masses)
    lds = parse_loads(m, loads, 1)
    _constant_only(lds)
    return _terms(mech, qa, qd, ms, lds, gravity_of(m, gravity))


def _constant_only(lds):
    for ld in lds:
        if (ld.force is not None and ld.force.shape[0] != 1) or (ld.torque is not None and ld.torque.shape[0] != 1):
            raise GearleverError("loads: simulate takes constant loads only")


@dataclass(frozen=True)
class Simulation(Result):
    """Motion of a mechanism with ``W`` inputs under driving torques (or forces, slider inputs).

    Attributes
    ----------
    t : (N,) times (s).
    q, qdot, qddot : (N, W) inputs (rad, or length for slider inputs), speeds, accelerations,
        columns in ``[[inputs]]`` order (named in :attr:`inputs`).
    torque : (N, W) driving torque (force for a slider input) of each input.
    kinetic_energy : (N,) ``qdot^T M(q) qdot / 2``.
    inertia : (N, W, W) mass matrix ``M(q)`` (for one input the reduced inertia ``J(q)``).
    work : (N,) work done by the drivers since ``t[0]``.
    load_work : (N,) work done by the loads and weights since ``t[0]``.
    inputs : names of the inputs.
    loss_work : (N,) energy the meshes and the joints' friction dissipated since ``t[0]`` (zero without losses):
        ``kinetic_energy - kinetic_energy[0] = work + load_work - loss_work`` (energy balance).
    """

    t: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    qddot: np.ndarray
    torque: np.ndarray
    kinetic_energy: np.ndarray
    inertia: np.ndarray
    work: np.ndarray
    load_work: np.ndarray
    inputs: tuple
    loss_work: np.ndarray

    def _frame_columns(self) -> dict:
        cols = {"t_s": self.t}
        for i, name in enumerate(self.inputs):
            cols[f"{name}_q"] = self.q[:, i]
            cols[f"{name}_qdot"] = self.qdot[:, i]
            cols[f"{name}_qddot"] = self.qddot[:, i]
            cols[f"{name}_torque"] = self.torque[:, i]
        cols["kinetic_energy"] = self.kinetic_energy
        cols["work"] = self.work
        cols["load_work"] = self.load_work
        cols["loss_work"] = self.loss_work
        return cols


def _torque_function(torque, m):
    """``f(t, q (W,), qdot (W,)) -> (W,)`` from a number, ``(W,)`` numbers, ``{input: number or callable}``
    or a callable (for one input called with floats and returning a number)."""
    labels = [spec.label for spec in m.inputs]
    W = len(labels)
    if callable(torque):
        if W == 1:
            return lambda t, q, qd: np.array([float(torque(t, q[0], qd[0]))])

        def f(t, q, qd):
            v = np.asarray(torque(t, q, qd), dtype=float)
            if v.shape != (W,):
                raise GearleverError(f"torque: the callable must return {W} numbers (one per input), got {v.shape}")
            return v

        return f
    if isinstance(torque, dict):
        parts = []
        for k, v in torque.items():
            if k not in labels:
                raise GearleverError(f"torque: unknown input {k!r} (inputs: {', '.join(labels)})")
            parts.append((labels.index(k), v if callable(v) else _capped_torque(f"torque[{k!r}]", v)))

        def fd(t, q, qd):
            out = np.zeros(W)
            for i, v in parts:
                out[i] = float(v(t, q, qd)) if callable(v) else v
            return out

        return fd
    a = np.asarray(torque, dtype=float) if not isinstance(torque, str) else np.array(np.nan)
    if a.ndim == 0 and (W == 1 or float(a) == 0.0):
        a = np.full(W, float(a))
    if a.shape != (W,) or not np.all(np.isfinite(a)):
        raise GearleverError(
            f"torque must be a finite number (one input), {W} numbers, {{input: number or f(t, q, qdot)}} "
            f"or f(t, q, qdot), got {torque!r}"
        )
    for i, v in enumerate(a):
        _capped_torque(f"torque[{labels[i]!r}]", v)
    return lambda t, q, qd: a


def _capped_torque(where: str, v) -> float:
    """A constant driving torque: finite and at most :data:`~gearlever.mechanism.loads.MAX_LOAD` in size."""
    from gearlever.mechanism.loads import MAX_LOAD

    x = V.finite(where, v)
    if abs(x) > MAX_LOAD:
        raise GearleverError(f"{where} must be at most {MAX_LOAD:g} in size (the motion would overflow), got {x:g}")
    return x


def simulate(
    mech,
    t,
    q0,
    qdot0,
    torque=0.0,
    masses=None,
    loads=None,
    gravity=None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    grid: int = SIM_GRID,
    max_evals: int = MAX_EVALS,
    efficiency=None,
    friction=None,
) -> Simulation:
    """Integrate the equations of motion ``M(q) q'' + b(q, q') = tau(t, q, q')`` in the inputs.

    Parameters
    ----------
    mech : Mechanism
    t : array_like
        Increasing output times (s); the motion starts at ``t[0]``.
    q0, qdot0 : float or (W,)
        Inputs (rad, or length for slider inputs) and their speeds at ``t[0]``.
    torque : number, (W,), dict or callable
        Driving torque (force, slider input) of each input: a number (one
        input, or 0 for all), ``W`` numbers, ``{input label: number or f(t, q, qdot)}``
        (missing inputs free), or ``f(t, q, qdot)`` returning ``W`` numbers
        (one input: called with floats, returns a number).
    masses, loads, gravity
        As for :func:`inverse_dynamics`; loads must be constant (not arrays over rows).
    rtol, atol : float
        Tolerances of :func:`scipy.integrate.solve_ivp` (method DOP853).
    grid : int
        One rotary input that turns fully: points per turn of the periodic
        tables of ``J`` and of the loads' generalized force (over as many
        turns as they take to repeat, at most 12).
    max_evals : int
        Several inputs (or one that does not repeat after a turn): cap on the
        evaluations of the equations of motion; a longer run is refused.
    efficiency : float or dict, optional
        Mesh efficiency (default the model's).  With losses the driver forces
        depend on the direction of the power flow through each mesh, found
        at every evaluation by a fixed point (:func:`inverse_dynamics`); the
        equations are then only piecewise smooth (slower integration where a
        direction switches), and a train that locks is refused.
    friction : dict, optional
        Joint friction as the model's ``[friction]`` (default the model's):
        at every evaluation ``q''`` solves ``tau(q'') = tau`` of the
        inverse dynamics with friction (:func:`inverse_dynamics`) by Newton
        steps on finite-difference slopes; its dissipated power joins
        ``loss_work``.

    Returns
    -------
    Simulation

    Examples
    --------
    A free crank with a 1 kg mass at radius 1 keeps its speed:

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> s = simulate(m, [0.0, 1.0], 0.0, 2.0, masses={"crank": {"mass": 1.0, "centre": "A"}})
    >>> np.round(s.q[:, 0], 9).tolist(), np.round(s.kinetic_energy, 9).tolist()
    ([0.0, 2.0], [2.0, 2.0])

    Notes
    -----
    Lagrange's equations in the input coordinates (:func:`dynamic_terms`;
    Nikravesh 1988, ch. 6; Kane and Levinson 1985, ch. 6): ``M`` is the
    mass matrix of the kinetic energy ``T = q'^T M q' / 2`` and ``b`` the
    convective terms minus the loads' generalized forces, from the kinematic
    solver's analytic velocities and accelerations; ``q'' = M^-1 (tau - b)``.
    Where ``M``, ``b`` repeat after a whole number of turns of a rotary input
    (checked numerically, at most 12 turns) they are evaluated within half a
    period of the start, which keeps each kinematic solve short.

    One rotary input that turns fully and repeats after ``k`` turns: the
    "equation of motion of a machine" of the reduced-inertia method,
    ``J(q) q'' + J'(q)/2 q'^2 = Q`` with ``J`` and the loads' generalized
    force tabulated over ``k`` turns and interpolated by periodic cubic
    splines (``J'`` their derivative), integrated in the variables ``q`` and
    ``u = sqrt(J) q'``: ``q' = u / sqrt(J)``, ``u' = Q / sqrt(J)``, which
    keeps ``J q'^2 / 2 = u^2 / 2`` constant to rounding when ``Q = 0``.

    The drivers' work ``int tau . q' dt``, the loads' ``int P_L dt`` and the
    meshes' losses are integrated with the motion, so
    ``T(t) - T(t0) = work + load_work - loss_work`` can be checked.
    """
    m = mech.model
    W = len(m.inputs)
    tt = V.nonempty_array("t", t)
    if tt.ndim != 1 or (tt.size > 1 and np.any(np.diff(tt) <= 0)):
        raise GearleverError("t must be a 1-D array of increasing times")
    q0a = np.atleast_1d(np.asarray(q0, dtype=float)).ravel()
    qd0a = np.atleast_1d(np.asarray(qdot0, dtype=float)).ravel()
    for name, a in (("q0", q0a), ("qdot0", qd0a)):
        if a.shape != (W,) or not np.all(np.isfinite(a)):
            raise GearleverError(f"{name} must be {W} finite number(s), one per input, got {a.tolist()}")
    grid = V.positive_int("grid", grid)
    if grid < 16 or grid > 100_000:
        raise GearleverError(f"grid must be between 16 and 100000, got {grid}")
    max_evals = V.positive_int("max_evals", max_evals)
    effs = mesh_efficiency_of(m, efficiency)
    from gearlever.mechanism.friction import parse_friction

    fr = parse_friction(m, friction)
    lossy = any(e < 1.0 for e in effs.values()) or bool(fr)
    ms = parse_masses(m, masses)
    lds = parse_loads(m, loads, 1)
    _constant_only(lds)
    g = gravity_of(m, gravity)
    tau = _torque_function(torque, m)
    # overflow is not warned about: every evaluation is checked and a non-finite one refused
    with np.errstate(over="ignore", invalid="ignore"):
        raw = dict(masses=masses, loads=loads, gravity=g, efficiency=effs) if lossy else None
        if fr:
            raw["friction"] = friction
        return _simulate_any(mech, m, W, tt, q0a, qd0a, tau, ms, lds, g, rtol, atol, grid, max_evals, raw)


def _simulate_any(mech, m, W, tt, q0a, qd0a, tau, ms, lds, g, rtol, atol, grid, max_evals, raw):
    """:func:`simulate` after its checks: the periodic tables for one rotary input, else the general equations."""
    if W == 1 and m.inputs[0].kind == "link" and raw is None:
        period = _periods(mech, q0a, ms, lds, g)[0]
        if np.isfinite(period):
            turns = round(period / (2 * np.pi))
            out = _simulate_periodic(
                mech, tt, float(q0a[0]), float(qd0a[0]), tau, ms, lds, g, rtol, atol, grid, turns, max_evals
            )
            if out is not None:
                return out
    return _simulate_general(mech, tt, q0a, qd0a, tau, ms, lds, g, rtol, atol, max_evals, raw)


#: One input on spline tables: an evaluation costs about 1/50 of a kinematic solve, so it may take this many
#: times ``max_evals`` evaluations (10^6 by default, about a minute at most).
SPLINE_EVALS_FACTOR = 5
#: Largest number of turns of a rotary input tried as the period of the equations of motion.
MAX_PERIOD_TURNS = 12


def _periods(mech, q0, ms, lds, g):
    """Period (rad) of the equations of motion in each rotary input, ``inf`` if none up to MAX_PERIOD_TURNS turns.

    ``M``, ``b`` and the loads' power depend on the inputs through the link
    poses; a gear pair of ratio ``z_a / z_b`` repeats them after a whole
    number of turns only (three for 20:30).  Checked at three sample states.
    """
    m = mech.model
    W = len(m.inputs)
    rng = np.random.default_rng(0)
    qs = q0[None, :] + rng.uniform(-1.0, 1.0, (3, W))
    qds = rng.uniform(0.5, 1.5, (3, W))
    ref = _terms(mech, qs, qds, ms, lds, g)
    out = np.full(W, np.inf)
    for i, spec in enumerate(m.inputs):
        if spec.kind != "link":
            continue
        for k in range(1, MAX_PERIOD_TURNS + 1):
            shift = np.zeros(W)
            shift[i] = 2 * np.pi * k
            got = _terms(mech, qs + shift, qds, ms, lds, g)
            if not (ref[3].all() and got[3].all()):
                break
            if all(
                np.allclose(a, b, rtol=0, atol=1e-10 * max(np.abs(a).max(), 1e-300)) for a, b in zip(ref[:3], got[:3])
            ):
                out[i] = 2 * np.pi * k
                break
    return out


def _lossy_acceleration(mech, time, q, qd, tq, qdd, raw):
    """``q''`` and the meshes' dissipated power with losses: fixed point on the power-flow directions.

    For given directions the driver forces are linear in ``q''`` (the lossy
    equilibrium rows do not depend on it): ``tau = A q'' + c`` from one
    inverse-dynamics call of ``W + 1`` rows; solve, find the directions at the
    new ``q''``, repeat until they agree.
    """
    W = q.size
    if raw.get("friction") is not None or mech.model.extra.get("friction"):
        return _friction_acceleration(mech, time, q, qd, tq, qdd, raw)
    for _ in range(MAX_PASSES):
        d = inverse_dynamics(mech, q[None, :], qd[None, :], qdd[None, :], **raw)
        drv = np.array([[v[0] for v in d.mesh_driven.values()]], dtype=np.int8)
        rows_qdd = np.vstack([np.zeros(W), np.eye(W)])
        dd = inverse_dynamics(
            mech, np.repeat(q[None, :], W + 1, 0), np.repeat(qd[None, :], W + 1, 0), rows_qdd, **raw, _driven=drv
        )
        c = dd.input_force[0]
        A = (dd.input_force[1:] - c).T
        if not np.all(np.isfinite(A)) or not np.all(np.isfinite(c)):
            raise GearleverError(
                f"simulate: at t = {time:.6g} s the lossy equations have no solution (the train locks)"
            )
        new = np.linalg.solve(A, tq - c)
        loss = np.array([v[0] + (v[1:] - v[0]) @ new for v in dd.mesh_loss.values()]).sum()
        if np.allclose(new, qdd, rtol=1e-11, atol=1e-11 * (1.0 + np.abs(new).max())):
            return new, float(loss)
        qdd = new
    raise GearleverError(  # pragma: no cover - the directions settle in a pass or two away from switching points
        f"self-locking: at t = {time:.6g} s the power flow through the meshes does not settle (the train locks)"
    )


def _friction_acceleration(mech, time, q, qd, tq, qdd, raw):
    """``q''`` and the dissipated power with joint friction: Newton steps on ``tau(q'') = tq``.

    ``tau(q'')`` is the inverse dynamics with friction (and mesh losses); its
    slopes are finite differences of ``W`` rows ``h`` apart around the
    current ``q''`` (piecewise linear in ``q''``: the friction magnitudes are
    norms of reactions linear in it), so the steps end in a few passes.
    """
    W = q.size
    for _ in range(4 * MAX_PASSES):
        h = 1e-3 * (1.0 + np.abs(qdd).max())
        rows = qdd[None, :] + np.vstack([np.zeros(W), h * np.eye(W)])
        dd = inverse_dynamics(mech, np.repeat(q[None, :], W + 1, 0), np.repeat(qd[None, :], W + 1, 0), rows, **raw)
        c = dd.input_force[0]
        A = (dd.input_force[1:] - c).T / h
        if not np.all(np.isfinite(A)) or not np.all(np.isfinite(c)):
            raise GearleverError(f"simulate: at t = {time:.6g} s the equations with friction have no solution (locks)")
        step = np.linalg.solve(A, tq - c)
        new = qdd + step
        if np.allclose(step, 0.0, rtol=0, atol=1e-11 * (1.0 + np.abs(new).max())):
            d = inverse_dynamics(mech, q[None, :], qd[None, :], new[None, :], **raw)
            loss = sum(float(v[0]) for v in d.mesh_loss.values()) + sum(float(v[0]) for v in d.friction_loss.values())
            return new, loss
        qdd = new
    raise GearleverError(f"self-locking: at t = {time:.6g} s the motion with joint friction does not settle (locks)")


class WorkCapError(GearleverError):
    """A simulation refused for its work: ``need`` evaluations (estimated; ``inf`` if unknown) over the ``cap``.

    ``reached`` is the time the integration got to in ``count`` evaluations
    and ``reach`` about the end time that the cap allows.
    """

    def __init__(self, message, *, need, cap, count, reached, reach):
        super().__init__(message)
        self.need, self.cap, self.count, self.reached, self.reach = need, cap, count, reached, reach


def _check_work(count: int, reached: float, t0: float, t1: float, cap: int, what: str) -> None:
    """Refuse a run past ``cap`` evaluations, or one whose progress so far projects more than ``cap``.

    ``count`` evaluations have brought the integration from ``t0`` to
    ``reached`` (of ``t1``).  At :data:`PROBE_EVALS` evaluations and at each
    doubling after, the work of the whole run is estimated as ``count (t1 -
    t0) / (reached - t0)``; a motion that speeds up needs more (the cap then
    stops it), one that slows down less, so the estimate is only acted on
    when it is over the cap.
    """
    if count > cap:
        raise WorkCapError(
            f"simulate: more than {what} = {cap} evaluations of the equations of motion; "
            "simulate a shorter time or loosen rtol",
            need=math.inf,
            cap=cap,
            count=count,
            reached=reached,
            reach=reached,
        )
    k, rest = divmod(count, PROBE_EVALS)
    if k >= 1 and rest == 0 and (k & (k - 1)) == 0:  # at PROBE_EVALS x 1, 2, 4, 8, ...
        done = reached - t0
        need = math.inf if done <= 0 else count * (t1 - t0) / done
        if need > cap:
            reach = t0 + (t1 - t0) * cap / need if math.isfinite(need) else t0
            raise WorkCapError(
                f"simulate: the motion needs about {need:.3g} evaluations of the equations of motion to reach "
                f"t = {t1:.6g} s (it reached t = {reached:.6g} s in {count}), more than {what} = {cap}; "
                f"simulate a shorter time (about {reach:.3g} s) or loosen rtol",
                need=need,
                cap=cap,
                count=count,
                reached=reached,
                reach=reach,
            )


def _integration_failed(sol, count: int):
    """Refuse a run the integrator gave up on (its steps fell below the float spacing: accelerations out of scale)."""
    t = float(sol.t[-1]) if len(sol.t) else math.nan
    raise WorkCapError(
        f"simulate: the motion cannot be integrated past t = {t:.6g} s ({sol.message.rstrip('.')}): "
        "the accelerations are out of scale; the torques, loads or speeds must be smaller",
        need=math.inf,
        cap=count,
        count=count,
        reached=t,
        reach=t,
    )


def _finite_state(time, values, what: str) -> None:
    """Refuse an evaluation of the equations of motion that overflowed (inf or NaN), naming ``what``."""
    if not np.all(np.isfinite(values)):
        raise GearleverError(
            f"simulate: at t = {time:.6g} s the {what} overflow floating point: the torques, loads or speeds "
            "must be smaller, or the masses larger"
        )


def _simulate_general(mech, tt, q0, qd0, tau, ms, lds, g, rtol, atol, max_evals, raw=None):
    from scipy.integrate import solve_ivp

    m = mech.model
    W = len(m.inputs)
    count = [0]
    period = _periods(mech, q0, ms, lds, g)
    fin = np.isfinite(period)
    per = np.where(fin, period, 1.0)

    def accel(time, q, qd):
        # the terms repeat with the period: evaluate within half a period of the start (short continuation)
        qe = np.where(fin, q0 + np.mod(q - q0 + per / 2, per) - per / 2, q)
        M, b, PL, closed = _terms(mech, qe[None, :], qd[None, :], ms, lds, g)
        if not closed[0]:
            raise GearleverError(
                f"simulate: at t = {time:.6g} s the mechanism does not close at q = {np.round(q, 9).tolist()} "
                "(the motion reaches a limit of the inputs' range)"
            )
        Mq = M[0]
        ev = np.linalg.eigvalsh(Mq)
        if not ev[0] > 1e-12 * max(ev[-1], 1e-300):
            raise GearleverError(
                f"simulate: the mass matrix is singular at t = {time:.6g} s, q = {np.round(q, 9).tolist()} "
                "(give masses or inertias to links that every input moves)"
            )
        tq = tau(time, q, qd)
        qdd = np.linalg.solve(Mq, tq - b[0])
        loss = 0.0
        if raw is not None:
            qdd, loss = _lossy_acceleration(mech, time, qe, qd, tq, qdd, raw)
        return qdd, tq, PL[0], Mq, loss

    reached = [float(tt[0])]

    def rhs(time, y):
        count[0] += 1
        reached[0] = max(reached[0], float(time))
        _check_work(count[0], reached[0], float(tt[0]), float(tt[-1]), max_evals, "max_evals")
        q, qd = y[:W], y[W : 2 * W]
        qdd, tq, PL, _, loss = accel(time, q, qd)
        out = np.concatenate([qd, qdd, [tq @ qd, PL, loss]])
        _finite_state(time, out, "accelerations")
        return out

    y0 = np.concatenate([q0, qd0, [0.0, 0.0, 0.0]])
    sol = solve_ivp(rhs, (tt[0], tt[-1]), y0, t_eval=tt, method="DOP853", rtol=rtol, atol=atol)
    if not sol.success:
        _integration_failed(sol, count[0])
    q, qd = sol.y[:W].T, sol.y[W : 2 * W].T
    n = len(sol.t)
    qdd, tq, Ms = np.zeros((n, W)), np.zeros((n, W)), np.zeros((n, W, W))
    for k in range(n):
        qdd[k], tq[k], _, Ms[k], _ = accel(sol.t[k], q[k], qd[k])
    ke = 0.5 * np.einsum("ni,nij,nj->n", qd, Ms, qd)
    return Simulation(
        t=sol.t,
        q=q,
        qdot=qd,
        qddot=qdd,
        torque=tq,
        kinetic_energy=ke,
        inertia=Ms,
        work=sol.y[2 * W],
        load_work=sol.y[2 * W + 1],
        inputs=tuple(spec.label for spec in m.inputs),
        loss_work=sol.y[2 * W + 2],
    )


def _simulate_periodic(mech, tt, q0, qdot0, tau, ms, lds, g, rtol, atol, grid, turns=1, max_evals=MAX_EVALS):
    """One rotary input that turns fully, ``J`` repeating after ``turns`` turns (spline tables); None otherwise."""
    from scipy.integrate import solve_ivp
    from scipy.interpolate import CubicSpline

    m = mech.model
    qg = q0 + np.linspace(0.0, 2 * np.pi * turns, grid * turns + 1)
    r = mech.solve(qg, np.ones_like(qg), np.zeros_like(qg))
    if not r.closed.all():
        return None
    J, _, _, _ = _terms(mech, qg[:, None], np.ones((len(qg), 1)), ms, [], np.zeros(2))
    J = J[:, 0, 0]
    if not np.all(np.isfinite(J)) or np.any(J <= 0):
        raise GearleverError("simulate: the reduced inertia must be positive over the turn (give masses)")
    N1 = len(qg)
    QL = _load_power(mech, r, ms, _const_loads(lds, N1), g)
    scale = max(abs(J).max(), 1e-300)
    if abs(J[-1] - J[0]) > 1e-7 * scale or abs(QL[-1] - QL[0]) > 1e-7 * max(abs(QL).max(), 1e-300):
        return None
    J[-1] = J[0]
    QL[-1] = QL[0]
    Js = CubicSpline(qg, J, bc_type="periodic")
    dJs = Js.derivative()
    Qs = CubicSpline(qg, QL, bc_type="periodic")
    period = 2 * np.pi * turns

    def wrap(q):
        return q0 + np.mod(q - q0, period)

    def torque1(time, q, qd):
        return float(tau(time, np.array([q]), np.array([qd]))[0])

    count = [0]
    reached = [float(tt[0])]

    def rhs(time, state):
        count[0] += 1
        reached[0] = max(reached[0], float(time))
        what = f"{SPLINE_EVALS_FACTOR} x max_evals"
        _check_work(count[0], reached[0], float(tt[0]), float(tt[-1]), SPLINE_EVALS_FACTOR * max_evals, what)
        q, u = state[0], state[1]
        qq = wrap(q)
        sJ = np.sqrt(Js(qq))
        qd = u / sJ
        tq = torque1(time, q, qd)
        ql = Qs(qq)
        out = [qd, (tq + ql) / sJ, tq * qd, ql * qd]
        _finite_state(time, out, "accelerations")
        return out

    u0 = math.sqrt(Js(wrap(q0))) * qdot0
    sol = solve_ivp(rhs, (tt[0], tt[-1]), [q0, u0, 0.0, 0.0], t_eval=tt, method="DOP853", rtol=rtol, atol=atol)
    if not sol.success:
        _integration_failed(sol, count[0])
    q, u = sol.y[0], sol.y[1]
    qq = wrap(q)
    Jq = Js(qq)
    qd = u / np.sqrt(Jq)
    tq = np.array([torque1(ti, qi, di) for ti, qi, di in zip(sol.t, q, qd)])
    qdd = (tq + Qs(qq) - 0.5 * dJs(qq) * qd * qd) / Jq
    return Simulation(
        t=sol.t,
        q=q[:, None],
        qdot=qd[:, None],
        qddot=qdd[:, None],
        torque=tq[:, None],
        kinetic_energy=0.5 * Jq * qd * qd,
        inertia=Jq[:, None, None],
        work=sol.y[2],
        load_work=sol.y[3],
        inputs=(m.inputs[0].label,),
        loss_work=np.zeros_like(sol.t),
    )
