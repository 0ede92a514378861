"""Constraint equations of a mechanism model in absolute coordinates, with the analytic Jacobian.

Each moving link ``k`` has the pose ``(x_k, y_k, theta_k)``: the position of
its first point (the origin of its body frame) and its angle (that of the
line from its first point to its second; for a one-point link its sketch
angle 0 plus its rotation).  Ground keeps its sketch pose.  A point with
body-fixed coordinates ``rho`` on link ``k`` is at ``r_k + R(theta_k) rho``.

Constraint rows, in this order:

- every revolute pair ``(P, i, j)``: 2 rows, ``r_i + R_i rho_iP - r_j - R_j rho_jP = 0``;
- every slider (``link`` L on ``on`` O, guide through G along ``u``): 2 rows,
  ``n_O . (p_L(G) - g_O) = 0`` (G stays on the guide line; ``n_O`` is the
  guide's normal turned with O, ``g_O`` the guide's sketch point carried by
  O) and ``theta_L - theta_O - (theta_L0 - theta_O0) = 0`` (no relative turn);
- every mesh (gears a, b, carrier c): 1 row,
  ``(phi_b - phi_c) - i (phi_a - phi_c) = 0``, ``phi`` the rotations from the
  sketch and ``i`` the signed Willis ratio of the pair
  (:func:`gearlever.gears.willis.basic_ratio`, ``-z_a/z_b`` external,
  ``+z_a/z_b`` internal), i.e. ``z_a (phi_a - phi_c) = -+ z_b (phi_b - phi_c)``.

Columns: ``x, y, theta`` of each moving link in :attr:`MechanismModel.moving`
order (3 n columns).  Pure numpy, batched over any leading shape.
"""

from __future__ import annotations

import numpy as np

from gearlever.gears.willis import basic_ratio
from gearlever.mechanism.model import GROUND, MechanismModel

__all__ = ["constraint_labels", "sketch_pose", "constraint_residual", "constraint_jacobian", "mesh_coefficients"]


def constraint_labels(model: MechanismModel) -> tuple:
    """Names of the constraint rows, in row order.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> constraint_labels(m)
    ('pin O ground-crank x', 'pin O ground-crank y')
    """
    out = []
    for p, a, b in model.joints:
        out += [f"pin {p} {a}-{b} x", f"pin {p} {a}-{b} y"]
    for s in model.sliders:
        out += [f"slider {s.name} on {s.on} normal", f"slider {s.name} on {s.on} angle"]
    for m in model.meshes:
        out.append(f"mesh {m.name} on {m.carrier}")
    return tuple(out)


def mesh_coefficients(model: MechanismModel, mesh) -> dict:
    """Coefficients of the rotations ``phi`` (of the gears' links and the carrier) in a mesh row.

    Returns
    -------
    dict
        Link name -> coefficient; the row is ``sum(coef * phi_link) = 0``.

    Notes
    -----
    Willis' inverted-motion equation (R. Willis, *Principles of Mechanism*,
    1841): seen from the carrier the pair is an ordinary mesh,
    ``(omega_b - omega_c) / (omega_a - omega_c) = i`` with the signed basic
    ratio ``i`` of :func:`gearlever.gears.willis.basic_ratio`; rotations from
    the sketch obey the same linear relation.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "P": [3, 0]},
    ...     "links": {"ground": ["O", "P"], "g1": ["O"], "g2": ["P"]},
    ...     "gears": {"a": {"link": "g1", "centre": "O", "teeth": 20},
    ...               "b": {"link": "g2", "centre": "P", "teeth": 40}},
    ...     "meshes": [{"gears": ["a", "b"]}], "inputs": [{"link": "g1"}]})
    >>> mesh_coefficients(m, m.meshes[0])
    {'g1': 0.5, 'g2': 1.0, 'ground': -1.5}
    """
    ga, gb = model.gears[mesh.a], model.gears[mesh.b]
    i = basic_ratio(ga.teeth, gb.teeth, "internal" if model.mesh_internal(mesh) else "external")
    coef: dict = {}
    for link, c in ((ga.link, -i), (gb.link, 1.0), (mesh.carrier, i - 1.0)):
        coef[link] = coef.get(link, 0.0) + c
    return coef


def sketch_pose(model: MechanismModel) -> np.ndarray:
    """Poses ``(x, y, theta)`` of the moving links in the sketch, shape ``(n, 3)``.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [0, 2]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> sketch_pose(m).round(6).tolist()
    [[0.0, 0.0, 1.570796]]
    """
    return np.array([[*model.links[k].origin, model.links[k].angle0] for k in model.moving], dtype=float)


def _pose_of(model, pose, link):
    """(x, y, theta) arrays of ``link`` (ground: its sketch pose, broadcast)."""
    if link == GROUND:
        g = model.links[GROUND]
        shape = pose.shape[:-2]
        return (np.full(shape, g.origin[0]), np.full(shape, g.origin[1]), np.full(shape, g.angle0))
    k = model.moving.index(link)
    return pose[..., k, 0], pose[..., k, 1], pose[..., k, 2]


def _rot(theta, v):
    c, s = np.cos(theta), np.sin(theta)
    return c * v[0] - s * v[1], s * v[0] + c * v[1]


def _guide(model, s):
    """Guide point and unit direction of slider ``s`` in the body frame of ``s.on``."""
    on = model.links[s.on]
    c, si = np.cos(on.angle0), np.sin(on.angle0)
    gx, gy = model.points[s.point][0] - on.origin[0], model.points[s.point][1] - on.origin[1]
    ux, uy = s.direction
    return (c * gx + si * gy, -si * gx + c * gy), (c * ux + si * uy, -si * ux + c * uy)


def constraint_residual(model: MechanismModel, pose) -> np.ndarray:
    """Residual of every constraint row at the link poses.

    Parameters
    ----------
    model : MechanismModel
    pose : array_like
        Shape ``(..., n, 3)``: ``x, y, theta`` of each moving link.

    Returns
    -------
    ndarray
        Shape ``(..., m)``, rows as :func:`constraint_labels`; zero at an
        assembly.

    Notes
    -----
    Absolute (Cartesian) coordinates as in P. E. Nikravesh, *Computer-Aided
    Analysis of Mechanical Systems* (Prentice Hall, 1988), ch. 4: revolute
    and translational joints, plus the mesh row of :func:`mesh_coefficients`.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> constraint_residual(m, [[0.0, 0.0, 1.0]]).tolist()
    [0.0, 0.0]
    """
    pose = np.asarray(pose, dtype=float)
    rows = []
    for p, a, b in model.joints:
        xa, ya, ta = _pose_of(model, pose, a)
        xb, yb, tb = _pose_of(model, pose, b)
        ra, rb = _rot(ta, model.links[a].local[p]), _rot(tb, model.links[b].local[p])
        rows += [xa + ra[0] - xb - rb[0], ya + ra[1] - yb - rb[1]]
    for s in model.sliders:
        xl, yl, tl = _pose_of(model, pose, s.link)
        xo, yo, to = _pose_of(model, pose, s.on)
        g, u = _guide(model, s)
        rl = _rot(tl, model.links[s.link].local[s.point])
        rg = _rot(to, g)
        nx, ny = _rot(to, (-u[1], u[0]))
        dx, dy = xl + rl[0] - xo - rg[0], yl + rl[1] - yo - rg[1]
        rows.append(nx * dx + ny * dy)
        rows.append(tl - to - (model.links[s.link].angle0 - model.links[s.on].angle0))
    for m in model.meshes:
        acc = 0.0
        for link, c in mesh_coefficients(model, m).items():
            acc = acc + c * (_pose_of(model, pose, link)[2] - model.links[link].angle0)
        rows.append(np.broadcast_to(acc, pose.shape[:-2]))
    if not rows:
        return np.zeros(pose.shape[:-2] + (0,))
    return np.stack(rows, axis=-1)


def constraint_jacobian(model: MechanismModel, pose) -> np.ndarray:
    """Analytic Jacobian of :func:`constraint_residual` with respect to the link poses.

    Parameters
    ----------
    model : MechanismModel
    pose : array_like
        Shape ``(..., n, 3)``.

    Returns
    -------
    ndarray
        Shape ``(..., m, 3 n)``: rows as :func:`constraint_labels`, columns
        ``x_k, y_k, theta_k`` for each moving link ``k`` in
        ``model.moving`` order.  The reactions of the pairs are
        ``-J^T lambda`` with the Lagrange multipliers ``lambda`` of these rows.

    Notes
    -----
    Nikravesh (*Computer-Aided Analysis of Mechanical Systems*, 1988),
    eqs. 4.8-4.20: for a revolute row the derivative with respect to
    ``theta_k`` is ``R'(theta_k) rho = (-(R rho)_y, (R rho)_x)``; for the
    slider's normal row ``d(n . d)/dtheta_O = n' . d - n . R'_O g``.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> constraint_jacobian(m, [[0.0, 0.0, 0.0]]).tolist() == [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]
    True
    """
    pose = np.asarray(pose, dtype=float)
    lead = pose.shape[:-2]
    n = len(model.moving)
    m_rows = 2 * len(model.joints) + 2 * len(model.sliders) + len(model.meshes)
    J = np.zeros(lead + (m_rows, 3 * n))
    col = {k: 3 * i for i, k in enumerate(model.moving)}

    def put(r, link, vals):
        if link == GROUND:
            return
        c = col[link]
        for j, v in enumerate(vals):
            if v is not None:
                J[..., r, c + j] += v

    r = 0
    for p, a, b in model.joints:
        for link, sign in ((a, 1.0), (b, -1.0)):
            _, _, t = _pose_of(model, pose, link)
            rx, ry = _rot(t, model.links[link].local[p])
            put(r, link, (sign, None, -sign * ry))
            put(r + 1, link, (None, sign, sign * rx))
        r += 2
    for s in model.sliders:
        xl, yl, tl = _pose_of(model, pose, s.link)
        xo, yo, to = _pose_of(model, pose, s.on)
        g, u = _guide(model, s)
        rl = _rot(tl, model.links[s.link].local[s.point])
        rg = _rot(to, g)
        nx, ny = _rot(to, (-u[1], u[0]))
        dx, dy = xl + rl[0] - xo - rg[0], yl + rl[1] - yo - rg[1]
        put(r, s.link, (nx, ny, nx * -rl[1] + ny * rl[0]))
        # n' = R' n_local = (-ny, nx); d(d)/dtheta_O = -R'_O g = (rg_y, -rg_x)
        put(r, s.on, (-nx, -ny, -ny * dx + nx * dy + nx * rg[1] - ny * rg[0]))
        put(r + 1, s.link, (None, None, 1.0))
        put(r + 1, s.on, (None, None, -1.0))
        r += 2
    for m in model.meshes:
        for link, c in mesh_coefficients(model, m).items():
            put(r, link, (None, None, c))
        r += 1
    return J
