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

from collections import deque
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite_array
from gearlever.errors import GearleverError
from gearlever.mechanism.constraints import mesh_coefficients
from gearlever.mechanism.model import GROUND, MechanismModel
from gearlever.mechanism.structural import RANK_TOL, analyze_structure, independent_rows, numeric_rank

__all__ = ["KinematicSystem", "MechanismResult", "solve"]

#: Largest step (rad, or length / model length scale) of the sequential continuation.
COARSE_STEP = 0.25
#: Hadamard-ratio threshold below which the reduced Jacobian counts as singular (a dead point).
SINGULAR_TOL = 1e-9

REASON_UNREACHED = "not reached continuously from the sketch (past a dead point, or no assembly there)"
REASON_DEAD = "dead point: the constraint Jacobian is singular (velocities undefined)"


def _null_space(A: np.ndarray, ncols: int) -> np.ndarray:
    if A.shape[0] == 0:
        return np.eye(ncols)
    u, sv, vt = np.linalg.svd(A)
    r = int(np.sum(sv > RANK_TOL * max(sv[0] if sv.size else 0.0, 1e-300)))
    return vt[r:].T.copy()


class _Forms:
    """Stacked point expressions ``c + sum_k R(phi_k) v_k + sum_j w_j s_j R(phi_o(j)) u_j``."""

    def __init__(self, c, V, W):
        self.c = np.asarray(c, dtype=float).reshape(-1, 2)
        self.Vx = np.ascontiguousarray(np.asarray(V, dtype=float).reshape(len(self.c), -1, 2)[..., 0].T)
        self.Vy = np.ascontiguousarray(np.asarray(V, dtype=float).reshape(len(self.c), -1, 2)[..., 1].T)
        self.W = np.ascontiguousarray(np.asarray(W, dtype=float).reshape(len(self.c), -1).T)
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
        x0 = np.zeros((1, self.nx))
        Jz = self._jz(x0, *self._trig(x0))[0]
        if numeric_rank(Jz / self.L) < self.dz:
            raise GearleverError(
                "inputs: the inputs do not fix the mechanism at the sketch (the sketch is a dead point, "
                "or an input is locked)"
            )
        self.sel = np.array(independent_rows(Jz / self.L), dtype=int) if self.dz else np.zeros(0, dtype=int)
        self.sgn0 = float(np.sign(np.linalg.det(Jz[self.sel][:, :]))) if self.dz else 1.0

    def _jz_tables(self):
        f, n, N = self.closure, self.n, self.N
        K = f.c.shape[0]
        dz = self.dz
        Nphi = N[:n]  # (n, dz)
        # rows interleaved (x0, y0, x1, y1, ...) x dz, flattened row-major
        self._A1 = (f.Vx[:, :, None] * Nphi[:, None, :]).reshape(n, K * dz)
        self._A2 = (f.Vy[:, :, None] * Nphi[:, None, :]).reshape(n, K * dz)
        S = self.S
        if S:
            Ns = N[n:]  # (S, dz)
            self._B1 = (f.W[:, :, None] * Ns[:, None, :]).reshape(S, K * dz)
            No = np.where(self.so[:, None] >= 0, Nphi[np.maximum(self.so, 0)], 0.0)  # (S, dz)
            self._B2 = (f.W[:, :, None] * No[:, None, :]).reshape(S, K * dz)

    # ------------------------------------------------------------- evaluation
    def _trig(self, x):
        phi = x[:, : self.n]
        return np.cos(phi), np.sin(phi)

    def _ru(self, c, s):
        """Slider directions turned with their guides, (N, S) each."""
        if not self.S:
            return None, None
        ce = np.concatenate([c, np.ones((c.shape[0], 1))], axis=1)[:, self.so]
        se = np.concatenate([s, np.zeros((s.shape[0], 1))], axis=1)[:, self.so]
        return ce * self.ux - se * self.uy, se * self.ux + ce * self.uy

    def eval_forms(self, f: _Forms, x, c, s, xd=None, xdd=None):
        """Positions (and velocities, accelerations) of stacked expressions: arrays ``(N, K)`` x, y each."""
        n = self.n
        X = f.c[:, 0] + c @ f.Vx - s @ f.Vy
        Y = f.c[:, 1] + s @ f.Vx + c @ f.Vy
        S = self.S
        if S and f.has_sliders:
            rux, ruy = self._ru(c, s)
            sl = x[:, n:]
            X = X + (sl * rux) @ f.W
            Y = Y + (sl * ruy) @ f.W
        out = [(X, Y)]
        if xd is None:
            return out
        w = xd[:, :n]
        # sum_k w_k R'_k v_k = rot90(sum_k w_k R_k v_k)
        a, b = w * c, w * s
        RX, RY = a @ f.Vx - b @ f.Vy, b @ f.Vx + a @ f.Vy
        VX, VY = -RY, RX
        if S and f.has_sliders:
            sd = xd[:, n:]
            wo = np.concatenate([w, np.zeros((w.shape[0], 1))], axis=1)[:, self.so]
            VX = VX + (sd * rux - sl * wo * ruy) @ f.W
            VY = VY + (sd * ruy + sl * wo * rux) @ f.W
        out.append((VX, VY))
        if xdd is None:
            return out
        e = xdd[:, :n]
        a2, b2 = e * c, e * s
        w2 = w * w
        a3, b3 = w2 * c, w2 * s
        AX = -(b2 @ f.Vx + a2 @ f.Vy) - (a3 @ f.Vx - b3 @ f.Vy)
        AY = (a2 @ f.Vx - b2 @ f.Vy) - (b3 @ f.Vx + a3 @ f.Vy)
        if S and f.has_sliders:
            sdd = xdd[:, n:]
            eo = np.concatenate([e, np.zeros((e.shape[0], 1))], axis=1)[:, self.so]
            # s'' R u + (2 s' w + s e) R' u - s w^2 R u
            k1 = sdd - sl * wo * wo
            k2 = 2.0 * sd * wo + sl * eo
            AX = AX + (k1 * rux - k2 * ruy) @ f.W
            AY = AY + (k1 * ruy + k2 * rux) @ f.W
        out.append((AX, AY))
        return out

    def _residual(self, x, c, s):
        X, Y = self.eval_forms(self.closure, x, c, s)[0]
        G = np.empty((x.shape[0], 2 * X.shape[1]))
        G[:, 0::2], G[:, 1::2] = X, Y
        return G

    def _jz(self, x, c, s):
        """Reduced Jacobian dG/dz, shape (N, 2K, dz)."""
        K, dz = self.closure.c.shape[0], self.dz
        JX = -(s @ self._A1 + c @ self._A2)
        JY = c @ self._A1 - s @ self._A2
        if self.S:
            rux, ruy = self._ru(c, s)
            sl = x[:, self.n :]
            JX = JX + rux @ self._B1 - (sl * ruy) @ self._B2
            JY = JY + ruy @ self._B1 + (sl * rux) @ self._B2
        J = np.empty((x.shape[0], 2 * K, dz))
        J[:, 0::2, :] = JX.reshape(-1, K, dz)
        J[:, 1::2, :] = JY.reshape(-1, K, dz)
        return J

    @staticmethod
    def _solve_small(J, b):
        """Solve J y = b for stacked small square J (N, d, d); closed form for d <= 2."""
        d = J.shape[-1]
        if d == 1:
            return b / J[:, :, 0]
        if d == 2:
            a, bb, c, dd = J[:, 0, 0], J[:, 0, 1], J[:, 1, 0], J[:, 1, 1]
            det = a * dd - bb * c
            y0 = (dd * b[:, 0] - bb * b[:, 1]) / det
            y1 = (a * b[:, 1] - c * b[:, 0]) / det
            return np.stack([y0, y1], axis=1)
        return np.linalg.solve(J, b[..., None])[..., 0]

    def _hadamard(self, J):
        d = J.shape[-1]
        if d == 0:
            return np.ones(J.shape[0]), np.ones(J.shape[0])
        if d == 1:
            det = J[:, 0, 0]
        elif d == 2:
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        else:
            det = np.linalg.det(np.nan_to_num(J))
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.abs(det) / np.prod(np.sqrt(np.sum(J * J, axis=-2)), axis=-1)
        return np.nan_to_num(ratio, nan=0.0), np.sign(det)

    def coordinates(self, dq, z):
        """Reduced coordinates ``x = X_p dq + N z``, shape (N, nx)."""
        x = dq @ self.Xp.T
        if self.dz:
            x = x + z @ self.N.T
        return x

    def newton(self, dq, z, max_iter: int = 12):
        """Batched Newton on the selected closure rows; returns ``(z, x, converged)``."""
        if self.dz == 0:
            x = self.coordinates(dq, z)
            return z, x, np.ones(dq.shape[0], dtype=bool)
        tol = 1e-13 * self.L
        z = z.copy()
        sel = self.sel
        for _ in range(max_iter):
            x = self.coordinates(dq, z)
            c, s = self._trig(x)
            G = self._residual(x, c, s)
            with np.errstate(invalid="ignore"):
                if not np.any(np.abs(G[:, sel]) > tol):
                    break
            J = self._jz(x, c, s)[:, sel]
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                z = z - self._solve_small(J, G[:, sel])
        else:
            x = self.coordinates(dq, z)
            c, s = self._trig(x)
            G = self._residual(x, c, s)
        with np.errstate(invalid="ignore"):
            conv = np.all(np.abs(G) <= 1e-9 * self.L, axis=1)
        return z, x, conv

    def derivatives(self, x, qd, qdd):
        """Velocities ``xd`` and accelerations ``xdd`` of the reduced coordinates, and a dead-point mask.

        Parameters
        ----------
        x : ndarray (N, nx)
        qd, qdd : ndarray (N, W)
            Input velocities and accelerations.

        Notes
        -----
        ``J_z zd = -G_x X_p qd`` and ``J_z zdd = -(G_x X_p qdd + gamma(xd))``:
        the first and second time derivatives of the closure rows, linear in
        the unknown rates with the Jacobian of the position problem
        (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, 1988,
        eqs. 3.15 and 3.17).
        """
        xd = qd @ self.Xp.T
        xdd = qdd @ self.Xp.T
        Nn = x.shape[0]
        if self.dz == 0:
            return xd, xdd, np.zeros(Nn, dtype=bool), np.ones(Nn)
        c, s = self._trig(x)
        J = self._jz(x, c, s)[:, self.sel]
        ratio, sgn = self._hadamard(J)
        dead = ~(ratio > SINGULAR_TOL)
        Jg = np.where(dead[:, None, None], np.eye(self.dz), J)
        (_, _), (VX, VY), (AX, AY) = self.eval_forms(self.closure, x, c, s, xd, xdd)
        b = np.empty((Nn, 2 * VX.shape[1]))
        b[:, 0::2], b[:, 1::2] = VX, VY
        zd = self._solve_small(Jg, -b[:, self.sel])
        xd = xd + zd @ self.N.T
        (_, _), (_, _), (AX, AY) = self.eval_forms(self.closure, x, c, s, xd, xdd)
        b[:, 0::2], b[:, 1::2] = AX, AY
        zdd = self._solve_small(Jg, -b[:, self.sel])
        xdd = xdd + zdd @ self.N.T
        xd[dead] = np.nan
        xdd[dead] = np.nan
        return xd, xdd, dead, sgn

    # ------------------------------------------------------------- continuation
    def _walk(self, dq0, z0, target, h):
        """Sequential continuation from ``(dq0, z0)`` to the input ``target``; None if it cannot get there."""
        cur_dq, cur_z = dq0.copy(), z0.copy()
        step = h
        while True:
            delta = target - cur_dq
            dist = float(np.max(np.abs(delta / self.qscale)))
            if dist == 0.0:
                return cur_z
            t = min(step, dist) / dist
            x = self.coordinates(cur_dq[None], cur_z[None])
            xd, xdd, dead, _ = self.derivatives(x, delta[None], np.zeros((1, self.W)))
            if dead[0]:
                return None
            zd, zdd = xd[0] @ self.N, xdd[0] @ self.N  # N has orthonormal columns, orthogonal to X_p
            pred = cur_z + zd * t + 0.5 * zdd * t * t
            new_dq = target.copy() if t >= 1.0 else cur_dq + t * delta
            z, xn, conv = self.newton(new_dq[None], pred[None])
            ok = bool(conv[0])
            if ok:
                J = self._jz(xn, *self._trig(xn))[:, self.sel]
                ratio, sgn = self._hadamard(J)
                trust = 0.2 * t * (1.0 + float(np.max(np.abs(zd)))) + 1e-12
                ok = ratio[0] > SINGULAR_TOL and sgn[0] == self.sgn0 and float(np.max(np.abs(z[0] - pred))) <= trust
            if ok:
                cur_dq, cur_z = new_dq, z[0]
                step = min(2 * step, h)
            else:
                step /= 2
                if step < 1e-7:
                    return None

    def solve(self, q, qd, qdd):
        """Reduced coordinates and their rates over the input rows ``q`` (N, W); see :func:`solve`."""
        Nn = q.shape[0]
        dq = q - self.q0
        x = np.full((Nn, self.nx), np.nan)
        closed = np.zeros(Nn, dtype=bool)
        if self.dz == 0:
            x = self.coordinates(dq, np.zeros((Nn, 0)))
            closed[:] = True
        else:
            self._positions(dq, x, closed)
        xs = np.where(closed[:, None], x, 0.0)
        xd, xdd, dead, _ = self.derivatives(xs, qd, qdd)
        reason = np.full(Nn, "", dtype=object)
        reason[closed & dead] = REASON_DEAD
        reason[~closed] = REASON_UNREACHED
        xd[~closed] = np.nan
        xdd[~closed] = np.nan
        return x, xd, xdd, closed, reason

    def _positions(self, dq, x_out, closed):
        Nn, h = dq.shape[0], COARSE_STEP
        qs = dq / self.qscale
        step = np.concatenate([[np.max(np.abs(qs[0]))], np.max(np.abs(np.diff(qs, axis=0)), axis=1)])
        cum = np.cumsum(step)
        bins = np.floor(cum / h)
        starts = np.concatenate([[0], np.flatnonzero(np.diff(bins)) + 1])
        bid = np.concatenate([[0], np.cumsum(np.diff(bins) != 0)])
        nb = starts.size
        # sequential continuation through the coarse points
        cz = np.full((nb, self.dz), np.nan)
        cok = np.zeros(nb, dtype=bool)
        last_dq, last_z = np.zeros(self.W), np.zeros(self.dz)
        blocked = None  # (from, at) input values of a failed walk (one input only)
        for k, i in enumerate(starts):
            target = dq[i]
            if blocked is not None and self.W == 1:
                q_from, q_at = blocked
                if (target[0] - q_from) * (q_at - q_from) > 0 and abs(target[0] - q_from) >= abs(q_at - q_from):
                    continue
            z = self._walk(last_dq, last_z, target, h)
            if z is None:
                blocked = (last_dq[0], target[0])
                continue
            blocked = None
            cz[k], cok[k] = z, True
            last_dq, last_z = target.copy(), z
        # derivatives at the coarse points (per input direction)
        good = np.flatnonzero(cok)
        if good.size == 0:
            return
        cdq = dq[starts]
        xc = self.coordinates(cdq[good], cz[good])
        Zp = np.zeros((nb, self.dz, self.W))
        Zpp = np.zeros((nb, self.dz))
        for w in range(self.W):
            e = np.zeros((good.size, self.W))
            e[:, w] = 1.0
            xd, xdd, _, _ = self.derivatives(xc, e, np.zeros_like(e))
            Zp[good, :, w] = xd @ self.N
            if self.W == 1:
                Zpp[good] = xdd @ self.N
        # batched Newton on every point whose coarse point was reached
        ptsok = cok[bid]
        idx = np.flatnonzero(ptsok)
        b = bid[idx]
        d = dq[idx] - cdq[b]
        pred = cz[b] + np.einsum("ndw,nw->nd", Zp[b], d)
        if self.W == 1:
            h1 = d[:, 0]
            pred += 0.5 * Zpp[b] * (h1 * h1)[:, None]
            # cubic Hermite towards the next coarse point where both ends are known
            nxt = np.minimum(b + 1, nb - 1)
            span = cdq[nxt, 0] - cdq[b, 0]
            use = (nxt > b) & cok[nxt] & (np.abs(span / self.qscale[0]) > 1e-3)
            if np.any(use):
                u = np.flatnonzero(use)
                t = h1[u] / span[u]
                tt = t * t
                h00, h10, h01, h11 = 2 * tt * t - 3 * tt + 1, tt * t - 2 * tt + t, -2 * tt * t + 3 * tt, tt * t - tt
                pred[u] = (
                    h00[:, None] * cz[b[u]]
                    + (h10 * span[u])[:, None] * Zp[b[u], :, 0]
                    + h01[:, None] * cz[nxt[u]]
                    + (h11 * span[u])[:, None] * Zp[nxt[u], :, 0]
                )
        z, x, conv = self.newton(dq[idx], pred)
        J = self._jz(x, *self._trig(x))[:, self.sel]
        ratio, sgn = self._hadamard(J)
        trust = 0.2 * h * (1.0 + np.max(np.abs(Zp[b] * self.qscale), axis=(1, 2)))
        with np.errstate(invalid="ignore"):
            ok = conv & (sgn == self.sgn0) & (np.max(np.abs(z - pred), axis=1) <= trust)
        x_out[idx[ok]] = x[ok]
        closed[idx[ok]] = True
        # repair the points that failed: sequential continuation from the previous point that closed
        bad = idx[~ok]
        if bad.size == 0:
            return
        zfull = np.full((Nn, self.dz), np.nan)
        zfull[idx[ok]] = z[ok]
        skip_bin = -1
        for i in bad:
            if bid[i] == skip_bin:
                continue
            prev = i - 1
            while prev >= 0 and not closed[prev]:
                prev -= 1
            if prev >= 0 and bid[prev] == bid[i]:
                src_dq, src_z = dq[prev], zfull[prev]
            else:
                src_dq, src_z = cdq[bid[i]], cz[bid[i]]
            zi = self._walk(src_dq, src_z, dq[i], h)
            if zi is None:
                skip_bin = bid[i]
                continue
            zfull[i] = zi
            x_out[i] = self.coordinates(dq[i][None], zi[None])[0]
            closed[i] = True


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


def solve(system: KinematicSystem, q, qdot=None, qddot=None) -> MechanismResult:
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
        results are then the velocity and acceleration analogues).

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

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> r = solve(KinematicSystem(m), [0.0, np.pi / 2])
    >>> np.round(r.point["A"], 12).tolist()
    [[1.0, 0.0], [0.0, 1.0]]
    """
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
    qd = np.ones((N, W)) if qdot is None else _as_rows("qdot", qdot, N, W)
    qdd = np.zeros((N, W)) if qddot is None else _as_rows("qddot", qddot, N, W)
    x, xd, xdd, closed, reason = system.solve(qa, qd, qdd)
    return MechanismResult(qa, qd, qdd, x, xd, xdd, closed, reason, system)


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

    Dicts (computed when first asked for): :attr:`angle`, :attr:`omega`,
    :attr:`alpha` (link -> ``(N,)``), :attr:`point`, :attr:`velocity`,
    :attr:`acceleration` (point -> ``(N, 2)``), :attr:`displacement`,
    :attr:`slider_velocity`, :attr:`slider_acceleration` (slider -> ``(N,)``);
    arrays :attr:`pose`, :attr:`pose_velocity`, :attr:`pose_acceleration`
    (``(N, n, 3)``: ``x, y, theta`` of each moving link's frame, the columns
    of :func:`~gearlever.mechanism.constraints.constraint_jacobian`).
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

    @property
    def model(self) -> MechanismModel:
        return self.system.model

    def _links(self, arr, ground_value):
        m = self.model
        out = {}
        for k, link in m.links.items():
            if k == GROUND:
                out[k] = np.full(arr.shape[0], ground_value(link))
            else:
                out[k] = arr[:, self.system.idx[k]]
        return out

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
        ok = np.isfinite(self.x).all(axis=1)
        x = np.where(ok[:, None], self.x, 0.0)
        c, s = ks._trig(x)
        (X, Y), (VX, VY), (AX, AY) = ks.eval_forms(f, x, c, s, self.xdot, self.xddot)
        P = np.stack([X, Y], axis=-1)
        P[~ok] = np.nan
        return names, P, np.stack([VX, VY], axis=-1), np.stack([AX, AY], axis=-1)

    def _pdict(self, which):
        names, *arrs = self._point_kinematics
        a = arrs[which]
        return {p: a[:, i] for i, p in enumerate(names) if not p.startswith("\0")}

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
        return {s.name: arr[:, n + j] for j, s in enumerate(self.model.sliders)}

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
        a = arrs[which]
        m = self.model
        out = np.empty((a.shape[0], len(m.moving), 3))
        base = [self.x, self.xdot, self.xddot][which]
        for i, k in enumerate(m.moving):
            out[:, i, :2] = a[:, names.index("\0" + k)]
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

    def _frame_columns(self) -> dict:
        m = self.model
        u = m.units or "length"
        cols = {}
        for i, spec in enumerate(m.inputs):
            unit = u if spec.kind == "slider" else "rad"
            cols[f"q_{spec.label} [{unit}]"] = self.q[:, i]
        for k in m.moving:
            cols[f"{k} angle [rad]"] = self.angle[k]
            cols[f"{k} omega [rad/s]"] = self.omega[k]
            cols[f"{k} alpha [rad/s^2]"] = self.alpha[k]
        for sname in self.displacement:
            cols[f"{sname} s [{u}]"] = self.displacement[sname]
            cols[f"{sname} v [{u}/s]"] = self.slider_velocity[sname]
            cols[f"{sname} a [{u}/s^2]"] = self.slider_acceleration[sname]
        for p in m.points:
            for lab, d, unit in (
                ("", self.point, u),
                ("v", self.velocity, f"{u}/s"),
                ("a", self.acceleration, f"{u}/s^2"),
            ):
                cols[f"{p} {lab}x [{unit}]".replace("  ", " ")] = d[p][:, 0]
                cols[f"{p} {lab}y [{unit}]".replace("  ", " ")] = d[p][:, 1]
        cols["closed"] = self.closed
        cols["reason"] = self.reason
        return cols


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
