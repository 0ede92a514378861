"""Positions, velocities and accelerations of a mechanism model, batched over the inputs.

The model is compiled once into *reduced coordinates* ``x = (phi, s)``: the
rotation ``phi_k`` of every moving link from the sketch and the displacement
``s_j`` of every slider.  A spanning tree of the joint graph (pins and
sliders, rooted at ground) writes every point as

    p = c + sum_k R(phi_k) v_k + sum_j w_j s_j R(phi_on(j)) u_j

(a sum of rotated sketch vectors), so the joints of the tree hold by
construction.  What is left:

- linear rows: a slider does not turn relative to its guide
  (``phi_link = phi_on``), a mesh obeys Willis' equation, each input fixes
  one coordinate; their null space is eliminated once, ``x = X_p (q - q0) + N z``;
- closure rows: every pin or slider not in the tree closes a loop of the
  joint graph (a cycle basis; the loops are never written by hand), two rows
  each, solved for ``z`` by batched Newton with the analytic Jacobian.

Velocities and accelerations are batched linear solves with the same
Jacobian.  Pure numpy; no solver call per point.
"""

from __future__ import annotations

import warnings
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite_array
from gearlever.errors import GearleverError, GearleverWarning
from gearlever.mechanism._constants import COARSE_STEP, SINGULAR_TOL
from gearlever.mechanism.branch import (
    DEFAULT_BRANCH,
    ETA,
    MAX_BRANCH_POINTS,
    NEAR,
    NEAR_RATES,
    NODE_STEP,
    NODES,
    RATIO_NEAR,
    BranchPoint,
    check_branch,
    cross,
    richardson,
)
from gearlever.mechanism.constraints import mesh_coefficients
from gearlever.mechanism.model import GROUND, MechanismModel
from gearlever.mechanism.structural import RANK_TOL, analyze_structure, independent_rows, numeric_rank

__all__ = ["KinematicSystem", "MechanismResult", "input_name", "solve"]


#: Largest change of the direction of motion along a step, beyond the trapezoid of the curvatures at its ends, as a
#: fraction of the change (:meth:`KinematicSystem._kinked`): on one smooth branch it is of the order of the step's
#: cube; a branch switched silently (Newton landing past a branch point on the other branch) turns the direction by
#: a finite angle however short the step.
KINK = 0.1
#: Longest step (rad, or times the model size) that may end or start within
#: :data:`~gearlever.mechanism.branch.RATIO_NEAR` of a singular pose (:meth:`KinematicSystem._kinked`).
NEAR_STEP = 1e-3
#: Smallest Hadamard ratio of ``J_z`` at a state :meth:`KinematicSystem._walk` passes on its way to its target.
RATIO_WAY = 1e-7

REASON_UNREACHED = "not reached continuously from the sketch (past a dead point, or no assembly there)"
REASON_DEAD = "dead point: the constraint Jacobian is singular (velocities undefined)"
REASON_STOP = (
    "dead point between {frm} and this row{where}: the continuation stops there, it never changes branch "
    "(the input reverses at a dead point, or the assembly ends); not reached"
)


def _null_space(A: np.ndarray, ncols: int) -> np.ndarray:
    if A.shape[0] == 0:
        return np.eye(ncols)
    u, sv, vt = np.linalg.svd(A)
    r = int(np.sum(sv > RANK_TOL * max(sv[0] if sv.size else 0.0, 1e-300)))
    return vt[r:].T.copy()


def _singular_links(model) -> list:
    """Links that can move at the sketch with every link input held: the binding links of a dead-point sketch."""
    from gearlever.mechanism.structural import scaled_jacobian

    J = scaled_jacobian(model)
    moving = list(model.moving)
    rows = []
    for spec in model.inputs:
        if spec.kind != "link":
            continue
        r = np.zeros(3 * len(moving))
        r[3 * moving.index(spec.name) + 2] = 1.0
        if spec.relative_to is not None and spec.relative_to != GROUND:
            r[3 * moving.index(spec.relative_to) + 2] = -1.0
        rows.append(r)
    A = np.vstack([J] + ([np.array(rows)] if rows else []))
    ns = _null_space(A, A.shape[1])
    if ns.shape[1] == 0:
        return moving
    move = np.abs(ns).reshape(len(moving), 3, -1).max(axis=(1, 2))
    return [k for k, v in zip(moving, move) if v > 0.05 * move.max()] or moving


class _Forms:
    """Stacked point expressions ``c + sum_k R(phi_k) v_k + sum_j w_j s_j R(phi_o(j)) u_j``."""

    def __init__(self, c, V, W):
        self.c = np.asarray(c, dtype=float).reshape(-1, 2)
        V = np.asarray(V, dtype=float).reshape(len(self.c), -1, 2)
        self.Vx = np.ascontiguousarray(V[..., 0])  # (K, n)
        self.Vy = np.ascontiguousarray(V[..., 1])
        self.W = np.ascontiguousarray(np.asarray(W, dtype=float).reshape(len(self.c), -1))  # (K, S)
        self.has_sliders = bool(np.any(self.W))


class KinematicSystem:
    """A mechanism model compiled to reduced coordinates (see the module docstring).

    Parameters
    ----------
    model : MechanismModel

    Raises
    ------
    GearleverError
        If the number of inputs differs from the degrees of freedom, or the
        inputs do not fix the mechanism at the sketch (a locked or dependent
        input).

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"],
    ...               "rocker": ["O4", "B"]}, "inputs": [{"link": "crank"}]})
    >>> ks = KinematicSystem(m)
    >>> (ks.nx, ks.dz, ks.n_closure_rows)
    (3, 2, 2)
    """

    def __init__(self, model: MechanismModel):
        self.model = model
        st = analyze_structure(model)
        self.structure = st
        W = len(model.inputs)
        if W != st.dof and W == st.W_formula and st.dof > W:
            raise GearleverError(
                f"inputs: the sketch is a dead point of the links {', '.join(_singular_links(model))}: the "
                f"constraints lose rank there ({st.dof} degrees of freedom at the sketch for {W} [[inputs]], "
                f"{st.W_formula} by the formula), so an input is locked there or moves one way only; sketch the "
                "mechanism off the dead point"
            )
        if W != st.dof:
            raise GearleverError(
                f"inputs: the mechanism has {st.dof} degree(s) of freedom (rank analysis at the sketch) "
                f"but {W} [[inputs]] are given"
            )
        moving = model.moving
        self.n = n = len(moving)
        self.S = S = len(model.sliders)
        self.nx = n + S
        self.W = W
        self.idx = {k: i for i, k in enumerate(moving)}
        self.slider_idx = {s.name: j for j, s in enumerate(model.sliders)}
        self.L = model.length_scale
        # slider directions (sketch) and the link whose rotation turns them (-1: ground)
        self.ux = np.array([s.direction[0] for s in model.sliders])
        self.uy = np.array([s.direction[1] for s in model.sliders])
        self.so = np.array([self.idx.get(s.on, -1) for s in model.sliders], dtype=int)
        self._tree()
        self._linear()
        self._closures()

    # ------------------------------------------------------------- compilation
    def _zero_form(self):
        return np.zeros(2), np.zeros((self.n, 2)), np.zeros(self.S)

    def form_at(self, link: str, X) -> tuple:
        """Expression ``(c, V, W)`` of the sketch location ``X`` carried by ``link``."""
        X = np.asarray(X, dtype=float)
        if link == GROUND:
            c, V, W = self._zero_form()
            return X.copy(), V, W
        A, (c, V, W) = self.anchor[link]
        V = V.copy()
        V[self.idx[link]] += X - A
        return c.copy(), V, W.copy()

    def _tree(self):
        model = self.model
        adj = {k: [] for k in model.links}
        for e, (_p, a, b) in enumerate(model.joints):
            adj[a].append(("pin", e, b))
            adj[b].append(("pin", e, a))
        for j, s in enumerate(model.sliders):
            adj[s.link].append(("slider", j, s.on))
            adj[s.on].append(("slider", j, s.link))
        self.anchor = {}
        used_pins, used_sliders = set(), set()
        seen = {GROUND}
        queue = deque([GROUND])
        while queue:
            p = queue.popleft()
            for kind, e, k in adj[p]:
                if k in seen:
                    continue
                seen.add(k)
                queue.append(k)
                if kind == "pin":
                    J = np.array(model.points[model.joints[e][0]], dtype=float)
                    self.anchor[k] = (J, self.form_at(p, J))
                    used_pins.add(e)
                else:
                    s = model.sliders[e]
                    G = np.array(model.points[s.point], dtype=float)
                    c, V, W = self.form_at(p, G)
                    W[e] += 1.0 if k == s.link else -1.0
                    self.anchor[k] = (G, (c, V, W))
                    used_sliders.add(e)
        self.cut_pins = [e for e in range(len(model.joints)) if e not in used_pins]
        self.cut_sliders = [j for j in range(len(model.sliders)) if j not in used_sliders]

    def _linear(self):
        model, n, nx = self.model, self.n, self.nx
        rows = []
        for s in model.sliders:
            r = np.zeros(nx)
            if s.link != GROUND:
                r[self.idx[s.link]] += 1.0
            if s.on != GROUND:
                r[self.idx[s.on]] -= 1.0
            rows.append(r)
        for m in model.meshes:
            r = np.zeros(nx)
            for link, c in mesh_coefficients(model, m).items():
                if link != GROUND:
                    r[self.idx[link]] += c
            rows.append(r)
        A_c = np.array(rows).reshape(len(rows), nx)
        Nc = _null_space(A_c, nx)
        A_in = np.zeros((self.W, nx))
        q0 = np.zeros(self.W)
        scale = np.ones(self.W)
        for i, spec in enumerate(model.inputs):
            if spec.kind == "slider":
                A_in[i, n + self.slider_idx[spec.name]] = 1.0
                scale[i] = self.L
            else:
                A_in[i, self.idx[spec.name]] = 1.0
                q0[i] = model.links[spec.name].angle0
                if spec.relative_to is not None:
                    q0[i] -= model.links[spec.relative_to].angle0
                    if spec.relative_to != GROUND:
                        A_in[i, self.idx[spec.relative_to]] -= 1.0
        B = A_in @ Nc
        if numeric_rank(B) < self.W:
            bad = [model.inputs[i].label for i in range(self.W) if numeric_rank(B[i : i + 1]) == 0]
            which = f" (input {bad[0]!r} cannot move)" if bad else ""
            raise GearleverError(
                f"inputs: the inputs are locked or depend on each other through gears or sliders{which}"
            )
        P = np.linalg.pinv(B)
        N2 = _null_space(B, Nc.shape[1])
        self.Xp = Nc @ P  # (nx, W)
        self.N = Nc @ N2  # (nx, dz)
        self.Xp[np.abs(self.Xp) < 1e-15] = 0.0
        self.N[np.abs(self.N) < 1e-15] = 0.0
        self.dz = self.N.shape[1]
        self.q0 = q0
        self.qscale = scale

    def _closures(self):
        model = self.model
        cs, Vs, Ws = [], [], []
        for e in self.cut_pins:
            p, a, b = model.joints[e]
            J = model.points[p]
            ca, Va, Wa = self.form_at(a, J)
            cb, Vb, Wb = self.form_at(b, J)
            cs.append(ca - cb)
            Vs.append(Va - Vb)
            Ws.append(Wa - Wb)
        for j in self.cut_sliders:
            s = model.sliders[j]
            G = model.points[s.point]
            ca, Va, Wa = self.form_at(s.link, G)
            cb, Vb, Wb = self.form_at(s.on, G)
            W = Wa - Wb
            W[j] -= 1.0
            cs.append(ca - cb)
            Vs.append(Va - Vb)
            Ws.append(W)
        K = len(cs)
        self.n_closure_rows = 2 * K
        if K == 0:
            self.closure = None
            self.sel = np.zeros(0, dtype=int)
            if self.dz:
                raise GearleverError("inputs: the inputs do not fix the mechanism")
            return
        self.closure = _Forms(np.array(cs), np.array(Vs), np.array(Ws))
        # reduced Jacobian tables: dG/dz = -(s @ A1 + c @ A2) (x rows), (c @ A1 - s @ A2) (y rows)
        self._jz_tables()
        # independent rows at the sketch
        x0 = np.zeros((self.nx, 1))
        Jz = self.jz(x0, *self.trig(x0))[:, :, 0]
        if numeric_rank(Jz / self.L) < self.dz:
            raise GearleverError(
                "inputs: the inputs do not fix the mechanism at the sketch: the sketch is a dead point of the "
                f"links {', '.join(self._binding(Jz))} (they can move with the inputs held), so an input is "
                "locked there or moves one way only; sketch the mechanism off the dead point"
            )
        self.sel = np.array(independent_rows(Jz / self.L), dtype=int) if self.dz else np.zeros(0, dtype=int)
        self.sgn0 = float(np.sign(np.linalg.det(Jz[self.sel][:, :]))) if self.dz else 1.0

    def _binding(self, Jz) -> list:
        """Links that move along the null vector of the closure Jacobian ``Jz`` (2K, dz) at a dead point."""
        v = np.linalg.svd(Jz / self.L)[2][-1]
        move = self.N @ v
        rot = np.abs(move[: self.n])
        big = float(rot.max()) if rot.size else 0.0
        names = [k for k in self.model.moving if big > 0 and rot[self.idx[k]] > 0.05 * big]
        names += [s.name for j, s in enumerate(self.model.sliders) if abs(move[self.n + j]) > 0.05 * max(big, 1e-300)]
        return names or list(self.model.moving)

    def _jz_tables(self):
        f, n, N = self.closure, self.n, self.N
        K = f.c.shape[0]
        dz = self.dz
        Nphi = N[:n]  # (n, dz)
        self.zlinks = np.flatnonzero(np.any(Nphi != 0, axis=1))
        # (K*dz, n): entry [K dz + m, k] = V[K, k] N[k, m]
        self._A1 = np.ascontiguousarray(np.einsum("Kk,km->Kmk", f.Vx, Nphi).reshape(K * dz, n))
        self._A2 = np.ascontiguousarray(np.einsum("Kk,km->Kmk", f.Vy, Nphi).reshape(K * dz, n))
        S = self.S
        if S:
            Ns = N[n:]  # (S, dz)
            No = np.where(self.so[:, None] >= 0, Nphi[np.maximum(self.so, 0)], 0.0)  # (S, dz)
            self._B1 = np.ascontiguousarray(np.einsum("Kj,jm->Kmj", f.W, Ns).reshape(K * dz, S))
            self._B2 = np.ascontiguousarray(np.einsum("Kj,jm->Kmj", f.W, No).reshape(K * dz, S))

    @property
    def dyad_plan(self):
        """Closed-form decomposition into drivers and dyads (:func:`~gearlever.mechanism.assur.plan_dyads`) or None."""
        if not hasattr(self, "_dyad_plan"):
            from gearlever.mechanism.assur import plan_dyads

            self._dyad_plan = plan_dyads(self)
        return self._dyad_plan

    # ------------------------------------------------------------- evaluation
    # Arrays are laid out feature-major: x (nx, N), C = cos(phi), S = sin(phi) (n, N),
    # so that every sum over links is one small-by-long matrix product.
    def trig(self, x):
        """``cos`` and ``sin`` of the link rotations, (n, N) each."""
        phi = x[: self.n]
        return np.cos(phi), np.sin(phi)

    def _ru(self, C, S):
        """Slider directions turned with their guides, (S, N) each."""
        Ce = np.concatenate([C, np.ones((1, C.shape[1]))])[self.so]
        Se = np.concatenate([S, np.zeros((1, S.shape[1]))])[self.so]
        return Ce * self.ux[:, None] - Se * self.uy[:, None], Se * self.ux[:, None] + Ce * self.uy[:, None]

    def eval_forms(self, f: _Forms, x, C, S, xd=None, xdd=None):
        """Positions (and velocities, accelerations) of stacked expressions, ``(K, N)`` arrays x and y."""
        n = self.n
        X = f.c[:, 0, None] + (f.Vx @ C - f.Vy @ S)
        Y = f.c[:, 1, None] + (f.Vx @ S + f.Vy @ C)
        sliders = self.S and f.has_sliders
        if sliders:
            rux, ruy = self._ru(C, S)
            sl = x[n:]
            X += f.W @ (sl * rux)
            Y += f.W @ (sl * ruy)
        out = [(X, Y)]
        if xd is None:
            return out
        w = xd[:n]
        a, b = w * C, w * S
        # sum_k w_k R'(phi_k) v_k = rot90(sum_k w_k R(phi_k) v_k)
        VX = -(f.Vx @ b + f.Vy @ a)
        VY = f.Vx @ a - f.Vy @ b
        if sliders:
            sd = xd[n:]
            wo = np.concatenate([w, np.zeros((1, w.shape[1]))])[self.so]
            VX += f.W @ (sd * rux - sl * wo * ruy)
            VY += f.W @ (sd * ruy + sl * wo * rux)
        out.append((VX, VY))
        if xdd is None:
            return out
        e = xdd[:n]
        ww = w * w
        # sum_k e_k R'_k v_k - w_k^2 R_k v_k
        P, Q = e * S + ww * C, e * C - ww * S
        AX = -(f.Vx @ P + f.Vy @ Q)
        AY = f.Vx @ Q - f.Vy @ P
        if sliders:
            sdd = xdd[n:]
            eo = np.concatenate([e, np.zeros((1, e.shape[1]))])[self.so]
            k1 = sdd - sl * wo * wo
            k2 = 2.0 * sd * wo + sl * eo
            AX += f.W @ (k1 * rux - k2 * ruy)
            AY += f.W @ (k1 * ruy + k2 * rux)
        out.append((AX, AY))
        return out

    def residual(self, x, C, S):
        """Closure rows, ``(2K, N)``: x and y of each cut pair, interleaved."""
        X, Y = self.eval_forms(self.closure, x, C, S)[0]
        G = np.empty((2 * X.shape[0], X.shape[1]))
        G[0::2], G[1::2] = X, Y
        return G

    def jz(self, x, C, S):
        """Reduced Jacobian ``dG/dz`` of the closure rows, shape ``(2K, dz, N)``."""
        K, dz = self.closure.c.shape[0], self.dz
        Nn = C.shape[1]
        JX = -(self._A1 @ S + self._A2 @ C)
        JY = self._A1 @ C - self._A2 @ S
        if self.S:
            rux, ruy = self._ru(C, S)
            sl = x[self.n :]
            JX += self._B1 @ rux - self._B2 @ (sl * ruy)
            JY += self._B1 @ ruy + self._B2 @ (sl * rux)
        J = np.empty((2 * K, dz, Nn))
        J[0::2] = JX.reshape(K, dz, Nn)
        J[1::2] = JY.reshape(K, dz, Nn)
        return J

    @staticmethod
    def _solve_small(J, b):
        """Solve ``J y = b`` for stacked square ``J`` (d, d, N), ``b`` (d, N); Cramer's rule for d <= 2."""
        d = J.shape[0]
        if d == 1:
            return b / J[0]
        if d == 2:
            a, bb, c, dd = J[0, 0], J[0, 1], J[1, 0], J[1, 1]
            det = a * dd - bb * c
            return np.stack([(dd * b[0] - bb * b[1]) / det, (a * b[1] - c * b[0]) / det])
        return np.linalg.solve(np.moveaxis(J, -1, 0), b.T[..., None])[..., 0].T

    @staticmethod
    def _hadamard(J):
        """Hadamard ratio ``|det J| / prod(column norms)`` (1 orthogonal, 0 singular) and ``sign(det J)``."""
        d = J.shape[0]
        if d == 1:
            det = J[0, 0]
        elif d == 2:
            det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
        else:
            det = np.linalg.det(np.nan_to_num(np.moveaxis(J, -1, 0)))
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.abs(det) / np.prod(np.sqrt(np.sum(J * J, axis=0)), axis=0)
        return np.nan_to_num(ratio, nan=0.0), np.sign(det)

    def coordinates(self, dq, z):
        """Reduced coordinates ``x = X_p dq + N z``, shape (nx, N)."""
        x = self.Xp @ dq
        if self.dz:
            x += self.N @ z
        return x

    def newton(self, dq, z, CS=None, max_iter: int = 12):
        """Batched Newton on the selected closure rows from ``z`` (dz, N).

        Returns ``(z, x, C, S, converged)``.  Once the corrections are below
        1e-4 rad the cosines and sines are turned by them (series to fourth
        order) instead of recomputed.
        """
        x = self.coordinates(dq, z)
        C, S = self.trig(x) if CS is None else CS
        Nn = x.shape[1]
        if self.dz == 0:
            return z, x, C, S, np.ones(Nn, dtype=bool)
        tol = 1e-14 * self.L
        sel, zl, Nz = self.sel, self.zlinks, self.N[self.zlinks]
        z = z.copy()
        for _ in range(max_iter):
            G = self.residual(x, C, S)
            with np.errstate(invalid="ignore"):
                if not np.any(np.abs(G[sel]) > tol):
                    break
            J = self.jz(x, C, S)[sel]
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                dz = self._solve_small(J, G[sel])
            z -= dz
            x = self.coordinates(dq, z)
            d = -(Nz @ dz)
            with np.errstate(invalid="ignore"):
                big = not np.all(np.abs(d) <= 1e-4)
            if big:
                Cz, Sz = np.cos(x[zl]), np.sin(x[zl])
            else:
                d2 = d * d
                cd, sd = 1.0 - d2 * (0.5 - d2 / 24.0), d * (1.0 - d2 / 6.0)
                Cz, Sz = C[zl] * cd - S[zl] * sd, S[zl] * cd + C[zl] * sd
            C, S = C.copy(), S.copy()
            C[zl], S[zl] = Cz, Sz
        else:
            G = self.residual(x, C, S)
        with np.errstate(invalid="ignore"):
            conv = np.all(np.abs(G) <= 1e-9 * self.L, axis=0)
        return z, x, C, S, conv

    def derivatives(self, x, qd, qdd, CS=None):
        """Velocities ``xd`` and accelerations ``xdd`` (nx, N) of the reduced coordinates, and a dead-point mask.

        Parameters
        ----------
        x : ndarray (nx, N)
        qd, qdd : ndarray (W, N)
            Input velocities and accelerations.

        Notes
        -----
        ``J_z zd = -G_x X_p qd`` and ``J_z zdd = -(G_x X_p qdd + gamma(xd))``:
        the first and second time derivatives of the closure rows, linear in
        the unknown rates with the Jacobian of the position problem
        (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, 1988,
        eqs. 3.15 and 3.17).
        """
        xd = self.Xp @ qd
        xdd = self.Xp @ qdd
        Nn = x.shape[1]
        if self.dz == 0:
            return xd, xdd, np.zeros(Nn, dtype=bool)
        C, S = self.trig(x) if CS is None else CS
        J = self.jz(x, C, S)[self.sel]
        ratio, _ = self._hadamard(J)
        dead = ~(ratio > SINGULAR_TOL)
        if np.any(dead):
            J = np.where(dead, np.eye(self.dz)[:, :, None], J)
        sel = self.sel
        (_, _), (VX, VY) = self.eval_forms(self.closure, x, C, S, xd)
        b = np.empty((2 * VX.shape[0], Nn))
        b[0::2], b[1::2] = VX, VY
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            xd += self.N @ self._solve_small(J, -b[sel])
        (_, _), (_, _), (AX, AY) = self.eval_forms(self.closure, x, C, S, xd, xdd)
        b[0::2], b[1::2] = AX, AY
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            xdd += self.N @ self._solve_small(J, -b[sel])
        if np.any(dead):
            xd[:, dead] = np.nan
            xdd[:, dead] = np.nan
        return xd, xdd, dead

    @cached_property
    def _kink_weights(self):
        """``N`` with its rotation rows times the model size: the driven motion in lengths (nx, dz)."""
        w = np.ones(self.nx)
        w[: self.n] = self.L
        return w[:, None] * self.N

    def _kinked(self, delta, z0, z1, rates0, rates1, r0, r1):
        """True where a step cannot be taken as one smooth branch (columns: steps): its direction of motion jumps.

        Parameters
        ----------
        delta : ndarray (W, M)
            The steps of the inputs.
        z0, z1 : ndarray (dz, M)
            The states at their ends.
        rates0, rates1 : tuple of ndarray (dz, M)
            First and second derivatives of ``z`` along each step at its ends, per unit of the step (the
            step is ``t`` in [0, 1]).
        r0, r1 : ndarray (M,)
            Hadamard ratios of ``J_z`` at the ends.

        Notes
        -----
        The solution curve in the space of inputs and coordinates (rotations times the model size, so all in
        lengths) is smooth along one branch, through dead points of the input too (a fold: the curve turns
        back there, its unit tangent ``T`` continuous and its curvature finite, although the velocity per
        unit input grows without bound).  Along a smooth curve the unit tangent changes over an arc ``s`` by
        the trapezoid of the curvature vectors ``K = dT/ds = (a - (a.T) T) / |v|^2`` at the ends, to the
        order of ``s^3`` (the trapezoidal rule).  A state that Newton put on the other branch past a branch
        point the step crosses has that branch's tangent: ``T`` jumps by a finite angle there (the square-rod
        slider-crank's slider, -7.3 against +27.3 per rad of the crank), however short the step.  A step is
        *kinked* when the change of ``T`` departs from the trapezoid by more than :data:`KINK` of the larger
        of the two.

        Within :data:`~gearlever.mechanism.branch.RATIO_NEAR` of a singular pose the rates lose the accuracy
        this needs (the position's rounding over the small singular value of ``J_z``): a step with such an
        end is not judged by its tangents, but it is refused when longer than :data:`NEAR_STEP` (a state by
        a singular pose is reached in short steps, whose predictor is accurate enough for its sign of
        ``det J_z`` to say the branch); the rows at such poses are then taken up by the crossing
        (:mod:`gearlever.mechanism.branch`).  Steps with an end at a dead point (NaN rates) are not judged.
        """
        Wn = self._kink_weights
        dw = delta * (self.L / self.qscale)[:, None]
        v0 = np.concatenate([dw, Wn @ rates0[0]])
        v1 = np.concatenate([dw, Wn @ rates1[0]])
        a0 = np.concatenate([np.zeros_like(dw), Wn @ rates0[1]])
        a1 = np.concatenate([np.zeros_like(dw), Wn @ rates1[1]])
        ds = np.sqrt(np.sum(dw * dw, axis=0) + np.sum((Wn @ (z1 - z0)) ** 2, axis=0))
        near = (r0 < RATIO_NEAR) | (r1 < RATIO_NEAR)
        with np.errstate(invalid="ignore", divide="ignore"):
            n0, n1 = np.sqrt(np.sum(v0 * v0, axis=0)), np.sqrt(np.sum(v1 * v1, axis=0))
            t0, t1 = v0 / n0, v1 / n1
            k0 = (a0 - np.sum(a0 * t0, axis=0) * t0) / (n0 * n0)
            k1 = (a1 - np.sum(a1 * t1, axis=0) * t1) / (n1 * n1)
            err = np.sqrt(np.sum((t1 - t0 - 0.5 * ds * (k0 + k1)) ** 2, axis=0))
            turn = np.maximum(
                np.sqrt(np.sum((t1 - t0) ** 2, axis=0)),
                0.5 * ds * (np.sqrt(np.sum(k0 * k0, axis=0)) + np.sqrt(np.sum(k1 * k1, axis=0))),
            )
            # rounding: the positions' over the small singular value, once more in the rates
            noise = 1e-12 / np.minimum(r0, r1) ** 2
            kink = (err > KINK * turn + 1e-9 + noise) & ~near
        return kink | (near & (np.max(np.abs(delta / self.qscale[:, None]), axis=0) > NEAR_STEP))

    def _step_kinked(self, dq0, z0, dq1, z1):
        """:meth:`_kinked` of the straight steps from the states ``(dq0, z0)`` to ``(dq1, z1)`` (columns)."""
        delta = dq1 - dq0
        zero = np.zeros_like(delta)
        NT, out = self.N.T, []
        for dq, z in ((dq0, z0), (dq1, z1)):
            x = self.coordinates(dq, z)
            CS = self.trig(x)
            d, dd, _ = self.derivatives(x, delta, zero, CS)
            out.append(((NT @ d, NT @ dd), self._hadamard(self.jz(x, *CS)[self.sel])[0]))
        return self._kinked(delta, z0, z1, out[0][0], out[1][0], out[0][1], out[1][1])

    # ------------------------------------------------------------- continuation
    def _walk(self, dq0, z0, target, h, sgn=None, stops=None):
        """Sequential continuation from ``(dq0, z0)`` to the input ``target`` (W,).

        Returns ``(z, None)`` at the target, or ``(None, dq)`` with the last
        input reached when it cannot get there (a dead point or the end of
        the assembly on the way: the step shrank below 1e-7); then ``(dq, z)``
        of that last state is appended to ``stops`` (when given).  ``sgn``:
        the sign of ``det J`` of the branch followed (default the sketch's).
        """
        sgn = self.sgn0 if sgn is None else sgn
        cur_dq, cur_z = dq0.copy(), z0.copy()
        step = h
        zeros = np.zeros((self.W, 1))
        NT = self.N.T  # N: orthonormal columns, orthogonal to X_p
        rates = None  # derivatives of z along the remaining way at the current state (dead, zd, zdd)
        while True:
            delta = target - cur_dq
            dist = float(np.max(np.abs(delta / self.qscale)))
            if dist == 0.0:
                return cur_z, None
            t = min(step, dist) / dist
            if rates is None:
                x = self.coordinates(cur_dq[:, None], cur_z[:, None])
                xd, xdd, dead = self.derivatives(x, delta[:, None], zeros)
                r_cur = self._hadamard(self.jz(x, *self.trig(x))[self.sel])[0]
                rates = (bool(dead[0]), NT @ xd[:, 0], NT @ xdd[:, 0], r_cur)
            if rates[0]:
                if stops is not None:
                    stops.append((cur_dq.copy(), cur_z.copy()))
                return None, cur_dq
            zd, zdd, r_cur = rates[1:]
            pred = cur_z + zd * t + 0.5 * zdd * t * t
            new_dq = target.copy() if t >= 1.0 else cur_dq + t * delta
            z, xn, C, S, conv = self.newton(new_dq[:, None], pred[:, None])
            ok = bool(conv[0])
            if ok:
                ratio, sgn_ = self._hadamard(self.jz(xn, C, S)[self.sel])
                trust = 0.2 * t * (1.0 + float(np.max(np.abs(zd)))) + 1e-12
                ok = ratio[0] > SINGULAR_TOL and sgn_[0] == sgn and float(np.max(np.abs(z[:, 0] - pred))) <= trust
                ok = ok and self._pred_sign(new_dq[:, None], pred[:, None])[0] == sgn
                # no state on the way this near a singular pose: its position's rounding over the small singular
                # value of J_z is as large as the distance between the branches there (which it is on is moot)
                ok = ok and (t >= 1.0 or ratio[0] > RATIO_WAY)
            if ok:
                # the direction of motion continuous along the step: not landed on another branch past a
                # branch point (:meth:`_kinked`)
                xd1, xdd1, _ = self.derivatives(xn, delta[:, None], zeros, (C, S))
                zd1, zdd1 = NT @ xd1[:, 0], NT @ xdd1[:, 0]
                tt = t * t
                step_dq = (new_dq - cur_dq)[:, None]
                ok = not self._kinked(
                    step_dq,
                    cur_z[:, None],
                    z,
                    ((zd * t)[:, None], (zdd * tt)[:, None]),
                    ((zd1 * t)[:, None], (zdd1 * tt)[:, None]),
                    r_cur,
                    ratio,
                )[0]
                if ok:  # the next way is the rest of this one: its derivatives are these, scaled
                    rates = (False, zd1 * (1.0 - t), zdd1 * (1.0 - t) ** 2, ratio)
            if ok:
                cur_dq, cur_z = new_dq, z[:, 0]
                step = min(2 * step, h)
                if t >= 1.0:
                    rates = None
            else:
                step /= 2
                if step < 1e-7:
                    if dist <= 1e-4:  # the target itself lies by the singular pose the walk stopped at
                        z, xn, C, S, conv = self.newton(target[:, None], cur_z[:, None])
                        ratio = self._hadamard(self.jz(xn, C, S)[self.sel])[0]
                        moved = float(np.max(np.abs(self._kink_weights @ (z[:, 0] - cur_z))))
                        # (by a dead point of the input the position moves as the square root of the input)
                        if conv[0] and ratio[0] < RATIO_NEAR and moved <= 10.0 * self.L * dist**0.5:
                            return z[:, 0], None
                    if stops is not None:
                        stops.append((cur_dq.copy(), cur_z.copy()))
                    return None, cur_dq

    def _near_pose(self, dq, z) -> bool:
        """True when the state ``(dq, z)`` is by a singular pose (:data:`~gearlever.mechanism.branch.RATIO_NEAR`)."""
        x = self.coordinates(dq[:, None], z[:, None])
        return bool(self._hadamard(self.jz(x, *self.trig(x))[self.sel])[0][0] < RATIO_NEAR)

    def _near_singular(self, xs, cl):
        """Rows closed within :data:`~gearlever.mechanism.branch.RATIO_NEAR` of a singular pose (indices)."""
        idx = np.flatnonzero(cl)
        if not idx.size:
            return idx
        x = xs[:, idx]
        ratio, _ = self._hadamard(self.jz(x, *self.trig(x))[self.sel])
        return idx[ratio < RATIO_NEAR]

    def _cross_at(self, sub, xs, i, s_dq, target, first, sgn, branch):
        """:func:`~gearlever.mechanism.branch.cross` at the stop ``s_dq`` before row ``i`` of the segment ``sub``."""
        back = first
        prior = np.flatnonzero(~np.isnan(xs[0, :i])) if self.nx else np.zeros(0, dtype=int)
        if prior.size:
            far = np.max(np.abs((sub[:, prior] - s_dq[:, None]) / self.qscale[:, None]), axis=0) >= 0.5 * ETA
            if far.any():
                k = int(prior[np.flatnonzero(far)[-1]])
                back = (sub[:, k], self.N.T @ xs[:, k])
        return cross(self, s_dq, back, target, sgn, "continue" if branch == "stop" else branch, rows=sub[:, i:])

    def _pred_sign(self, dq, z):
        """Sign of ``det J_z`` at the predicted states ``(dq, z)`` (W, M), (dz, M)."""
        x = self.coordinates(dq, z)
        return self._hadamard(self.jz(x, *self.trig(x))[self.sel])[1]

    def solve(self, q, qd, qdd, branch: str = DEFAULT_BRANCH):
        """Reduced coordinates and rates over the input rows; arrays (nx, N), see :func:`solve`.

        Parameters
        ----------
        q, qd, qdd : ndarray (W, N)
        branch : {"continue", "keep", "stop"}
            The policy at branch points (:mod:`gearlever.mechanism.branch`).

        Returns
        -------
        tuple
            ``x, xd, xdd, closed, reason, CS, points, side``: ``points`` the
            :class:`~gearlever.mechanism.branch.BranchPoint` passed, ``side``
            (N,) the assembly branch of each row (+1 the sketch's, -1 the
            other, 0 not closed).
        """
        Nn = q.shape[1]
        dq = q - self.q0[:, None]
        CS = None
        points, near = (), {}
        if self.dz == 0:
            x = self.coordinates(dq, np.zeros((0, Nn)))
            closed = np.ones(Nn, dtype=bool)
            if self.closure is not None:
                C, S = self.trig(x)
                closed = np.all(np.abs(self.residual(x, C, S)) <= 1e-9 * self.L, axis=0)
            side = closed.astype(int)
        else:
            x = np.full((self.nx, Nn), np.nan)
            closed = np.zeros(Nn, dtype=bool)
            stuck = []
            CS, points, near, side = self._follow(dq, x, closed, stuck, branch)
        if closed.all():
            xs = x
        else:
            xs = np.where(closed, x, 0.0)
            CS = None
        xd, xdd, dead = self.derivatives(xs, qd, qdd, CS)
        for i, (dq4, z4) in near.items():
            if branch != "continue":  # the velocity jumps there (keep) or is one-sided (stop): undefined
                xd[:, i], xdd[:, i], dead[i] = np.nan, np.nan, True
                continue
            x4 = self.coordinates(dq4, z4)
            d1, d2, dd = self.derivatives(
                x4, np.repeat(qd[:, i : i + 1], 4, axis=1), np.repeat(qdd[:, i : i + 1], 4, axis=1)
            )
            if not dd.any():
                xd[:, i], xdd[:, i], dead[i] = richardson(d1), richardson(d2), False
        if points and branch == "continue":
            self._limit_rates(dq, qd, qdd, x, xd, xdd, closed, dead, points, near)
        reason = np.full(Nn, "", dtype=object)
        reason[closed & dead] = REASON_DEAD
        reason[~closed] = REASON_UNREACHED
        if self.dz:
            for i in np.flatnonzero(~closed & np.concatenate([[True], closed[:-1]])):
                reason[i] = self._stop_reason(dq, i, stuck)
        if not closed.all():
            xd[:, ~closed] = np.nan
            xdd[:, ~closed] = np.nan
        return x, xd, xdd, closed, reason, CS, points, side

    def _limit_rates(self, dq, qd, qdd, x, xd, xdd, closed, dead, points, near):
        """Rows by a branch point passed smoothly: their position and rates as the limit of the branch's either side.

        Within :data:`~gearlever.mechanism.branch.NEAR_RATES` of a branch point ``J_z`` is nearly singular
        (exactly, at the pose), so the linear solves for the rates lose digits (the position's rounding over
        the small singular value, and once more for the accelerations) or have no unique answer.  On the
        branch continued smoothly the position and the rates are analytic through the point: they are taken
        as the interpolating polynomial, at the row, of :data:`~gearlever.mechanism.branch.NODES` states of
        that branch about it (offsets ``+-1 .. +-4`` times :data:`~gearlever.mechanism.branch.NODE_STEP` along
        the path), where ``J_z`` is well conditioned: Lagrange interpolation of degree 7, its error of the
        order of ``NODE_STEP^8`` times the eighth derivative.  Each node is checked to be on the branch the
        row's side of the point calls for (the sign of ``det J_z``), and the interpolated position to agree
        with the row's; otherwise the row keeps its values.  Arrays are changed in place.
        """
        Nn = dq.shape[1]
        c = np.concatenate([-np.arange(NODES // 2, 0, -1), np.arange(1, NODES // 2 + 1)]).astype(float)
        wts = np.array([np.prod([-cj / (ck - cj) for cj in c if cj != ck]) for ck in c])  # Lagrange at 0
        Wn = self._kink_weights
        for p in points:
            if p.policy != "continue" or p.sign_before == p.sign_after:
                continue
            qs = np.asarray(p.q, dtype=float) - self.q0
            r = min(p.row, Nn - 1)  # the first row past it (or at it): the direction of the path there
            u = dq[:, r] - qs
            if not float(np.max(np.abs(u / self.qscale))) > 10 * NEAR:
                u = dq[:, r + 1] - dq[:, r] if r + 1 < Nn else dq[:, r] - (dq[:, r - 1] if r else qs)
            size = float(np.max(np.abs(u / self.qscale)))
            if not size > 0.0:
                continue
            u = u / size  # unit step along the path (scaled)
            sc = u / self.qscale
            rel = (dq - qs[:, None]) / self.qscale[:, None]
            t = (rel.T @ sc) / (sc @ sc)
            off = np.max(np.abs(rel - t[None, :] * sc[:, None]), axis=0)
            rows = np.flatnonzero(closed & (off <= 1e-9) & (np.abs(t) <= NEAR_RATES))
            if not rows.size:
                continue
            M = rows.size
            ti = t[rows]
            s = ti[:, None] + NODE_STEP * c[None, :]  # (M, K): node offsets from the branch point
            K = c.size
            ndq = qs[:, None, None] + u[:, None, None] * s[None, :, :]  # (W, M, K)
            # predictor: the branch's Taylor expansion at the row (at the states ETA either side of a row at the
            # point itself, where the rates are undefined)
            xr = x[:, rows]
            zi, xp = self._polish(dq[:, rows], self.N.T @ xr)[:2]  # (Newton at the pose itself may wander)
            keep = ~(np.max(np.abs(Wn @ (zi - self.N.T @ xr)), axis=0) <= 1e-9 * self.L)
            zi[:, keep], xp[:, keep] = self.N.T @ xr[:, keep], xr[:, keep]
            d1, d2, dd = self.derivatives(xp, np.repeat(u[:, None], M, axis=1), np.zeros((self.W, M)))
            Z1, Z2 = self.N.T @ d1, self.N.T @ d2
            base_t = np.repeat(ti[:, None], K, axis=1)
            base_z = np.repeat(zi[:, :, None], K, axis=2)
            B1 = np.repeat(Z1[:, :, None], K, axis=2)
            B2 = np.repeat(Z2[:, :, None], K, axis=2)
            for m, i in enumerate(rows):
                if i not in near:
                    if dd[m]:
                        B1[:, m], B2[:, m] = np.nan, np.nan
                    continue
                dq4, z4 = near[i]  # offsets -ETA, ETA, -2 ETA, 2 ETA about the row
                e1, e2, _ = self.derivatives(
                    self.coordinates(dq4, z4), np.repeat(u[:, None], 4, axis=1), np.zeros((self.W, 4))
                )
                side = np.where(c < 0, 0, 1)
                base_t[m] = ti[m] + np.array([-ETA, ETA])[side]
                base_z[:, m] = z4[:, side]
                B1[:, m] = (self.N.T @ e1)[:, side]
                B2[:, m] = (self.N.T @ e2)[:, side]
            h = s - base_t
            pred = base_z + B1 * h[None] + 0.5 * B2 * (h * h)[None]
            nz, nx, C, S, conv = self.newton(ndq.reshape(self.W, -1), pred.reshape(self.dz, -1), max_iter=30)
            nz, nx, (C, S), conv = self._polish(ndq.reshape(self.W, -1), nz)
            ratio, sg = self._hadamard(self.jz(nx, C, S)[self.sel])
            want = np.where(c < 0, p.sign_before, p.sign_after) * self.sgn0  # the sign of det J_z either side
            ok = (conv & (ratio > 10 * RATIO_NEAR)).reshape(M, K).all(axis=1)
            ok &= (sg.reshape(M, K) == want[None, :]).all(axis=1)
            nx3 = nx.reshape(self.nx, M, K)
            xi = np.einsum("nmk,k->nm", nx3, wts)
            with np.errstate(invalid="ignore"):
                ok &= np.max(np.abs(Wn @ (self.N.T @ (xi - xr))), axis=0) <= 1e-7 * self.L
            if not ok.any():
                continue
            rq = np.repeat(qd[:, rows, None], K, axis=2).reshape(self.W, -1)
            rqq = np.repeat(qdd[:, rows, None], K, axis=2).reshape(self.W, -1)
            v, a_, bad = self.derivatives(nx, rq, rqq, (C, S))
            ok &= ~bad.reshape(M, K).any(axis=1)
            vi = np.einsum("nmk,k->nm", v.reshape(self.nx, M, K), wts)
            ai = np.einsum("nmk,k->nm", a_.reshape(self.nx, M, K), wts)
            g = rows[ok]
            x[:, g], xd[:, g], xdd[:, g], dead[g] = xi[:, ok], vi[:, ok], ai[:, ok], False

    def _polish(self, dq, z):
        """Two more Newton steps from converged states ``z`` (their rounding, not the stopping rule, left).

        Returns ``(z, x, (C, S), converged)``.
        """
        for _ in range(2):
            x = self.coordinates(dq, z)
            C, S = self.trig(x)
            G = self.residual(x, C, S)[self.sel]
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                z = z - self._solve_small(self.jz(x, C, S)[self.sel], G)
        x = self.coordinates(dq, z)
        C, S = self.trig(x)
        with np.errstate(invalid="ignore"):
            conv = np.all(np.abs(self.residual(x, C, S)) <= 1e-9 * self.L, axis=0)
        return z, x, (C, S), conv

    def _follow(self, dq, x_out, closed, stuck, branch):
        """:meth:`_positions` through the branch points under the policy ``branch``, segment by segment.

        Returns ``(CS, points, near, side)``: (C, S) when the one segment closed every row, the
        :class:`~gearlever.mechanism.branch.BranchPoint` passed, the rows at a branch point (row ->
        states either side, for their rates) and the assembly branch of each row (+1 the sketch's).
        """
        Nn = dq.shape[1]
        side = np.zeros(Nn, dtype=int)
        points, near = [], {}
        start, sgn, off, idle, stall = None, self.sgn0, 0, 0, 0.0
        while True:
            sub = dq[:, off:]
            xs = np.full((self.nx, sub.shape[1]), np.nan)
            cl = np.zeros(sub.shape[1], dtype=bool)
            st, stops = [], []
            cs = self._positions(sub, xs, cl, st, start=start, sgn=sgn, stops=stops)
            rel = int(sgn * self.sgn0)
            got = None
            first = (np.zeros(self.W), np.zeros(self.dz)) if start is None else start
            if len(points) + idle < MAX_BRANCH_POINTS:
                # a row closed at (or within RATIO_NEAR of) a singular pose: a branch point there?
                reached = cl.size if cl.all() else int(np.argmin(cl))  # (a row past one not reached: not yet)
                ks_near = self._near_singular(xs, cl)
                for k in ks_near[ks_near < reached]:
                    nxt = sub[:, k + 1] if k + 1 < sub.shape[1] else 2 * sub[:, k] - (sub[:, k - 1] if k else first[0])
                    trial = self._cross_at(sub, xs, k, sub[:, k], nxt, first, sgn, branch)
                    if trial is not None and trial["qstar"] is not None:
                        if branch != "stop":
                            got, i = trial, k
                        else:  # stop at it: the rows past it (the row at it, if any, closed) are not reached
                            cut = k + len(trial["pre"]) + (1 if trial["near"] is not None else 0)
                            if trial["near"] is not None:  # the row at it: its position from either side
                                xs[:, cut - 1] = self.coordinates(sub[:, cut - 1 : cut], trial["near"][2][:, None])[
                                    :, 0
                                ]
                                near[off + cut - 1] = trial["near"][:2]
                            if cut < sub.shape[1]:
                                cl[cut:] = False
                                xs[:, cut:] = np.nan
                                cs = None
                                st.append(trial["qstar"])
                    break
            if got is None and not cl.all() and branch != "stop" and len(points) + idle < MAX_BRANCH_POINTS:
                i = int(np.argmin(cl))
                a_dq = sub[:, i - 1] if i > 0 else first[0]
                s_dq = (_stop_on(stops, a_dq, sub[:, i], self.qscale) or (a_dq,))[0]
                got = self._cross_at(sub, xs, i, s_dq, sub[:, i], first, sgn, branch)
            if got is not None and i == 0 and not got["pre"] and got["near"] is None:
                # no row taken (several branch points on the way to the first row): a crossing that comes no
                # nearer to that row than the one before it goes nowhere (stop there)
                left = float(np.max(np.abs((sub[:, 0] - got["dq"]) / self.qscale)))
                got = None if stall and not left < stall else got
                stall = left
            else:
                stall = 0.0
            if got is None:
                x_out[:, off:] = xs
                closed[off:] = cl
                side[off:] = np.where(cl, rel, 0)
                stuck.extend(st)
                return (cs if off == 0 else None), tuple(points), near, side
            x_out[:, off : off + i] = xs[:, :i]
            closed[off : off + i] = True
            side[off : off + i] = rel
            for zp in got["pre"]:  # rows in the window before the branch point
                x_out[:, off + i] = self.coordinates(sub[:, i : i + 1], zp[:, None])[:, 0]
                closed[off + i] = True
                side[off + i] = rel
                i += 1
            after = int(got["sgn"] * self.sgn0)
            if got["changed"] or (branch == "keep" and got["qstar"] is not None):
                qs = got["qstar"] + self.q0
                points.append(BranchPoint(int(off + i), tuple(float(v) for v in qs), branch, rel, after))
            else:
                idle += 1
            if got["near"] is not None:
                dq4, z4, zr = got["near"]
                x_out[:, off + i] = self.coordinates(sub[:, i : i + 1], zr[:, None])[:, 0]
                closed[off + i] = True
                side[off + i] = after
                near[off + i] = (dq4, z4)
                off += i + 1
            else:
                off += i
            start, sgn = (got["dq"], got["z"]), got["sgn"]
            if off >= Nn:
                return None, tuple(points), near, side

    def _stop_reason(self, dq, i, stuck):
        """Reason of the first row ``i`` not reached after a reached one (or the first row)."""
        a = dq[:, i - 1] if i > 0 else np.zeros(self.W)
        b = dq[:, i]
        where = ""
        span = b - a
        nn = float(span @ span)
        for at in stuck:
            t = float((at - a) @ span) / nn if nn > 0 else 0.0
            if -1e-9 <= t <= 1 + 1e-9 and np.max(np.abs(a + t * span - at) / self.qscale) <= 1e-6:
                vals = at + self.q0
                where = (
                    " (at "
                    + ", ".join(
                        f"{spec.label} = {v:.6g} {'rad' if spec.kind == 'link' else 'length'}"
                        for spec, v in zip(self.model.inputs, vals)
                    )
                    + ")"
                )
                break
        frm = f"row {i - 1}" if i > 0 else "the sketch"
        return REASON_STOP.format(frm=frm, where=where)

    def _state(self, dq, z):
        """Derivatives of ``z`` at one point: first per input (dz, W) and, for one input, second (dz,)."""
        x = self.coordinates(dq[:, None], z[:, None])
        Zp = np.zeros((self.dz, self.W))
        Zpp = np.zeros(self.dz)
        for w in range(self.W):
            e = np.zeros((self.W, 1))
            e[w] = 1.0
            xd, xdd, dead = self.derivatives(x, e, np.zeros_like(e))
            if dead[0]:
                return None
            Zp[:, w] = self.N.T @ xd[:, 0]
            if self.W == 1:
                Zpp = self.N.T @ xdd[:, 0]
        return Zp, Zpp

    def _coarse(self, cdq, cz, cok, h, stuck, block: int = 8, start=None, sgn=None, stops=None):
        """Continuation through the coarse points ``cdq`` (W, nb) from the sketch, in batched blocks.

        Consecutive coarse points (and the sketch and the first point) are at
        most ``h`` apart (:meth:`_positions` inserts points where rows are
        farther apart).  From the last accepted state the next ``block``
        coarse points are predicted (Taylor, second order for one input),
        corrected together by batched Newton, and the longest prefix that
        passes the checks (converged, same sign of det J, correction within
        the trust radius, each point within ``h`` of the one accepted before
        it) is accepted; when none passes, the next point is walked to in
        small sequential steps (:meth:`_walk`).  The inputs where a walk
        stopped are appended to ``stuck``.  ``start``: the state ``(dq, z)``
        to start from (default the sketch), ``sgn`` the sign of ``det J`` of
        its branch (default the sketch's).
        """
        nb = cdq.shape[1]
        sgn = self.sgn0 if sgn is None else sgn
        st_dq, st_z = (np.zeros(self.W), np.zeros(self.dz)) if start is None else (start[0].copy(), start[1].copy())
        st = self._state(st_dq, st_z)
        blocked = None  # (from, at) input values of a failed walk (one input only)
        reach = h * (1.0 + 1e-9)
        k = 0
        while k < nb:
            if blocked is not None and self.W == 1:
                q_from, q_at = blocked
                t0 = cdq[0, k]
                if (t0 - q_from) * (q_at - q_from) > 0 and abs(t0 - q_from) >= abs(q_at - q_from):
                    k += 1
                    continue
            m = 0
            if st is not None:
                ks = np.arange(k, min(k + block, nb))
                d = cdq[:, ks] - st_dq[:, None]
                Zp, Zpp = st
                pred = st_z[:, None] + Zp @ d
                if self.W == 1:
                    pred += 0.5 * Zpp[:, None] * d[0] ** 2
                z, x, C, S, conv = self.newton(cdq[:, ks], pred)
                ratio, sg = self._hadamard(self.jz(x, C, S)[self.sel])
                # the branch of the predictor (the incoming one, continued smoothly): Newton must not land on
                # another branch of the same sign of det J past a branch point (the velocity would jump)
                psg = self._pred_sign(cdq[:, ks], pred)
                dist = np.max(np.abs(d / self.qscale[:, None]), axis=0)
                # chain: every point within h of the one before it (the first: of the state), so that no
                # dead point or gap in the assembly wider than h is stepped over
                prev = np.concatenate([st_dq[:, None], cdq[:, ks[:-1]]], axis=1)
                near = np.max(np.abs((cdq[:, ks] - prev) / self.qscale[:, None]), axis=0) <= reach
                trust = 0.2 * np.maximum(dist, 1e-3) * (1.0 + np.max(np.abs(Zp * self.qscale[None, :])))
                with np.errstate(invalid="ignore"):
                    good = (
                        conv
                        & near
                        & (ratio > SINGULAR_TOL)
                        & (sg == sgn)
                        & (psg == sgn)
                        & (np.max(np.abs(z - pred), axis=0) <= trust)
                    )
                if good.any():  # each point's velocity continuous with the one before it (the first: the state)
                    pz = np.concatenate([st_z[:, None], z[:, :-1]], axis=1)
                    good &= ~self._step_kinked(prev, pz, cdq[:, ks], z)
                m = int(np.argmin(good)) if not good.all() else good.size
                if m:
                    cz[:, ks[:m]] = z[:, :m]
                    cok[ks[:m]] = True
                    # a dead point exactly at the accepted point: keep the older state; and by a singular pose,
                    # where the branch of a state is moot (:meth:`_kinked`): the points on from the older one
                    nst = self._state(cdq[:, ks[m - 1]], z[:, m - 1]) if ratio[m - 1] >= RATIO_NEAR else None
                    if nst is None and ratio[m - 1] < RATIO_NEAR:
                        k += m
                        continue
                    if nst is None:
                        m = 0
                    else:
                        st_dq, st_z, st = cdq[:, ks[m - 1]].copy(), z[:, m - 1].copy(), nst
                        blocked = None
                        k += m
                        continue
            zk, at = self._walk(st_dq, st_z, cdq[:, k], h, sgn, stops)
            if zk is None:
                blocked = (st_dq[0], cdq[0, k])
                stuck.append(at)
            else:
                nst = self._state(cdq[:, k], zk) if not self._near_pose(cdq[:, k], zk) else None
                cz[:, k], cok[k] = zk, True
                if nst is not None:
                    st_dq, st_z, st = cdq[:, k].copy(), zk, nst
                blocked = None
            k += 1

    def _positions(self, dq, x_out, closed, stuck, start=None, sgn=None, stops=None):
        """Fill ``x_out`` (nx, N) and ``closed`` by continuation; return (C, S) of the points when all closed.

        The inputs where the continuation stopped (dead points) are appended to ``stuck`` (and the states
        ``(dq, z)`` there to ``stops``); ``start`` and ``sgn`` as in :meth:`_coarse`.
        """
        sgn = self.sgn0 if sgn is None else sgn
        dq_start = np.zeros(self.W) if start is None else start[0]
        Nn, h = dq.shape[1], COARSE_STEP
        step = np.empty(Nn)
        step[0] = np.max(np.abs((dq[:, 0] - dq_start) / self.qscale))
        if Nn > 1:
            step[1:] = np.max(np.abs(np.diff(dq / self.qscale[:, None], axis=1)), axis=0)
        bins = np.floor(np.cumsum(step) / h)
        newbin = np.diff(bins) != 0
        starts = np.concatenate([[0], np.flatnonzero(newbin) + 1])
        nb = starts.size
        counts = np.diff(np.concatenate([starts, [Nn]]))
        cdq = dq[:, starts]
        # coarse points at most h apart, from the sketch: a large step between rows (a coarse sweep,
        # degrees given for radians) is subdivided, so the continuation never steps over a dead point
        prev = np.concatenate([dq_start[:, None], cdq[:, :-1]], axis=1)
        gap = np.max(np.abs((cdq - prev) / self.qscale[:, None]), axis=0)
        sub = np.maximum(np.ceil(gap / h * (1.0 - 1e-12)), 1).astype(int)
        if sub.max() > 1:
            frac = np.concatenate([np.arange(1, m + 1) / m for m in sub])
            seg = np.repeat(np.arange(nb), sub)
            ecdq = prev[:, seg] + frac * (cdq[:, seg] - prev[:, seg])
            real = np.cumsum(sub) - 1
            ecdq[:, real] = cdq  # exactly the rows
        else:
            ecdq, real = cdq, np.arange(nb)
        ecz = np.full((self.dz, ecdq.shape[1]), np.nan)
        ecok = np.zeros(ecdq.shape[1], dtype=bool)
        self._coarse(ecdq, ecz, ecok, h, stuck, start=start, sgn=sgn, stops=stops)
        cz, cok = ecz[:, real], ecok[real]

        if not cok.any():
            return None
        # first (per input) and, for one input, second derivatives of z at the coarse points
        good = np.flatnonzero(cok)
        xc = self.coordinates(cdq[:, good], cz[:, good])
        Zp = np.zeros((self.dz, self.W, nb))
        Zpp = np.zeros((self.dz, nb))
        for w in range(self.W):
            e = np.zeros((self.W, good.size))
            e[w] = 1.0
            xd, xdd, _ = self.derivatives(xc, e, np.zeros_like(e))
            Zp[:, w, good] = self.N.T @ xd
            if self.W == 1:
                Zpp[:, good] = self.N.T @ xdd
        Zp = np.nan_to_num(Zp)
        Zpp = np.nan_to_num(Zpp)
        # start of every point from its coarse point: cubic Hermite (one input) or Taylor
        allok = bool(cok.all())
        if allok:
            idx = None
            b = np.repeat(np.arange(nb), counts)
            d = dq - np.repeat(cdq, counts, axis=1)
        else:
            bid = np.repeat(np.arange(nb), counts)
            idx = np.flatnonzero(cok[bid])
            b = bid[idx]
            d = dq[:, idx] - cdq[:, b]
        if self.W == 1:
            # per-bin cubic in the local input offset d: a0 + a1 d + a2 d^2 + a3 d^3
            nxt = np.minimum(np.arange(nb) + 1, nb - 1)
            span = cdq[0, nxt] - cdq[0]
            use = (nxt > np.arange(nb)) & cok & cok[nxt] & (np.abs(span / self.qscale[0]) > 1e-3)
            a0, a1 = cz.copy(), Zp[:, 0].copy()
            a2, a3 = 0.5 * Zpp, np.zeros_like(Zpp)
            if np.any(use):
                u = np.flatnonzero(use)
                hs = span[u]
                dz_ = cz[:, nxt[u]] - cz[:, u]
                m0, m1 = Zp[:, 0, u], Zp[:, 0, nxt[u]]
                a2[:, u] = (3 * dz_ / hs - 2 * m0 - m1) / hs
                a3[:, u] = (m0 + m1 - 2 * dz_ / hs) / (hs * hs)
            coef = np.stack([a0, a1, a2, a3])  # (4, dz, nb)
            cb = np.repeat(coef, counts, axis=2) if allok else coef[:, :, b]
            t = d[0]
            pred = cb[0] + t * (cb[1] + t * (cb[2] + t * cb[3]))
        else:
            zb = np.repeat(cz, counts, axis=1) if allok else cz[:, b]
            Zb = np.repeat(Zp, counts, axis=2) if allok else Zp[:, :, b]
            pred = zb + np.einsum("dwn,wn->dn", Zb, d)
        dqi = dq if allok else dq[:, idx]
        z, x, C, S, conv = self.newton(dqi, pred)
        ratio, sg = self._hadamard(self.jz(x, C, S)[self.sel])
        zpb = np.max(np.abs(Zp * self.qscale[None, :, None]), axis=(0, 1))
        trust = 0.2 * h * (1.0 + (np.repeat(zpb, counts) if allok else zpb[b]))
        with np.errstate(invalid="ignore"):
            ok = conv & (sg == sgn) & (np.max(np.abs(z - pred), axis=0) <= trust)
        # each row's velocity continuous with its coarse point's (no branch point stepped over onto the other
        # branch between them: :meth:`_kinked`); a row that fails is walked to from the row before it
        bdq = np.repeat(cdq, counts, axis=1) if allok else cdq[:, b]
        zbz = np.repeat(cz, counts, axis=1) if allok else cz[:, b]
        if self.W == 1:
            zr, zrr, _ = self.derivatives(x, np.ones((1, x.shape[1])), np.zeros((1, x.shape[1])), (C, S))
            dd = d[0]
            zb1 = np.repeat(Zp[:, 0], counts, axis=1) if allok else Zp[:, 0, b]
            zb2 = np.repeat(Zpp, counts, axis=1) if allok else Zpp[:, b]
            NT = self.N.T
            xc_r = self._hadamard(self.jz(xc, *self.trig(xc))[self.sel])[0]
            rc = np.ones(nb)
            rc[good] = xc_r
            rb = np.repeat(rc, counts) if allok else rc[b]
            rates0, rates1 = (zb1 * dd, zb2 * dd * dd), ((NT @ zr) * dd, (NT @ zrr) * dd * dd)
            ok &= ~self._kinked(d, zbz, z, rates0, rates1, rb, ratio)
        else:
            ok &= ~self._step_kinked(bdq, zbz, dqi, z)
        if allok and ok.all():
            x_out[:] = x
            closed[:] = True
            return C, S
        ii = np.arange(Nn) if allok else idx
        x_out[:, ii[ok]] = x[:, ok]
        closed[ii[ok]] = True
        # repair the points that failed: sequential continuation from the previous point that closed
        zfull = np.full((self.dz, Nn), np.nan)
        zfull[:, ii[ok]] = z[:, ok]
        bid = np.repeat(np.arange(nb), counts)
        skip_bin = -1
        for i in ii[~ok]:
            if bid[i] == skip_bin:
                continue
            prev = i - 1  # (not from a row by a singular pose, where the branch of a state is moot)
            while prev >= 0 and (not closed[prev] or self._near_pose(dq[:, prev], zfull[:, prev])):
                prev -= 1
            if prev >= 0 and bid[prev] == bid[i]:
                src_dq, src_z = dq[:, prev], zfull[:, prev]
            else:
                src_dq, src_z = cdq[:, bid[i]], cz[:, bid[i]]
            zi, at = self._walk(src_dq, src_z, dq[:, i], h, sgn, stops)
            if zi is None:
                stuck.append(at)
                skip_bin = bid[i]
                continue
            zfull[:, i] = zi
            x_out[:, i] = self.coordinates(dq[:, i : i + 1], zi[:, None])[:, 0]
            closed[i] = True
        return None


def _stop_on(stops, a, b, qscale):
    """The state ``(dq, z)`` of ``stops`` that lies on the segment of inputs from ``a`` to ``b``, or None."""
    span = b - a
    nn = float(span @ span)
    for at, z in reversed(stops):
        t = float((at - a) @ span) / nn if nn > 0 else 0.0
        if -1e-9 <= t <= 1 + 1e-9 and np.max(np.abs(a + t * span - at) / qscale) <= 1e-6:
            return at, z
    return None


def _as_rows(name, v, N, W):
    a = finite_array(name, v)
    if a.ndim == 0:
        a = np.full((N, W), float(a))
    elif a.ndim == 1 and W == 1:
        a = a[:, None]
    elif a.ndim == 1 and a.shape[0] == W and N == 1:
        a = a[None, :]
    if a.shape != (N, W):
        raise GearleverError(f"{name} must have shape ({N},) or ({N}, {W}) like q, got {a.shape}")
    return a


def input_name(spec) -> str:
    """Column name of an input: the link (``crank``, ``crank_rel_ground2``) or the slider (``piston``)."""
    if spec.kind == "slider":
        return spec.name
    return spec.name if spec.relative_to is None else f"{spec.name}_rel_{spec.relative_to}"


def _warn_degrees(system: KinematicSystem, qa: np.ndarray) -> None:
    """One :class:`~gearlever.errors.GearleverWarning` when a link input's rows look like degrees.

    Looks like degrees: at least two distinct values, all whole numbers, and
    the largest magnitude beyond a full turn (``0, 10, ..., 360``).
    """
    for j, spec in enumerate(system.model.inputs):
        v = qa[:, j]
        if spec.kind != "link" or v.size < 2 or any(h != round(h) for h in v[:8].tolist()):
            continue  # (the first rows decide without a pass over all of them, most of the time)
        if not np.all(v == np.round(v)):
            continue
        if np.max(np.abs(v)) > 2 * np.pi and np.ptp(v) > 0:
            warnings.warn(
                f"q: input {spec.label!r} runs {v.min():g} .. {v.max():g} in whole numbers: this looks like "
                "degrees, but link inputs are radians (np.radians converts)",
                GearleverWarning,
                stacklevel=3,
            )
            return


def solve(system: KinematicSystem, q, qdot=None, qddot=None, branch: str = DEFAULT_BRANCH) -> MechanismResult:
    """Positions, velocities and accelerations of every link and point over the input rows.

    Parameters
    ----------
    system : KinematicSystem
    q : array_like
        ``(N,)`` for one input or ``(N, W)``, columns in the order of
        ``[[inputs]]``: link angles in rad (absolute, or relative to
        ``relative_to``), slider displacements in length units from the sketch.
    qdot, qddot : array_like, optional
        Input velocities and accelerations, same shape (default 1 and 0: the
        results are then the velocity and acceleration analogues, and
        :meth:`MechanismResult.columns` names them so: ``omega_coupler_per_crank``).
    branch : {"continue", "keep", "stop"}
        What the rows do at a *branch point*, a singular pose past which the
        input goes on (:mod:`gearlever.mechanism.branch`): ``"continue"``
        (the default) on the branch that keeps the motion smooth (velocity
        continuous, the input's direction kept: the motion the mechanism
        makes, carried through by its inertia, as PMKS+ animates it),
        leaving the sketch's assembly branch; ``"keep"`` on the sketch's
        assembly branch (the sign of ``det J_z``), the velocity jumping
        there; ``"stop"`` not past it (the rows there not closed).  Every
        branch point passed is in :attr:`MechanismResult.branch_points`.  A
        dead point of the input (no assembly past it) stops the rows under
        every policy.

    Returns
    -------
    MechanismResult

    Notes
    -----
    Continuation (E. L. Allgower and K. Georg, *Numerical Continuation
    Methods*, Springer, 1990, ch. 2, predictor-corrector): the inputs are
    followed from the sketch in steps of at most :data:`COARSE_STEP`
    through a coarse subsequence (second-order Taylor predictor, Newton
    corrector), then every point is corrected at once by batched Newton from
    a cubic Hermite (one input) or Taylor (several) start.  A point whose
    correction moves farther than the predictor explains, or where the sign
    of ``det J`` differs from the sketch's (the other assembly branch), is
    re-walked sequentially and otherwise left NaN with ``closed`` False.
    Rows farther apart than :data:`COARSE_STEP` (a coarse sweep) are joined
    by intermediate continuation points, so the result does not depend on
    how densely the rows sample the path: the continuation never steps over
    a dead point onto the other branch.  Where it meets one (the input
    reverses, the branch would change, or the assembly ends), it stops: the
    first row not reached says so in :attr:`MechanismResult.reason` (with
    the input where it stopped), :attr:`MechanismResult.dead_rows` lists it,
    and the later rows stay NaN.  Link inputs given as whole numbers beyond a
    full turn (degrees by mistake) give a
    :class:`~gearlever.errors.GearleverWarning`.

    A mechanism made of drivers and RRR/RRP dyads is first offered to the
    closed-form path (:mod:`gearlever.mechanism.assur`); it answers (equal to
    the continuation to rounding) only away from dead points and for rows
    at most :data:`COARSE_STEP` apart, otherwise the continuation answers.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> r = solve(KinematicSystem(m), [0.0, np.pi / 2])
    >>> np.round(r.point["A"], 12).tolist()
    [[1.0, 0.0], [0.0, 1.0]]

    A parallelogram four-bar folds onto one line at crank 180 deg and goes on
    as a parallelogram (``"continue"``), or as an anti-parallelogram
    (``"keep"``), or stops there (``"stop"``):

    >>> p = model_from_dict({"points": {"O": [0, 0], "Q": [10, 0], "A": [0, 4], "B": [10, 4]},
    ...     "links": {"ground": ["O", "Q"], "crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["Q", "B"]},
    ...     "inputs": [{"link": "crank"}]})
    >>> q = np.radians([90.0, 150.0, 210.0, 270.0])
    >>> for policy in ("continue", "keep", "stop"):
    ...     r = solve(KinematicSystem(p), q, branch=policy)
    ...     print(policy, np.round(np.degrees(r.angle["rocker"]), 6).tolist(), r.side.tolist())
    continue [90.0, 150.0, 210.0, 270.0] [1, 1, -1, -1]
    keep [90.0, 150.0, 166.898227, 133.602819] [1, 1, 1, 1]
    stop [90.0, 150.0, nan, nan] [1, 1, 0, 0]
    >>> solve(KinematicSystem(p), q).branch_points[0].q
    (3.141592653589793,)
    """
    check_branch(branch)
    W = system.W
    qa = finite_array("q", q)
    if qa.ndim == 0:
        qa = qa.reshape(1, 1) if W == 1 else qa
    if qa.ndim == 1:
        qa = qa[:, None] if W == 1 else (qa[None, :] if qa.shape[0] == W else qa)
    if qa.ndim != 2 or qa.shape[1] != W:
        raise GearleverError(f"q must have shape (N,) for one input or (N, {W}) for {W} inputs, got {np.shape(q)}")
    if qa.shape[0] == 0:
        raise GearleverError("q must hold at least one input row")
    N = qa.shape[0]
    _warn_degrees(system, qa)
    qd = np.ones((N, W)) if qdot is None else _as_rows("qdot", qdot, N, W)
    qdd = np.zeros((N, W)) if qddot is None else _as_rows("qddot", qddot, N, W)
    plan = system.dyad_plan
    fast = plan.solve(qa.T, qd.T, qdd.T) if plan is not None else None
    points, side = (), None
    if fast is not None and not np.all(np.isfinite(fast[0])):
        fast = None  # a row where a dyad does not assemble: the continuation answers (closed = False there)
    if fast is not None:
        x, xd, xdd, CS, _ = fast
        closed = np.ones(N, dtype=bool)
        reason = np.empty(N, dtype=object)
        reason.fill("")  # three times faster than np.full for object arrays
    else:
        x, xd, xdd, closed, reason, CS, points, side = system.solve(qa.T, qd.T, qdd.T, branch)
    fpoints = fast[4] if fast is not None else None
    side = np.ones(N, dtype=int) if side is None else side
    r = MechanismResult(qa, qd, qdd, x.T, xd.T, xdd.T, closed, reason, system, tuple(points), side)
    object.__setattr__(r, "_analogues", qdot is None)
    object.__setattr__(r, "_cs", CS)
    if fpoints is not None:
        object.__setattr__(r, "_fast_points", fpoints)
    return r


@dataclass(frozen=True)
class MechanismResult(Result):
    """Positions, velocities and accelerations of a mechanism over its input rows.

    Attributes
    ----------
    q, qdot, qddot : ndarray
        ``(N, W)`` inputs and their rates, columns in ``[[inputs]]`` order.
    x, xdot, xddot : ndarray
        ``(N, n + S)`` reduced coordinates: rotation from the sketch of each
        moving link (rad), then displacement of each slider; NaN where not
        closed (rates also NaN at a dead point).
    closed : ndarray of bool
        ``(N,)``: the mechanism is assembled at this input row.
    reason : ndarray of str
        ``(N,)``: ``""`` where closed with finite rates, otherwise why not.
    system : KinematicSystem
        The compiled model.
    branch_points : tuple of BranchPoint
        The branch points the rows passed (:func:`solve`'s ``branch``), in
        row order: where the assembly branch changed (``"continue"``) or the
        velocity jumped (``"keep"``); empty when none.
    side : ndarray of int
        ``(N,)``: the assembly branch of each row, +1 the sketch's (the sign
        of ``det J_z`` there), -1 the other, 0 where not closed.

    Dicts (computed when first asked for): :attr:`angle`, :attr:`omega`,
    :attr:`alpha` (link -> ``(N,)``), :attr:`point`, :attr:`velocity`,
    :attr:`acceleration` (point -> ``(N, 2)``), :attr:`displacement`,
    :attr:`slider_velocity`, :attr:`slider_acceleration` (slider -> ``(N,)``);
    arrays :attr:`pose`, :attr:`pose_velocity`, :attr:`pose_acceleration`
    (``(N, n, 3)``: ``x, y, theta`` of each moving link's frame, the columns
    of :func:`~gearlever.mechanism.constraints.constraint_jacobian`).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [2, 0]},
    ...                          "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...                          "inputs": [{"link": "crank"}]})
    >>> r = m.solve(np.array([0.0, np.pi / 2]))
    >>> np.round(r.point["A"], 12) + 0.0
    array([[2., 0.],
           [0., 2.]])
    >>> np.round(r.velocity["A"][1], 12) + 0.0  # analogue: d(A)/d(theta) at 90 degrees
    array([-2.,  0.])
    """

    q: np.ndarray
    qdot: np.ndarray
    qddot: np.ndarray
    x: np.ndarray
    xdot: np.ndarray
    xddot: np.ndarray
    closed: np.ndarray
    reason: np.ndarray
    system: KinematicSystem = field(repr=False, compare=False)
    branch_points: tuple = ()
    side: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def model(self) -> MechanismModel:
        return self.system.model

    @property
    def dead_rows(self) -> np.ndarray:
        """Rows (indices) at which, or in the step to which, the continuation met a dead point.

        A row closed exactly at a dead point (rates undefined) or the first row
        the continuation could not reach, because a dead point or the end of
        the assembly lies in the step from the row before it (or from the
        sketch); :attr:`reason` says which and where.  The rows after a stop
        are not reached either (NaN): the branch never changes silently.
        """
        return np.flatnonzero(np.array([r.startswith("dead point") for r in self.reason], dtype=bool))

    def _links(self, arr, ground_value):
        m = self.model
        out = {}
        for k, link in m.links.items():
            if k == GROUND:
                out[k] = np.full(arr.shape[0], ground_value(link))
            else:
                out[k] = arr[:, self.system.idx[k]]
        return _NamedDict(out, "link")

    @cached_property
    def angle(self) -> dict:
        """Link -> absolute angle (rad): sketch angle plus rotation."""
        m = self.model
        out = self._links(self.x, lambda link: link.angle0)
        for k in m.moving:
            out[k] = out[k] + m.links[k].angle0
        return out

    @cached_property
    def omega(self) -> dict:
        """Link -> angular velocity (rad/s, or the velocity analogue)."""
        return self._links(self.xdot, lambda link: 0.0)

    @cached_property
    def alpha(self) -> dict:
        """Link -> angular acceleration (rad/s^2, or the acceleration analogue)."""
        return self._links(self.xddot, lambda link: 0.0)

    @cached_property
    def _point_kinematics(self):
        ks = self.system
        names, f = _point_forms(ks)
        ok = self.closed
        allok = bool(ok.all())
        x = self.x.T if allok else np.where(ok, self.x.T, 0.0)
        CS = self.__dict__.get("_cs") if allok else None
        C, S = ks.trig(x) if CS is None else CS
        (X, Y), (VX, VY), (AX, AY) = ks.eval_forms(f, x, C, S, self.xdot.T, self.xddot.T)
        if not allok:
            X[:, ~ok] = np.nan
            Y[:, ~ok] = np.nan
        return names, (X, Y), (VX, VY), (AX, AY)

    def _pdict(self, which):
        fast = self.__dict__.get("_fast_points") or {}
        names = _point_forms(self.system)[0]

        def compute(p):
            got = fast.get(p)
            if got is not None:
                return got[which]
            names, *arrs = self._point_kinematics
            X, Y = arrs[which]
            return np.stack([X[names.index(p)], Y[names.index(p)]], axis=1)

        return _LazyDict([p for p in names if not p.startswith("\0")], compute, "point")

    @cached_property
    def point(self) -> dict:
        """Point -> position ``(N, 2)``."""
        return self._pdict(0)

    @cached_property
    def velocity(self) -> dict:
        """Point -> velocity ``(N, 2)`` (or its analogue)."""
        return self._pdict(1)

    @cached_property
    def acceleration(self) -> dict:
        """Point -> acceleration ``(N, 2)`` (or its analogue)."""
        return self._pdict(2)

    def _sliders(self, arr):
        n = self.system.n
        return _NamedDict({s.name: arr[:, n + j] for j, s in enumerate(self.model.sliders)}, "slider")

    @cached_property
    def displacement(self) -> dict:
        """Slider -> displacement along its guide from the sketch (length)."""
        return self._sliders(self.x)

    @cached_property
    def slider_velocity(self) -> dict:
        """Slider -> sliding velocity along its guide."""
        return self._sliders(self.xdot)

    @cached_property
    def slider_acceleration(self) -> dict:
        """Slider -> sliding acceleration along its guide."""
        return self._sliders(self.xddot)

    def _pose(self, which):
        names, *arrs = self._point_kinematics
        X, Y = arrs[which]
        m = self.model
        out = np.empty((X.shape[1], len(m.moving), 3))
        base = [self.x, self.xdot, self.xddot][which]
        for i, k in enumerate(m.moving):
            j = names.index("\0" + k)
            out[:, i, 0], out[:, i, 1] = X[j], Y[j]
            out[:, i, 2] = base[:, i] + (m.links[k].angle0 if which == 0 else 0.0)
        return out

    @cached_property
    def pose(self) -> np.ndarray:
        """``(N, n, 3)``: ``x, y, theta`` of each moving link (origin at its first point)."""
        return self._pose(0)

    @cached_property
    def pose_velocity(self) -> np.ndarray:
        """``(N, n, 3)``: time derivative of :attr:`pose`."""
        return self._pose(1)

    @cached_property
    def pose_acceleration(self) -> np.ndarray:
        """``(N, n, 3)``: second time derivative of :attr:`pose`."""
        return self._pose(2)

    @property
    def analogues(self) -> bool:
        """True when ``qdot`` was not given to :func:`solve` (rates 1: the rates are analogues, not velocities)."""
        return bool(self.__dict__.get("_analogues", False))

    def columns(self, degrees: bool = False, per: str | None = None) -> dict:
        """The result as named columns: the model's names, each column name ending in its unit.

        Parameters
        ----------
        degrees : bool
            Angles in degrees (``_deg``, the command line) instead of radians
            (``_rad``); angular rates stay in rad.
        per : str, optional
            Name the rates as *analogues* per unit rate of this input
            (``omega_coupler_per_crank``: ``d theta_coupler / d crank``;
            accelerations ``..._per_crank_sq``): the caller's ``qdot`` is 1 for
            that input (and the others move in proportion) and ``qddot`` 0.
            When None: analogues per the input (or ``per_unit_rates`` for
            several inputs) when ``qdot`` was not given to :func:`solve`,
            velocities otherwise (``omega_coupler_rad_s``, ``v_P_x_mm_s``:
            ``qdot`` in rad/s or length/s).

        Returns
        -------
        dict
            One row per input point: ``input_<name>_rad`` (or ``_deg``, or the
            length unit for a slider input), ``qdot_<name>_...``,
            ``qddot_<name>_...``; per moving link ``<link>_angle_rad``,
            ``omega_<link>_...``, ``alpha_<link>_...``; per slider
            ``<slider>_s_<u>``, ``v_<slider>_...``, ``a_<slider>_...``; per
            point ``<P>_x_<u>``, ``<P>_y_<u>``, ``v_<P>_x_...``, ``v_<P>_y_...``,
            ``a_<P>_x_...``, ``a_<P>_y_...``.  Lengths in the model's
            ``units`` label (``len`` when it gives none).  This is the one
            naming of result columns: :meth:`to_frame` and ``gearlever
            mechanism analyze`` both use it.

        Examples
        --------
        >>> from gearlever.mechanism.model import model_from_dict
        >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]}, "mechanism": {"units": "mm"},
        ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
        >>> list(solve(KinematicSystem(m), [0.0, 1.0]).columns())[3:6]
        ['crank_angle_rad', 'omega_crank_per_crank', 'alpha_crank_per_crank_sq']
        >>> list(solve(KinematicSystem(m), [0.0, 1.0], qdot=[2.0, 2.0]).columns())[4]
        'omega_crank_rad_s'
        """
        m = self.model
        u = m.units or "len"
        ang, conv = ("deg", np.degrees) if degrees else ("rad", lambda x: x)
        names = [input_name(spec) for spec in m.inputs]
        if per is None and self.analogues:
            per = names[0] if len(names) == 1 else "unit_rates"
        if per is None:
            r1, r2, l1, l2 = "rad_s", "rad_s2", f"{u}_s", f"{u}_s2"
        else:
            r1, r2, l1, l2 = f"per_{per}", f"per_{per}_sq", f"{u}_per_{per}", f"{u}_per_{per}_sq"
        cols = {}
        for i, spec in enumerate(m.inputs):
            slider = spec.kind == "slider"
            cols[f"input_{names[i]}_{u if slider else ang}"] = self.q[:, i] if slider else conv(self.q[:, i])
            cols[f"qdot_{names[i]}_{l1 if slider else r1}"] = self.qdot[:, i]
            cols[f"qddot_{names[i]}_{l2 if slider else r2}"] = self.qddot[:, i]
        for k in m.moving:
            cols[f"{k}_angle_{ang}"] = conv(self.angle[k])
            cols[f"omega_{k}_{r1}"] = self.omega[k]
            cols[f"alpha_{k}_{r2}"] = self.alpha[k]
        for sname in self.displacement:
            cols[f"{sname}_s_{u}"] = self.displacement[sname]
            cols[f"v_{sname}_{l1}"] = self.slider_velocity[sname]
            cols[f"a_{sname}_{l2}"] = self.slider_acceleration[sname]
        for p in m.points:
            P, V, A = self.point[p], self.velocity[p], self.acceleration[p]
            cols[f"{p}_x_{u}"], cols[f"{p}_y_{u}"] = P[:, 0], P[:, 1]
            cols[f"v_{p}_x_{l1}"], cols[f"v_{p}_y_{l1}"] = V[:, 0], V[:, 1]
            cols[f"a_{p}_x_{l2}"], cols[f"a_{p}_y_{l2}"] = A[:, 0], A[:, 1]
        return cols

    def _frame_columns(self) -> dict:
        cols = self.columns()
        cols["closed"] = self.closed
        cols["reason"] = self.reason
        return cols


class UnknownName(GearleverError, KeyError):
    """A result looked up by a name the model does not have (a GearleverError and a KeyError)."""

    def __str__(self) -> str:  # KeyError would quote the whole message
        return str(self.args[0]) if self.args else ""


def _unknown(key, kind: str, names) -> UnknownName:
    import difflib

    names = [str(n) for n in names]
    close = difflib.get_close_matches(str(key), names, n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    shown = ", ".join(names[:50]) + (", ..." if len(names) > 50 else "")
    return UnknownName(f"unknown {kind} {key!r}{hint}; the {kind}s are: {shown}")


class _NamedDict(dict):
    """A dict of results by element name; a missing name raises :class:`UnknownName` listing the valid ones."""

    def __init__(self, data, kind: str):
        super().__init__(data)
        self._kind = kind

    def __missing__(self, key):
        raise _unknown(key, self._kind, self)


class _LazyDict(Mapping):
    """A read-only mapping whose values are computed on first access."""

    def __init__(self, keys, compute, kind: str = "name"):
        self._keys = list(keys)
        self._compute = compute
        self._cache = {}
        self._kind = kind

    def __getitem__(self, key):
        if key not in self._cache:
            if key not in self._keys:
                raise _unknown(key, self._kind, self._keys)
            self._cache[key] = self._compute(key)
        return self._cache[key]

    def __contains__(self, key):
        return key in self._keys

    def __iter__(self):
        return iter(self._keys)

    def __len__(self):
        return len(self._keys)

    def __repr__(self):
        return f"<{len(self._keys)} arrays: {', '.join(self._keys)}>"


def _point_forms(ks: KinematicSystem):
    cached = getattr(ks, "_pforms", None)
    if cached is not None:
        return cached
    m = ks.model
    names, cs, Vs, Ws = [], [], [], []
    for p, X in m.points.items():
        carriers = m.carriers(p)
        if not carriers:
            continue
        c, V, W = ks.form_at(carriers[0], X)
        names.append(p)
        cs.append(c)
        Vs.append(V)
        Ws.append(W)
    for k in m.moving:
        c, V, W = ks.form_at(k, m.links[k].origin)
        names.append("\0" + k)
        cs.append(c)
        Vs.append(V)
        Ws.append(W)
    out = (names, _Forms(np.array(cs), np.array(Vs), np.array(Ws)))
    ks._pforms = out
    return out
