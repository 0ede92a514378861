"""Through branch points: the ``branch`` policy of the continuation (``"continue"``, ``"keep"``, ``"stop"``).

Where the closure Jacobian ``J_z`` of a mechanism becomes singular on the
way, two things can happen:

- a *dead point of the input* (a fold: the coupler and follower of a
  four-bar stretched out): no assembly exists past it, the input must
  reverse; it is a limit (:mod:`gearlever.mechanism.limits`) under every
  policy;
- a *branch point* (a bifurcation: two assembly branches cross, as the
  square-rod slider-crank where the rod stands square to the guide, or a
  parallelogram four-bar where all its links fold onto one line): the input
  goes on, and the mechanism can leave on either of two branches.

The policy says which:

``"continue"`` (the default)
    the branch that keeps the motion smooth: the one whose velocity is
    continuous with the incoming one, the input's direction kept.  Through a
    branch point the sign of ``det J_z`` changes: the assembly branch of the
    sketch (that sign) is left, and each change is recorded as a
    :class:`BranchPoint`.
``"keep"``
    the sketch's assembly branch (the sign of ``det J_z``, what a closed form
    with a fixed ``+-`` root gives): the position is continuous through the
    branch point but the velocity jumps there (the square-rod slider's
    slider turns back at full speed; a parallelogram becomes an
    anti-parallelogram); each such point is recorded too.
``"stop"``
    the continuation stops at the singular pose, as it does at a dead point:
    the rows past it are not closed (the behaviour before this policy; a row
    closed at the branch point itself is the last one).

How a branch point is crossed (:func:`cross`): from the state where the
continuation stopped, a state :data:`ETA` before it is solved on the
incoming branch, with its first and second derivatives along the path;
from there the incoming branch's Taylor expansion predicts the points up
to ``2 ETA`` past the stop and batched Newton corrects them.  When the far
point converges within the predictor's error (the same smooth curve goes
on), the sign of ``det J_z`` along the samples locates the branch point
(the root of a cubic through the signed Hadamard ratios about the sign
change); when it does not, no branch goes on smoothly: a true dead point.
Under ``"keep"`` the other branch at the far point is found by Newton from
starts along the null vector of ``J_z`` at the branch point, with the
incoming sign of ``det J_z``.  The continuation then resumes, batched, from
the far point on the branch chosen.

Numeric core: numpy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.mechanism._constants import COARSE_STEP, SINGULAR_TOL

__all__ = [
    "BRANCHES",
    "DEFAULT_BRANCH",
    "ETA",
    "MAX_BRANCH_POINTS",
    "NEAR_RATES",
    "NODES",
    "NODE_STEP",
    "BranchPoint",
    "branch_message",
    "check_branch",
    "cross",
    "richardson",
]

#: The policies (module docstring).
BRANCHES = ("continue", "keep", "stop")
#: The default policy: the motion the mechanism makes (smooth through a branch point).
DEFAULT_BRANCH = "continue"
#: Half-width of the window across a branch point (rad, or times the model size for a slider input).
ETA = 1e-3
#: A row this near a branch point (rad, or times the model size) takes its position and rates from the
#: branch followed at ``ETA`` and ``2 ETA`` either side (:func:`richardson`: error of the order of ``ETA^4``),
#: where ``J_z`` is well conditioned.
NEAR = 1e-6
#: Rows this near a branch point passed smoothly (rad, or times the model size) take their position and rates as
#: the limit of the branch either side (:meth:`~gearlever.mechanism.solve.KinematicSystem._limit_rates`): nearer,
#: the rates of the linear solves lose digits to the nearly singular ``J_z`` (about 1e-8 of their scale at 1e-4).
NEAR_RATES = 1.5e-2
#: Spacing of the states of the continued branch about such a row that its values are interpolated from.
NODE_STEP = 3e-2
#: How many (half on either side of the row).
NODES = 8
#: Most branch points one solve crosses (and most crossings that change nothing).
MAX_BRANCH_POINTS = 10_000
#: Hadamard ratio of ``J_z`` below which a row the continuation closed is checked for a branch point.
RATIO_NEAR = 1e-5
#: Samples of the smooth path across the window.
_SAMPLES = 12


@dataclass(frozen=True)
class BranchPoint(Result):
    r"""A branch point the rows passed (``branch="continue"`` or ``"keep"``).

    Attributes
    ----------
    row : int
        The first row past it (the row at it when one is there).
    q : tuple of float
        The inputs at the branch point, in ``[[inputs]]`` order (rad for a
        link, length for a slider).
    policy : str
        ``"continue"`` (the branch changed, the velocity is continuous) or
        ``"keep"`` (the branch kept, the velocity jumps).
    sign_before, sign_after : int
        The assembly branch before and after: +1 the sketch's (the sign of
        ``det J_z`` at the sketch), -1 the other.

    Examples
    --------
    >>> p = BranchPoint(540, (4.71238898038469,), "continue", 1, -1)
    >>> print(*p.text(["crank"], ["link"]).split(": "), sep=":\n")
    crank passes a branch point at 270.000 deg (row 540):
    continuing on the other assembly branch, the velocity continuous
    """

    row: int
    q: tuple
    policy: str
    sign_before: int
    sign_after: int

    def text(self, labels, kinds) -> str:
        """One line saying where and what (degrees for a link input)."""
        at = ", ".join(
            f"{n} = {math.degrees(v):.3f} deg" if k == "link" else f"{n} = {v:.6g}"
            for n, k, v in zip(labels, kinds, self.q)
        )
        if len(labels) == 1:
            at = at.split(" = ", 1)[1]
            head = f"{labels[0]} passes a branch point at {at} (row {self.row})"
        else:
            head = f"the inputs pass a branch point at {at} (row {self.row})"
        if self.policy == "keep":
            return f"{head}: keeping the assembly branch, the velocity jumps there"
        return f"{head}: continuing on the other assembly branch, the velocity continuous"


def branch_message(points, labels, kinds) -> str | None:
    r"""The one line that says where the rows passed branch points (the first, and how many more), or None.

    >>> pts = (BranchPoint(540, (4.71238898038469,), "keep", 1, 1), BranchPoint(1260, (10.99557428756,), "keep", 1, 1))
    >>> print(*branch_message(pts, ["crank"], ["link"]).split(": "), sep=":\n")
    crank passes a branch point at 270.000 deg (row 540):
    keeping the assembly branch, the velocity jumps there; 1 more at row 1260
    """
    if not points:
        return None
    line = points[0].text(labels, kinds)
    more = [p.row for p in points[1:]]
    if more:
        rows = ", ".join(str(r) for r in more[:10]) + (", ..." if len(more) > 10 else "")
        line += f"; {len(more)} more at row{'s' if len(more) > 1 else ''} {rows}"
    return line


def check_branch(branch) -> str:
    """``branch`` if it is one of :data:`BRANCHES`, else a :class:`~gearlever.errors.GearleverError` naming it.

    >>> check_branch("keep")
    'keep'
    """
    if not isinstance(branch, str) or branch not in BRANCHES:
        raise GearleverError(f"branch must be one of {', '.join(map(repr, BRANCHES))}, got {branch!r}")
    return branch


def _tangent(ks, dq, z, u):
    """First and second derivatives of ``z`` along the input direction ``u`` at one state, or None at a dead point."""
    x = ks.coordinates(dq[:, None], z[:, None])
    xd, xdd, dead = ks.derivatives(x, u[:, None], np.zeros((ks.W, 1)))
    if dead[0]:
        return None
    return ks.N.T @ xd[:, 0], ks.N.T @ xdd[:, 0]


def _signed(ks, x, C, S):
    ratio, sgn = ks._hadamard(ks.jz(x, C, S)[ks.sel])
    return ratio, sgn


def _root(tau, rho, j) -> float:
    """Zero of the signed ratios ``rho`` between samples ``j`` and ``j + 1`` (a cubic through four about it)."""
    lo, hi = max(j - 1, 0), min(j + 3, tau.size)
    t, r = tau[lo:hi], rho[lo:hi]
    a, b = tau[j], tau[j + 1]
    t0 = a - (b - a) * rho[j] / (rho[j + 1] - rho[j])  # linear
    if t.size >= 3:
        c = np.polynomial.polynomial.polyfit(t - a, r, t.size - 1)
        roots = np.polynomial.polynomial.polyroots(c)
        real = [
            float(v.real) + a for v in roots if abs(v.imag) <= 1e-12 * (b - a) and -1e-9 <= v.real <= (b - a) * 1.000001
        ]
        if real:
            t0 = min(real, key=lambda v: abs(v - t0))
    return float(t0)


def richardson(v):
    """Value at the middle of the columns ``v[:, k]`` at offsets ``-h, h, -2h, 2h``: error ``O(h^4)``.

    The means of the symmetric pairs differ from the value by ``c h^2`` and
    ``4 c h^2``; ``(4 M(h) - M(2h)) / 3`` removes that term (Richardson
    extrapolation).

    >>> t = np.array([-1.0, 1.0, -2.0, 2.0]) * 1e-2
    >>> bool(abs(richardson(np.cos(0.3 + t)[None, :])[0] - np.cos(0.3)) < 2e-9)  # h^4 / 6 = 1.7e-9
    True
    """
    m1 = 0.5 * (v[:, 0] + v[:, 1])
    m2 = 0.5 * (v[:, 2] + v[:, 3])
    return (4.0 * m1 - m2) / 3.0


def cross(ks, s_dq, back, target, sgn: float, policy: str, rows=None):
    """Cross the singular pose ahead of the state ``(s_dq, s_z)`` towards the input ``target`` (module docstring).

    Parameters
    ----------
    ks : KinematicSystem
    s_dq : ndarray (W,)
        The input offsets where the continuation stopped.
    back : tuple of ndarray
        A state ``(dq, z)`` of the incoming branch at least ``ETA / 2``
        before the stop (a row reached, or the start of the segment).
    target : ndarray (W,)
        Input offsets of the first row not reached (the direction of the path).
    sgn : float
        Sign of ``det J_z`` of the branch followed so far.
    policy : {"continue", "keep"}
    rows : ndarray (W, M), optional
        Input offsets of the rows ahead: the first, when within :data:`NEAR`
        of the branch point, is evaluated by the mean either side.

    Returns
    -------
    dict or None
        None when no branch goes on smoothly (a true dead point), else
        ``dq``, ``z``, ``sgn``: the state to resume from and its branch's
        sign; ``changed``: a branch point was passed; ``qstar``: the input
        offsets there; ``pre``: the reduced coordinates of the leading rows
        that lie in the window before the branch point (on the incoming
        branch); ``near``: None or ``(dq, z, z_row)`` of the next row when it
        lies at the branch point: the states at ``-ETA, ETA, -2 ETA, 2 ETA``
        about it, (W, 4) and (dz, 4), and its reduced coordinates
        (:func:`richardson`).
    """
    delta = target - s_dq
    dist = float(np.max(np.abs(delta / ks.qscale)))
    if not dist > 0.0:
        return None
    u = delta / dist
    eta = ETA
    b_dq = s_dq - eta * u
    # the state ETA before the stop, walked to from a state of the incoming branch that is not near the
    # singular pose (derivatives there are unreliable: the position's error along the null vector of J_z
    # over its small singular value)
    zb, _ = ks._walk(back[0], back[1], b_dq, COARSE_STEP, sgn)
    if zb is None:
        return None
    tb = _tangent(ks, b_dq, zb, u)
    if tb is None:
        return None
    zd, zdd = tb
    scale = 1.0 + float(np.max(np.abs(zd)))

    def smooth(tau):
        """Newton on the incoming branch's Taylor expansion at path positions ``tau`` from ``b``."""
        dqs = b_dq[:, None] + tau[None, :] * u[:, None]
        p = zb[:, None] + zd[:, None] * tau + 0.5 * zdd[:, None] * tau * tau
        z, x, C, S, conv = ks.newton(dqs, p, max_iter=30)
        r, s = _signed(ks, x, C, S)
        with np.errstate(invalid="ignore"):
            good = conv & (np.max(np.abs(z - p), axis=0) <= 1e-2 * np.maximum(np.abs(tau), 1e-6) * scale)
        return dqs, z, r, s, good

    tau = np.append((np.arange(_SAMPLES) + 0.5) * 3 * eta / _SAMPLES, 3 * eta)
    dqs, z, r, s, good = smooth(tau)
    if not (good[-1] and r[-1] > SINGULAR_TOL):
        return None  # nothing goes on smoothly past it: a dead point of the input (or the assembly ends)
    f_dq, z_f, sgn_f = dqs[:, -1], z[:, -1], float(s[-1])
    out = {"dq": f_dq, "z": z_f, "sgn": sgn_f, "changed": sgn_f != sgn, "qstar": None, "near": None, "pre": []}
    if sgn_f == sgn:
        return out  # the same branch goes on: no branch point crossed
    rho = np.where(good, r * s, np.nan)
    ok = np.flatnonzero(good)
    j = None
    for a, b in zip(ok[:-1], ok[1:]):
        if rho[a] * rho[b] < 0:
            j = a
            break
    if j is None:
        return None
    tstar = _root(tau[ok], rho[ok], int(np.flatnonzero(ok == j)[0]))
    qstar = b_dq + tstar * u
    out["qstar"] = qstar
    zstar = zb + zd * tstar + 0.5 * zdd * tstar * tstar  # the branch point (to the predictor's error)
    out["pre"] = []
    if rows is not None and rows.shape[1]:
        sc = u / ks.qscale
        rel = (rows - b_dq[:, None]) / ks.qscale[:, None]
        t_rows = (rel.T @ sc) / (sc @ sc)
        off_line = np.max(np.abs(rel - t_rows[None, :] * sc[:, None]), axis=0)
        j = 0
        # rows of the window before the branch point: on the incoming branch
        while j < t_rows.size and off_line[j] <= 1e-9 and 0.0 <= t_rows[j] < tstar - NEAR:
            dq1, z1, r1, s1, g1 = smooth(t_rows[j : j + 1])
            if not (g1[0] and r1[0] > SINGULAR_TOL and s1[0] == sgn):
                return None
            out["pre"].append(z1[:, 0])
            j += 1
        if j < t_rows.size and off_line[j] <= 1e-9 and abs(t_rows[j] - tstar) <= NEAR:
            pm = t_rows[j] + np.array([-1.0, 1.0, -2.0, 2.0]) * eta
            dq2, z2, r2, s2, g2 = smooth(pm)
            if g2.all() and np.all(r2 > SINGULAR_TOL):
                out["near"] = (dq2, z2, richardson(z2))
    if policy == "continue":
        return out
    # keep: the other branch at the far point, with the incoming sign of det J_z
    xs_ = ks.coordinates(qstar[:, None], zstar[:, None])
    Cs, Ss = ks.trig(xs_)
    J = ks.jz(xs_, Cs, Ss)[ks.sel][:, :, 0]
    n = np.linalg.svd(J)[2][-1]
    gap = max(float(np.max(np.abs(z_f - zb))), 1e-12)
    c = np.concatenate([-np.arange(1, 9), np.arange(1, 9)]) * 0.5 * gap
    starts = z_f[:, None] + n[:, None] * c[None, :]
    zk, xk, Ck, Sk, ck = ks.newton(np.repeat(f_dq[:, None], c.size, axis=1), starts, max_iter=40)
    rk, sk = _signed(ks, xk, Ck, Sk)
    with np.errstate(invalid="ignore"):
        d_f = np.max(np.abs(zk - z_f[:, None]), axis=0)
        d_b = np.max(np.abs(zk - zb[:, None]), axis=0)
        cand = ck & (rk > SINGULAR_TOL) & (sk == sgn) & (d_f > 1e-6 * gap) & (d_b <= 20.0 * gap)
    if not cand.any():
        return None
    k = int(np.flatnonzero(cand)[np.argmin(d_b[cand])])
    out.update(z=zk[:, k], sgn=sgn)
    return out
