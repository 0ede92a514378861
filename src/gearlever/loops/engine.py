"""General planar vector loops: batched Newton positions, analogues by linear solves.

A *loop* is a list of planar vectors whose signed sum is zero.  Each vector has
a length and an angle; each of the two is either a fixed number, the input
(:class:`Input`, ``k * phi + offset``) or an unknown (:class:`Unknown`, a name
plus an optional constant offset).  Several loops may share unknowns.  A
:class:`LoopSystem` of ``m`` loops must have exactly ``2 m`` unknowns.

Everything is batched over an array of input values: the residual, the
analytic Jacobian and the linear solves are computed for all points at once
(``np.linalg.solve`` on stacked matrices).  Positions are found by Newton's
method seeded along the input (a second-order Taylor predictor from the last
converged point), so a branch chosen by the seed is kept; a point where the
loop cannot close, or where the Jacobian is singular (a dead point), comes out
as NaN with ``valid`` False (or raises if ``strict=True``).

Pure numpy; imports neither matplotlib nor pandas (nor scipy).
"""

from __future__ import annotations

import math  # noqa: F401  (used by the doctests)
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite, finite_array, positive
from gearlever.errors import ClosureError, GearleverError

__all__ = ["Input", "Unknown", "Vector", "LoopSystem", "LoopSolution", "INPUT"]


@dataclass(frozen=True)
class Input:
    """The input coordinate as a vector's length or angle: ``k * phi + offset``.

    Examples
    --------
    >>> from gearlever.loops import Input
    >>> Input(1, 0.5)          # angle = 1 * phi + 0.5
    Input(k=1, offset=0.5)
    """

    k: float = 1.0
    offset: float = 0.0


#: The input itself (``k=1``, no offset).
INPUT = Input()


@dataclass(frozen=True)
class Unknown:
    """An unknown of the loop system, as a vector's length or angle: ``scale * value + offset``.

    A ``scale`` other than 1 lets a loop carry a linear transmission constraint
    (a rack, a gear ratio, a lever arm), e.g. ``(rA + rB) * theta1``.

    Examples
    --------
    >>> from gearlever.loops import Unknown
    >>> Unknown("theta3", offset=0.0, scale=1.0).name
    'theta3'
    """

    name: str
    offset: float = 0.0
    scale: float = 1.0


def _spec(kind: str, value):
    """Normalize a spec to ('fixed', v) | ('input', k, off) | ('unknown', name, off, scale)."""
    if isinstance(value, Input):
        return ("input", finite(f"{kind} k", value.k), finite(f"{kind} offset", value.offset))
    if isinstance(value, Unknown):
        if not value.name:
            raise GearleverError(f"{kind} unknown must have a non-empty name")
        return (
            "unknown",
            value.name,
            finite(f"{kind} offset", value.offset),
            finite(f"{kind} scale", value.scale),
        )
    if isinstance(value, str):
        if value == "input":
            return ("input", 1.0, 0.0)
        if not value:
            raise GearleverError(f"{kind} unknown must have a non-empty name")
        return ("unknown", value, 0.0, 1.0)
    return ("fixed", finite(kind, value))


@dataclass(frozen=True)
class Vector:
    """One planar vector of a loop: ``sign * length * exp(i * angle)``.

    Parameters
    ----------
    name : str
        Label used in plans (e.g. ``"A"`` for the crank's tip, ``"BA"``).
    length, angle : float, str, Input or Unknown
        A number is fixed; ``"input"`` or :class:`Input` is the input
        coordinate; any other string or :class:`Unknown` is an unknown.
    sign : {+1, -1}
        Direction in which the vector is taken in the loop sum.

    Examples
    --------
    >>> from gearlever.loops import INPUT, Vector
    >>> Vector("crank", 5.0, INPUT).length
    5.0
    """

    name: str
    length: object
    angle: object
    sign: int = 1

    def __post_init__(self):
        if self.sign not in (1, -1):
            raise GearleverError(f"sign must be +1 or -1, got {self.sign!r}")
        _spec("length", self.length)
        _spec("angle", self.angle)


class LoopSystem:
    """A set of vector loops sharing unknowns, solved over arrays of input values.

    Parameters
    ----------
    loops : sequence of sequences of Vector
        Each inner sequence sums to zero: ``sum(sign * L * exp(i A)) = 0``.

    Notes
    -----
    For loop ``j`` the residual is the real and imaginary part of
    ``sum_k s_k L_k exp(i A_k)``.  Differentiating along the input ``phi``
    (Norton, *Design of Machinery*, ch. 4, 6 and 7, written for analogues)::

        sum s (L' + i L A') exp(iA) = 0                               (velocity)
        sum s (L'' + i L A'' + 2 i L' A' - L A'^2) exp(iA) = 0         (acceleration)

    Both are linear in the unknowns' analogues with the same matrix, the
    Jacobian ``J`` of the position residual, so ``J x' = -F_phi`` and
    ``J x'' = -c(x')`` (the input's own second analogue is zero).

    Examples
    --------
    A four-bar (ground 9, crank 5, coupler 8, rocker 8) as a loop:

    >>> sys4 = LoopSystem([[Vector("A", 5.0, "input"), Vector("BA", 8.0, "theta3"),
    ...                     Vector("B", 8.0, "theta4", -1), Vector("G", 9.0, 0.0, -1)]])
    >>> sys4.unknowns
    ('theta3', 'theta4')
    >>> sol = sys4.solve([1.0, 1.1], {"theta3": 0.5, "theta4": 1.5})
    >>> bool(sol.valid.all()), float(np.abs(sys4.residual([1.0, 1.1], sol.x)).max()) < 1e-12
    (True, True)
    """

    def __init__(self, loops: Sequence[Sequence[Vector]]):
        loops = [list(loop) for loop in loops]
        if not loops or any(len(loop) == 0 for loop in loops):
            raise GearleverError("loops must be a non-empty list of non-empty vector lists")
        names: list[str] = []
        specs = []
        for j, loop in enumerate(loops):
            for v in loop:
                if not isinstance(v, Vector):
                    raise GearleverError(f"loops must hold Vector objects, got {type(v).__name__}")
                ls, as_ = _spec("length", v.length), _spec("angle", v.angle)
                for s in (ls, as_):
                    if s[0] == "unknown" and s[1] not in names:
                        names.append(s[1])
                specs.append((j, v, ls, as_))
        if len(names) != 2 * len(loops):
            raise GearleverError(
                f"loops must have exactly 2 unknowns per loop ({2 * len(loops)}), got {len(names)}: {names}"
            )
        self.loops = tuple(tuple(loop) for loop in loops)
        self.unknowns = tuple(names)
        self._index = {n: i for i, n in enumerate(names)}
        self._specs = [(j, v.sign, self._compile(ls), self._compile(as_)) for j, v, ls, as_ in specs]
        self.vectors = tuple(v for _, v, _, _ in specs)
        fixed = [abs(ls[1]) for _, _, ls, _ in specs if ls[0] == "fixed"]
        self.scale = max(fixed) if fixed else 1.0
        self._tables()

    def _compile(self, s):
        if s[0] == "unknown":
            return ("unknown", self._index[s[1]], s[2], s[3])
        return s

    def _tables(self):
        """Per-vector coefficient arrays: value = c + k * phi + scale * x[idx]."""
        V, m, n = len(self._specs), len(self.loops), len(self.unknowns)
        inc = np.zeros((V, m))
        coef = {w: (np.zeros(V), np.zeros(V), np.zeros(V), np.zeros(V, dtype=int)) for w in "LA"}
        W = {w: np.zeros((V, m, n)) for w in "LA"}
        for v, (j, sign, ls, as_) in enumerate(self._specs):
            inc[v, j] = sign
            for w, spec in (("L", ls), ("A", as_)):
                c, k, sc, idx = coef[w]
                if spec[0] == "fixed":
                    c[v] = spec[1]
                elif spec[0] == "input":
                    k[v], c[v] = spec[1], spec[2]
                else:
                    idx[v], c[v], sc[v] = spec[1], spec[2], spec[3]
                    W[w][v, j, spec[1]] = sign * spec[3]
        self._inc, self._coef, self._W = inc, coef, W

    # ------------------------------------------------------------------ basics
    def _values(self, w, phi, x):
        c, k, sc, idx = self._coef[w]
        return c + k * phi[..., None] + sc * x[..., idx]

    def _rates(self, w, dx, d2x=None):
        c, k, sc, idx = self._coef[w]
        first = k + sc * dx[..., idx]
        return first if d2x is None else (first, sc * d2x[..., idx])

    @staticmethod
    def _split(zc):
        """Complex loop sums (..., m) -> real rows (..., 2m): re, im interleaved."""
        out = np.empty(zc.shape[:-1] + (2 * zc.shape[-1],))
        out[..., 0::2] = zc.real
        out[..., 1::2] = zc.imag
        return out

    def _LAE(self, phi, x):
        L, A = self._values("L", phi, x), self._values("A", phi, x)
        return L, A, np.cos(A) + 1j * np.sin(A)

    def residual(self, phi, x) -> np.ndarray:
        """Loop-closure residual, shape ``phi.shape + (2 m,)``.

        Parameters
        ----------
        phi : array_like
            Input values, any shape.
        x : array_like
            Unknowns, shape ``phi.shape + (n,)``, in :attr:`unknowns` order.

        Notes
        -----
        Rows ``2j, 2j+1``: real and imaginary part of ``sum_k s_k L_k e^{i A_k}``
        over the vectors of loop ``j`` (Norton, eq. 4.5, any number of vectors).

        Examples
        --------
        >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
        ...                  Vector("y", "y", math.pi / 2, -1)]])
        >>> np.allclose(s.residual([0.0], [[2.0, 0.0]]), 0.0, atol=1e-15)
        True
        """
        phi = np.asarray(phi, dtype=float)
        x = np.asarray(x, dtype=float)
        L, _, E = self._LAE(phi, x)
        return self._split((L * E) @ self._inc)

    def jacobian(self, phi, x) -> np.ndarray:
        """Analytic Jacobian dF/dx, shape ``phi.shape + (2 m, n)``.

        Notes
        -----
        For an unknown length ``L = scale x + offset``: column ``s scale e^{iA}``;
        for an unknown angle: ``s scale L i e^{iA}`` (real and imaginary rows),
        summed over every vector the unknown appears in.

        Examples
        --------
        >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
        ...                  Vector("y", "y", math.pi / 2, -1)]])
        >>> np.allclose(s.jacobian([0.0], [[2.0, 0.0]]), [[[-1.0, 0.0], [0.0, -1.0]]], atol=1e-15)
        True
        """
        phi = np.asarray(phi, dtype=float)
        x = np.asarray(x, dtype=float)
        L, _, E = self._LAE(phi, x)
        Jc = np.tensordot(E, self._W["L"], axes=([-1], [0])) + np.tensordot(1j * L * E, self._W["A"], axes=([-1], [0]))
        J = np.empty(Jc.shape[:-2] + (2 * Jc.shape[-2], Jc.shape[-1]))
        J[..., 0::2, :] = Jc.real
        J[..., 1::2, :] = Jc.imag
        return J

    def _input_column(self, phi, x):
        """dF/dphi at fixed unknowns."""
        L, _, E = self._LAE(phi, x)
        kL, kA = self._coef["L"][1], self._coef["A"][1]
        return self._split(((kL + 1j * L * kA) * E) @ self._inc)

    def vector_analogues(self, phi, x, dx, d2x):
        """Per vector: ``(L, A, L', A', L'', A'')`` arrays (analogues along the input).

        Notes
        -----
        ``L' = scale x_j'`` for an unknown, ``k`` for the input, 0 if fixed;
        second analogues likewise (the input's is 0).  Used by the plans.

        Examples
        --------
        >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
        ...                  Vector("y", "y", math.pi / 2, -1)]])
        >>> L, A, Lp, Ap, Lpp, App = s.vector_analogues(0.0, [2.0, 0.0], [0.0, 2.0], [-2.0, 0.0])[0]
        >>> float(L), float(Ap), float(App) + 0.0
        (2.0, 1.0, 0.0)
        """
        phi = np.asarray(phi, dtype=float)
        x, dx, d2x = (np.asarray(v, dtype=float) for v in (x, dx, d2x))
        L, A = self._values("L", phi, x), self._values("A", phi, x)
        (Lp, Lpp), (Ap, App) = self._rates("L", dx, d2x), self._rates("A", dx, d2x)
        return [tuple(arr[..., v] for arr in (L, A, Lp, Ap, Lpp, App)) for v in range(len(self._specs))]

    def _quadratic_column(self, phi, x, dx):
        """Velocity-product terms of the acceleration equation (everything but J x'')."""
        L, _, E = self._LAE(phi, x)
        Lp, Ap = self._rates("L", dx), self._rates("A", dx)
        return self._split(((-L * Ap * Ap + 2j * Lp * Ap) * E) @ self._inc)

    # --------------------------------------------------------------- analogues
    def _singular(self, J, tol: float) -> np.ndarray:
        """True where ``J`` is singular: Hadamard ratio ``|det J| / prod(column norms)`` below ``tol``.

        The ratio is 1 for orthogonal columns and 0 for dependent ones; for the
        four-bar it is ``|sin(theta3 - theta4)|``, the closed form's criterion.
        """
        Jf = np.nan_to_num(J, nan=0.0)
        with np.errstate(invalid="ignore"):
            bad = ~(np.abs(np.linalg.det(Jf)) > tol * np.prod(np.linalg.norm(Jf, axis=-2), axis=-1))
        return bad | ~np.all(np.isfinite(J), axis=(-2, -1))

    def analogues(self, phi, x, singular_tol: float = 1e-7):
        """Velocity and acceleration analogues of the unknowns at known positions.

        Parameters
        ----------
        phi : array_like
            Input values, any shape.
        x : array_like
            Unknowns, shape ``phi.shape + (n,)`` (NaN rows allowed).
        singular_tol : float
            Hadamard-ratio threshold for a dead point (see ``_singular``).

        Returns
        -------
        dx_dphi, d2x_dphi2 : ndarray
            Shape ``phi.shape + (n,)``; NaN where ``x`` is NaN or ``J`` singular.
        singular : ndarray of bool
            Where the Jacobian is singular (or ``x`` is NaN).

        Notes
        -----
        ``J x' = -dF/dphi`` and ``J x'' = -c(x')`` (see :class:`LoopSystem`),
        solved with ``np.linalg.solve`` on the stacked matrices.

        Examples
        --------
        >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
        ...                  Vector("y", "y", math.pi / 2, -1)]])
        >>> d1, d2, bad = s.analogues([0.0], [[2.0, 0.0]])
        >>> d1.round(12).tolist() == [[0.0, 2.0]], d2.round(12).tolist() == [[-2.0, 0.0]]
        (True, True)
        """
        phi = np.asarray(phi, dtype=float)
        x = np.asarray(x, dtype=float)
        n = len(self.unknowns)
        J = self.jacobian(phi, x)
        bad = self._singular(J, singular_tol) | ~np.all(np.isfinite(x), axis=-1)
        Jg = np.where(bad[..., None, None], np.eye(n), J)
        xs = np.where(bad[..., None], 0.0, x)
        b = self._input_column(phi, xs)
        dx = np.linalg.solve(Jg, -b[..., None])[..., 0]
        c = self._quadratic_column(phi, xs, dx)
        d2x = np.linalg.solve(Jg, -c[..., None])[..., 0]
        dx[bad] = np.nan
        d2x[bad] = np.nan
        return dx, d2x, bad

    # ----------------------------------------------------------------- Newton
    def _newton(self, phi, x, max_iter=30):
        """Batched Newton from ``x``; returns (x, converged)."""
        n = len(self.unknowns)
        tol = 1e-13 * self.scale
        x = x.copy()
        conv = np.zeros(phi.shape, dtype=bool)
        for _ in range(max_iter):
            F = self.residual(phi, x)
            J = self.jacobian(phi, x)
            bad = self._singular(J, 1e-14) | ~np.all(np.isfinite(F), axis=-1)
            Jg = np.where(bad[..., None, None], np.eye(n), J)
            dx = np.linalg.solve(Jg, -np.where(bad[..., None], 0.0, F)[..., None])[..., 0]
            x = np.where(bad[..., None], np.nan, x + dx)
            small = np.max(np.abs(dx), axis=-1) <= 1e-14 * (1.0 + np.max(np.abs(x), axis=-1))
            if np.all(small | bad):
                break
        F = self.residual(phi, x)
        with np.errstate(invalid="ignore"):
            conv = np.max(np.abs(F), axis=-1) <= 1e3 * tol
        conv &= np.all(np.isfinite(x), axis=-1)
        return x, conv

    def solve(
        self,
        phi,
        guess: Mapping[str, float],
        *,
        strict: bool = False,
        max_step: float = 0.1,
        singular_tol: float = 1e-7,
    ) -> LoopSolution:
        """Positions and analogues of the unknowns over an array of input values.

        Parameters
        ----------
        phi : array_like
            Input values in path order (any shape; traversed in C order).
        guess : mapping
            Approximate value of every unknown at the first point; it chooses
            the branch, which is then followed along the input.
        strict : bool
            Raise :class:`~gearlever.errors.ClosureError` instead of returning
            NaN where the loop does not close or is at a dead point.
        max_step : float
            Largest input step taken by the predictor (> 0); larger gaps are
            sub-stepped, and no sub-step is longer either.
        singular_tol : float
            Hadamard-ratio threshold for a dead point (see ``_singular``).

        Returns
        -------
        LoopSolution

        Raises
        ------
        ClosureError
            With ``strict=True``, naming the first input value where the loop
            cannot close or is at a dead point and how many points fail.

        Notes
        -----
        Continuation: from the last converged point ``(phi0, x0, x0', x0'')``
        the next block of points is seeded with ``x0 + x0' h + x0'' h^2 / 2``
        (``h = phi - phi0``) and refined by batched Newton with the analytic
        Jacobian.  A point whose Newton result moves farther from its seed than
        the predictor could explain, or where ``det J`` has changed sign (the
        other branch: the sign is constant along a branch between dead
        points), or that does not converge, is retried with smaller steps and
        finally marked invalid; points beyond it in the same direction are
        marked invalid without retrying.

        Examples
        --------
        >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
        ...                  Vector("y", "y", math.pi / 2, -1)]])
        >>> sol = s.solve(np.linspace(0, 1, 5), {"x": 2.0, "y": 0.0})
        >>> np.allclose(sol["x"], 2 * np.cos(np.linspace(0, 1, 5)))
        True
        """
        phi_in = finite_array("phi", phi)
        if phi_in.size == 0:
            raise GearleverError("phi must hold at least one value, got an empty array")
        missing = [n for n in self.unknowns if n not in guess]
        if missing:
            raise GearleverError(f"guess must give every unknown, missing {missing}")
        seed = np.array([finite(f"guess[{n!r}]", guess[n]) for n in self.unknowns])
        max_step = positive("max_step", max_step)
        p = phi_in.reshape(-1)
        N, n = p.size, len(self.unknowns)
        X = np.full((N, n), np.nan)
        ok = np.zeros(N, dtype=bool)

        state = None  # (phi0, x0, d1, d2)
        sgn0 = 0.0  # sign of det J on the seeded branch
        blocked = None  # input value beyond which continuation failed
        i = 0
        block = 16
        while i < N:
            if state is None:
                x1, c1 = self._newton(p[i : i + 1], seed[None, :])
                if c1[0]:
                    d1, d2, bad = self.analogues(p[i : i + 1], x1, singular_tol)
                    X[i] = x1[0]
                    if not bad[0]:
                        ok[i] = True
                        state = (p[i], x1[0], d1[0], d2[0])
                        sgn0 = self._det_sign(p[i : i + 1], x1)[0]
                i += 1
                continue
            phi0, x0, d10, d20 = state
            if blocked is not None and (p[i] - phi0) * (blocked - phi0) > 0 and abs(p[i] - phi0) >= abs(blocked - phi0):
                i += 1
                continue
            # largest prefix within max_step of phi0
            hs = p[i : i + block] - phi0
            within = np.abs(hs) <= max_step
            m = int(np.argmin(within)) if not within.all() else within.size
            if m == 0:
                got = self._substep(phi0, x0, d10, d20, p[i], max_step, max_step, singular_tol, sgn0)
                if got is None:
                    blocked = p[i]
                else:
                    X[i], ok[i] = got[1], True
                    state = got
                    blocked = None
                i += 1
                continue
            idx = slice(i, i + m)
            h = hs[:m, None]
            pred = x0 + d10 * h + 0.5 * d20 * h * h
            xs, conv = self._newton(p[idx], pred)
            d1, d2, bad = self.analogues(p[idx], xs, singular_tol)
            trust = 0.1 * max_step * (1.0 + np.abs(d10).max())
            with np.errstate(invalid="ignore"):
                near = np.max(np.abs(xs - pred), axis=-1) <= trust
            # same branch: det J keeps its sign between dead points
            good = conv & ~bad & near & (self._det_sign(p[idx], xs) == sgn0)
            k = int(np.argmin(good)) if not good.all() else m
            if k > 0:
                X[i : i + k], ok[i : i + k] = xs[:k], True
                state = (p[i + k - 1], xs[k - 1], d1[k - 1], d2[k - 1])
                blocked = None
                i += k
                block = min(2 * block, 4096) if k == m else max(k, 1)
            else:
                block = 1
                got = self._substep(phi0, x0, d10, d20, p[i], max_step / 4, max_step, singular_tol, sgn0)
                if got is None:
                    blocked = p[i]
                else:
                    X[i], ok[i] = got[1], True
                    state = got
                i += 1

        Xr = X.reshape(phi_in.shape + (n,))
        okr = ok.reshape(phi_in.shape)
        dx, d2x, bad = self.analogues(phi_in, np.where(okr[..., None], Xr, np.nan), singular_tol)
        closed = okr.copy()
        valid = okr & ~bad
        Xr = np.where(closed[..., None], Xr, np.nan)
        if strict and not valid.all():
            first = int(np.flatnonzero(~valid.reshape(-1))[0])
            raise ClosureError(
                f"phi: the loop does not close or is at a dead point at phi = {p[first]!r} "
                f"({int((~valid).sum())} of {valid.size} points)"
            )
        return LoopSolution(self.unknowns, phi_in, Xr, dx, d2x, valid, closed)

    def _det_sign(self, phi, x):
        with np.errstate(invalid="ignore"):
            return np.sign(np.linalg.det(np.nan_to_num(self.jacobian(phi, x), nan=0.0)))

    def _substep(self, phi0, x0, d10, d20, target, step, max_step, singular_tol, sgn0, min_step=1e-7):
        """Walk from phi0 to target, first in steps of ``step``, never more than ``max_step``; None if it fails.

        A step that succeeds doubles the next one up to ``max_step`` (the
        caller's :meth:`solve` argument); a step that fails halves it.
        """
        cur = (phi0, x0, d10, d20)
        while True:
            phi_c, x_c, d1_c, d2_c = cur
            if phi_c == target:
                return cur
            h = float(np.clip(target - phi_c, -step, step))
            pt = np.array([phi_c + h])
            pred = (x_c + d1_c * h + 0.5 * d2_c * h * h)[None, :]
            xs, conv = self._newton(pt, pred)
            ok = bool(conv[0])
            if ok:
                d1, d2, bad = self.analogues(pt, xs, singular_tol)
                trust = 0.1 * abs(h) * (1.0 + np.abs(d1_c).max()) + 1e-12
                ok = (not bad[0]) and np.max(np.abs(xs[0] - pred[0])) <= trust and self._det_sign(pt, xs)[0] == sgn0
            if ok:
                cur = (
                    pt[0] if pt[0] != target and abs(target - pt[0]) > 1e-15 else target,
                    xs[0],
                    d1[0],
                    d2[0],
                )
                step = min(step * 2, max_step)
            else:
                step /= 2
                if step < min_step:
                    return None


@dataclass(frozen=True)
class LoopSolution(Result):
    """Positions and analogues of a loop system's unknowns over the input values.

    Attributes
    ----------
    names : tuple of str
        Unknown names, in the order of the last axis.
    phi : ndarray
        The input values.
    x, dx_dphi, d2x_dphi2 : ndarray
        Shape ``phi.shape + (n,)``; NaN where invalid.
    valid : ndarray of bool
        The loop closes and the Jacobian is regular (analogues finite).
    closed : ndarray of bool
        The loop closes (positions finite; analogues may be NaN at a dead point).

    Examples
    --------
    >>> s = LoopSystem([[Vector("P", 2.0, "input"), Vector("x", "x", 0.0, -1),
    ...                  Vector("y", "y", math.pi / 2, -1)]])
    >>> sol = s.solve([0.0], {"x": 1.9, "y": 0.1})
    >>> float(sol["x"][0]), float(sol.d1("y")[0]), float(sol.d2("x")[0])
    (2.0, 2.0, -2.0)
    """

    names: tuple
    phi: np.ndarray
    x: np.ndarray
    dx_dphi: np.ndarray
    d2x_dphi2: np.ndarray
    valid: np.ndarray
    closed: np.ndarray

    def _i(self, name):
        try:
            return self.names.index(name)
        except ValueError:
            raise GearleverError(f"name must be one of {self.names}, got {name!r}") from None

    def __getitem__(self, name) -> np.ndarray:
        """Position array of unknown ``name``."""
        return self.x[..., self._i(name)]

    def d1(self, name) -> np.ndarray:
        """Velocity analogue of unknown ``name``."""
        return self.dx_dphi[..., self._i(name)]

    def d2(self, name) -> np.ndarray:
        """Acceleration analogue of unknown ``name``."""
        return self.d2x_dphi2[..., self._i(name)]

    def _frame_columns(self) -> dict:
        """One row per input value: ``phi``, then each unknown, ``d<name>_dphi``, ``d2<name>_dphi2``."""
        cols = {"phi": np.ravel(self.phi)}
        for name in self.names:
            cols[name] = np.ravel(self[name])
            cols[f"d{name}_dphi"] = np.ravel(self.d1(name))
            cols[f"d2{name}_dphi2"] = np.ravel(self.d2(name))
        cols["valid"], cols["closed"] = np.ravel(self.valid), np.ravel(self.closed)
        return cols
