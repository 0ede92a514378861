"""Batched simulation of dyadic linkages over a crank turn, with the analytic Jacobian.

Many candidates of one topology (a :class:`~gearlever.mechanism.linkage.SolvePlan`)
are solved at once: every candidate and every crank step in one array pass
per dyad, no solver per point.

Notes
-----
The challenge's kinematics (A. H. Nobari, F. Ahmed et al., MIT 2.156 linkage
synthesis challenge, ``LINKS.Kinematics``), implemented from its description:
the crank tip is at ``pivot + r (cos t, sin t)`` with ``r`` the sketch's crank
length and ``t`` the absolute crank angle, ``steps`` values evenly from 0 to
2 pi inclusive (200 in the challenge); a dyad joint ``k`` with parents ``i``,
``j`` is at ``x_i + alpha d + beta perp(d)`` with ``d = x_j - x_i``,
``alpha = (|d|^2 + a^2 - b^2) / (2 |d|^2)``, ``beta = s sqrt(a^2/|d|^2 - alpha^2)``,
``a``, ``b`` the sketch lengths ``|k - i|``, ``|k - j|`` and ``s`` the side of
the line ``i -> j`` the sketch puts ``k`` on (law of cosines; the branch of
the sketch).  Where ``alpha^2 > a^2/|d|^2`` the dyad cannot close: the
linkage locks and its positions are NaN from there on.

>>> import numpy as np
>>> from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
>>> lk = linkage_from_dict({"x0": [[0, 0], [1, 0], [4, 0], [3, 3]],
...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
>>> x = simulate(lk.x0[None], solve_plan(lk))
>>> x.shape, bool(np.isfinite(x).all())
((1, 4, 200, 2), True)
"""

from __future__ import annotations

import numpy as np

__all__ = ["STEPS", "crank_angles", "dyad_signs", "simulate", "simulate_jacobian"]

#: Crank steps over a turn, as in the challenge.
STEPS = 200


def crank_angles(steps: int = STEPS) -> np.ndarray:
    """Absolute crank angles: ``steps`` values from 0 to 2 pi inclusive."""
    return np.linspace(0.0, 2.0 * np.pi, steps)


def dyad_signs(x0s, plan) -> np.ndarray:
    """Side of each dyad joint from its parents' line in the sketch: +1 (left of ``i -> j``) or -1, (B, D)."""
    d = plan.dyads
    xi, xj, xk = x0s[:, d[:, 1]], x0s[:, d[:, 2]], x0s[:, d[:, 0]]
    u, v = xj - xi, xk - xi
    cross = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return np.where(cross < 0.0, -1.0, 1.0)


def simulate(x0s, plan, steps: int = STEPS, thetas=None) -> np.ndarray:
    """Positions of every joint of every candidate at every crank step.

    Parameters
    ----------
    x0s : array_like, shape (B, N, 2)
        Sketch positions of ``B`` candidates of one topology.
    plan : SolvePlan
        The topology's solve plan.
    steps : int
        Crank steps over 0..2 pi (inclusive).
    thetas : array_like, optional
        Crank angles (radians) instead of ``steps``.

    Returns
    -------
    ndarray, shape (B, N, T, 2)
        NaN from the step where a dyad cannot close (the candidate locks).

    Notes
    -----
    See the module docstring (law of cosines per dyad, branch of the sketch).

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
    >>> lk = linkage_from_dict({"x0": [[0, 0], [1, 0], [4, 0], [3, 3]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> x = simulate(lk.x0[None], solve_plan(lk), steps=5)
    >>> np.round(x[0, 1, :, 0], 6).tolist()  # crank tip x at 0, 90, 180, 270, 360 degrees
    [1.0, 0.0, -1.0, -0.0, 1.0]
    """
    x0s = np.asarray(x0s, dtype=float)
    th = crank_angles(steps) if thetas is None else np.asarray(thetas, dtype=float)
    B, N, _ = x0s.shape
    T = th.shape[0]
    x = np.empty((B, N, T, 2))
    x[:] = x0s[:, :, None, :]
    p, t = plan.pivot, plan.tip
    r = np.hypot(*(x0s[:, t] - x0s[:, p]).T)
    x[:, t, :, 0] = x0s[:, p, None, 0] + r[:, None] * np.cos(th)
    x[:, t, :, 1] = x0s[:, p, None, 1] + r[:, None] * np.sin(th)
    s = dyad_signs(x0s, plan)
    with np.errstate(invalid="ignore", divide="ignore"):
        for n, (k, i, j, _) in enumerate(plan.dyads):
            A = ((x0s[:, k] - x0s[:, i]) ** 2).sum(-1)[:, None]
            Bq = ((x0s[:, k] - x0s[:, j]) ** 2).sum(-1)[:, None]
            d = x[:, j] - x[:, i]
            L = (d**2).sum(-1)
            alpha = 0.5 + (A - Bq) / (2.0 * L)
            beta = s[:, n, None] * np.sqrt(A / L - alpha**2)
            x[:, k, :, 0] = x[:, i, :, 0] + alpha * d[..., 0] - beta * d[..., 1]
            x[:, k, :, 1] = x[:, i, :, 1] + alpha * d[..., 1] + beta * d[..., 0]
    return x


def simulate_jacobian(x0s, plan, steps: int = STEPS, thetas=None, joints=None):
    """Positions and their analytic Jacobian with respect to the sketch positions.

    Parameters
    ----------
    x0s, plan, steps, thetas
        As :func:`simulate`.
    joints : sequence of int, optional
        Joints whose Jacobian is returned (default all).

    Returns
    -------
    x : ndarray, shape (B, N, T, 2)
    J : ndarray, shape (B, len(joints), T, 2, 2 N)
        ``J[b, m, t, c, 2 q + e]`` = d x[b, joints[m], t, c] / d x0s[b, q, e].

    Notes
    -----
    Forward-mode differentiation of the closed form of the module docstring:
    ``dx_k = dx_i + dalpha d + alpha dd + dbeta perp(d) + beta perp(dd)`` with
    ``dalpha = (dA - dB) / (2 L) - (A - B) dL / (2 L^2)`` and
    ``dbeta = (dA / L - A dL / L^2 - 2 alpha dalpha) / (2 beta)``; the crank
    tip's ``dr = (x_tip - x_pivot) / r . (d x_tip - d x_pivot)``; the branch
    signs are piecewise constant.  Checked against finite differences in the
    tests.

    Examples
    --------
    >>> from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
    >>> lk = linkage_from_dict({"x0": [[0, 0], [1, 0], [4, 0], [3, 3]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> x, J = simulate_jacobian(lk.x0[None], solve_plan(lk), steps=10, joints=[3])
    >>> J.shape
    (1, 1, 10, 2, 8)
    """
    x0s = np.asarray(x0s, dtype=float)
    th = crank_angles(steps) if thetas is None else np.asarray(thetas, dtype=float)
    B, N, _ = x0s.shape
    T = th.shape[0]
    P = 2 * N
    x = simulate(x0s, plan, thetas=th)
    J = np.zeros((B, N, T, 2, P))
    eye = np.eye(P)
    for q in range(N):
        J[:, q, :, 0, :] = eye[2 * q]
        J[:, q, :, 1, :] = eye[2 * q + 1]
    p, t = plan.pivot, plan.tip
    dv = x0s[:, t] - x0s[:, p]
    r = np.hypot(dv[:, 0], dv[:, 1])
    dr = np.zeros((B, P))
    dr[:, 2 * t : 2 * t + 2] = dv / r[:, None]
    dr[:, 2 * p : 2 * p + 2] -= dv / r[:, None]
    cs = np.stack([np.cos(th), np.sin(th)], -1)  # (T, 2)
    J[:, t] = J[:, p] + cs[None, :, :, None] * dr[:, None, None, :]
    s = dyad_signs(x0s, plan)
    with np.errstate(invalid="ignore", divide="ignore"):
        for n, (k, i, j, _) in enumerate(plan.dyads):
            vk_i = x0s[:, k] - x0s[:, i]
            vk_j = x0s[:, k] - x0s[:, j]
            A = (vk_i**2).sum(-1)
            Bq = (vk_j**2).sum(-1)
            dA = np.zeros((B, P))
            dA[:, 2 * k : 2 * k + 2] += 2 * vk_i
            dA[:, 2 * i : 2 * i + 2] -= 2 * vk_i
            dB = np.zeros((B, P))
            dB[:, 2 * k : 2 * k + 2] += 2 * vk_j
            dB[:, 2 * j : 2 * j + 2] -= 2 * vk_j
            d = x[:, j] - x[:, i]  # (B, T, 2)
            dd = J[:, j] - J[:, i]  # (B, T, 2, P)
            L = (d**2).sum(-1)  # (B, T)
            dL = 2.0 * np.einsum("btc,btcp->btp", d, dd)
            A_, B_ = A[:, None], Bq[:, None]
            alpha = 0.5 + (A_ - B_) / (2.0 * L)
            beta = s[:, n, None] * np.sqrt(A_ / L - alpha**2)
            dalpha = (dA - dB)[:, None, :] / (2.0 * L[..., None]) - ((A_ - B_) / (2.0 * L**2))[..., None] * dL
            dbeta = (dA[:, None, :] / L[..., None] - (A_ / L**2)[..., None] * dL - 2.0 * alpha[..., None] * dalpha) / (
                2.0 * beta[..., None]
            )
            perp = np.stack([-d[..., 1], d[..., 0]], -1)
            dperp = np.stack([-dd[:, :, 1], dd[:, :, 0]], 2)
            J[:, k] = (
                J[:, i]
                + dalpha[:, :, None, :] * d[..., None]
                + alpha[..., None, None] * dd
                + dbeta[:, :, None, :] * perp[..., None]
                + beta[..., None, None] * dperp
            )
    if joints is not None:
        J = J[:, list(joints)]
    return x, J
