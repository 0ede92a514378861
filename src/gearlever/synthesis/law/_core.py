"""The common core of law synthesis: the sampled target, the kind interface and registry, objective and polish.

A *kind* (one module each: :mod:`~gearlever.synthesis.law.fourbar`, ...)
is a :class:`LawKind`, added by :func:`register` to the one registry of
synthesis kinds (:mod:`gearlever.synthesis.registry`, family ``law``, its
class the record's ``spec``; :data:`KINDS` is a read-only view of it): a box of design variables, the achieved output of
``n`` candidates at ``N`` law inputs at once in closed form
(:meth:`LawKind.generate`, complex-safe so that the polish differentiates it
by the complex step), its exact constraints and its model writer.
:class:`LawProblem` turns a kind and a :class:`LawTarget` into the batched
objective of the global search and the minimax polish.

Pure numpy and scipy.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis import registry

__all__ = [
    "KINDS",
    "MIN_BUDGET",
    "LawKind",
    "LawProblem",
    "LawTarget",
    "atan2c",
    "law_target",
    "register",
    "SAMPLES",
    "DWELL_WEIGHT",
]

#: Law inputs sampled over one turn by the search and the polish.
SAMPLES = 360
#: Weight of the dwell samples in the objective: 4 asks for a dwell four times as tight as the rest
#: (the benchmark's 0.25 deg over the dwell against 1 deg over the cycle).
DWELL_WEIGHT = 4.0
#: The dwell excursion is held to this fraction of ``dwell_tolerance`` over the search samples, so that the
#: result measured at ten times as many inputs stays within it.
DWELL_MARGIN = 0.99
#: Weight of the dwell excursion's excess in the search's objective (the bound as a penalty, then exact), and
#: the fraction of the bound above which the search's penalty starts (a search ends near, not on, its optimum).
DWELL_PENALTY = 10.0
SEARCH_MARGIN = 0.9
#: Complex step of the derivatives (Squire and Trapp 1998): exact to rounding for any step this small.
_H = 1e-30

#: Smallest budget of a law synthesis (per kind).
MIN_BUDGET = 100

#: Dwell, cycloidal rise of 45 deg, 3-4-5 return (a law with a dwell; the angle kinds' tiny problem).
DWELL = (
    {"to": 120, "motion": "dwell"},
    {"to": 240, "motion": "cycloidal", "rise": 45},
    {"to": 360, "motion": "345", "rise": -45},
)
#: A harmonic lift of 40 and its return (the displacement kinds' tiny problem).
LIFT = ({"to": 180, "motion": "harmonic", "rise": 40}, {"to": 360, "motion": "harmonic", "rise": -40})


class _LawKinds(Mapping):
    """Read-only view of the law kinds of the one registry: name -> :class:`LawKind` subclass, in order.

    Not a second registry: every lookup reads :func:`gearlever.synthesis.registry.kinds` (family ``law``),
    so a kind registered there is seen here.
    """

    def _map(self) -> dict:
        return {k.name: k.spec for k in registry.kinds("law")}

    def __getitem__(self, name):
        return self._map()[name]

    def __iter__(self):
        return iter(self._map())

    def __len__(self):
        return len(self._map())

    def __repr__(self):
        return f"KINDS({', '.join(self._map())})"


#: The law kinds of the one registry (a view): kind name -> :class:`LawKind` subclass, in the order of ``auto``.
KINDS = _LawKinds()


def kind_class(name: str):
    """The :class:`LawKind` subclass of law kind ``name``, or the registry's refusal naming the kinds.

    Examples
    --------
    >>> kind_class("slotted-lever").__name__, kind_class("slotted-lever").outputs
    ('SlottedLeverLaw', ('angle', 'displacement'))
    """
    return registry.get("law", name).spec


def register(cls):
    """Class decorator: add a :class:`LawKind` subclass to the one registry (family ``law``, name ``cls.name``).

    The record's description is the first line of the class docstring, its order ``cls.order`` (that of
    ``auto``), its tiny problem ``cls.example`` (see :func:`example`), its spec the class.
    """
    registry.register(
        registry.Kind(
            "law",
            cls.name,
            ((cls.__doc__ or "").strip().splitlines() or [cls.name])[0].replace(" (see the module docstring)", ""),
            "gearlever.synthesis.law.driver:synthesize_law",
            polish_counted=True,
            min_budget=MIN_BUDGET,
            order=cls.order,
            example=example(cls.name, cls.example),
            spec=cls,
        )
    )
    return cls


def _sine(power: int = 1, **kwargs) -> tuple:
    """A 20 deg sine of the input (to ``power``) sampled at 72 inputs, and the keyword arguments."""
    th = np.linspace(0.0, 2 * math.pi, 72, endpoint=False)
    return (law_target(th, math.radians(20) * np.sin(th) ** power),), dict(kwargs)


class example:  # noqa: N801 (a picklable callable named as the function it stands for)
    """The tiny problem of a law kind: ``example()`` gives ``(args, kwargs)`` of ``synthesize_law``.

    ``spec`` is the kind's ``example`` attribute: None (a 20 deg sine of the input, 72 samples), a dict
    ``{"output", "units", "segments"}`` (a segment law) or ``{"power": p, "kwargs": {...}}``.

    >>> args, kwargs = example("gear-lever", {"power": 2, "kwargs": {"teeth": (20, 40)}})()
    >>> args[0].theta.size, kwargs
    (72, {'teeth': (20, 40)})
    """

    def __init__(self, name: str, spec=None):
        self.name, self.spec = name, spec

    def __call__(self) -> tuple:
        spec = self.spec or {}
        if "segments" in spec:
            from gearlever.laws import law_from_segments

            segments = [dict(g) for g in spec["segments"]]
            return (law_from_segments(spec["output"], spec["units"], segments),), dict(spec.get("kwargs", {}))
        return _sine(spec.get("power", 1), **spec.get("kwargs", {}))


def atan2c(y, x):
    """``arctan2(y, x)`` that carries a complex step: the real angle plus ``i`` times its first-order change.

    Notes
    -----
    ``d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)``; with the step ``i h`` the
    imaginary parts are ``h`` times the derivatives (J. R. R. A. Martins,
    P. Sturdza and J. J. Alonso, "The complex-step derivative approximation",
    ACM TOMS 29 (2003) 245-262).

    Examples
    --------
    >>> z = atan2c(np.array([1.0 + 1e-30j]), np.array([1.0 + 0j]))
    >>> round(float(z.real[0]), 6), round(float(z.imag[0] / 1e-30), 6)
    (0.785398, 0.5)
    """
    if np.iscomplexobj(y) or np.iscomplexobj(x):
        yr, xr = np.real(y), np.real(x)
        return np.arctan2(yr, xr) + 1j * (xr * np.imag(y) - yr * np.imag(x)) / (xr * xr + yr * yr)
    return np.arctan2(y, x)


@dataclass(frozen=True)
class LawTarget:
    """A wanted law sampled over one turn of the input.

    Attributes
    ----------
    theta : ndarray (N,)
        Law inputs, radians, ``0 <= theta < 2 pi``, increasing.
    s, v, a : ndarray (N,)
        Wanted output (radians for an angle law, length otherwise) and its
        first and second derivatives per radian of input.
    output : {"angle", "displacement"}
    units : str
    segment : ndarray (N,) of int
        Segment of each sample (all 0 for a sampled law).
    breaks : ndarray (K + 1,)
        Segment boundaries, radians.
    motions : tuple of str
        Motion of each segment (``"samples"`` for a sampled law).
    weight : ndarray (N,)
        Weight of each sample in the objective (:data:`DWELL_WEIGHT` in dwells, else 1).
    net : float
        Output change over one turn (0 for a returning law).

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    >>> t = law_target(th, 0.3 * np.sin(th))
    >>> t.s.shape, float(t.net), t.output
    ((36,), 0.0, 'angle')
    """

    theta: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    output: str
    units: str
    segment: np.ndarray
    breaks: np.ndarray
    motions: tuple
    weight: np.ndarray
    net: float

    @property
    def scale(self) -> float:
        """Size of the output: its range over the cycle with the net change removed (at least 1e-12)."""
        drift = self.s - self.net * self.theta / (2 * math.pi)
        return float(max(np.ptp(drift), 1e-12))

    @property
    def dwell(self) -> np.ndarray:
        """Samples in a dwell segment."""
        return np.array([self.motions[k] == "dwell" for k in self.segment], dtype=bool)


def law_target(
    theta,
    s,
    v=None,
    a=None,
    *,
    output: str = "angle",
    units: str = "deg",
    breaks=None,
    motions=None,
    net: float = 0.0,
    dwell_weight: float = DWELL_WEIGHT,
) -> LawTarget:
    """A :class:`LawTarget` from plain arrays (the law's samples over one turn).

    Parameters
    ----------
    theta : array_like (N,)
        Inputs, radians in ``[0, 2 pi)``, increasing.
    s : array_like (N,)
        Wanted outputs.
    v, a : array_like (N,), optional
        Wanted analogues (default: periodic finite differences of ``s`` with the net change removed).
    output, units : str
    breaks, motions : optional
        Segment boundaries (radians, from 0 to 2 pi) and their motion names.
    net : float
        Output change over one turn.
    dwell_weight : float
        Weight of dwell samples.

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> t = law_target(th, np.sin(th))
    >>> t.theta.size, t.motions, round(t.scale, 6)
    (8, ('samples',), 2.0)
    """
    th = np.asarray(theta, dtype=float).reshape(-1)
    s = np.asarray(s, dtype=float).reshape(-1)
    if th.size < 8 or th.shape != s.shape:
        raise GearleverError(f"theta and s must be arrays of the same length >= 8, got {th.size} and {s.size}")
    if not (np.all(np.isfinite(th)) and np.all(np.isfinite(s))):
        raise GearleverError("theta and s must be finite")
    if th[0] < 0 or th[-1] >= 2 * math.pi or np.any(np.diff(th) <= 0):
        raise GearleverError("theta must increase within [0, 2 pi)")
    if output not in ("angle", "displacement"):
        raise GearleverError(f"output must be 'angle' or 'displacement', got {output!r}")
    if not (math.isfinite(dwell_weight) and dwell_weight > 0):
        raise GearleverError(f"dwell_weight must be positive, got {dwell_weight!r}")
    net = float(net)
    if v is None or a is None:
        drift = s - net * th / (2 * math.pi)
        h = np.diff(np.concatenate([th, [th[0] + 2 * math.pi]]))
        g = np.diff(np.concatenate([drift, [drift[0]]])) / h
        v = net / (2 * math.pi) + 0.5 * (g + np.roll(g, 1)) if v is None else v
        a = (g - np.roll(g, 1)) / (0.5 * (h + np.roll(h, 1))) if a is None else a
    if breaks is None:
        breaks, motions, seg = np.array([0.0, 2 * math.pi]), ("samples",), np.zeros(th.size, dtype=int)
    else:
        breaks = np.asarray(breaks, dtype=float)
        motions = tuple(motions)
        seg = np.clip(np.searchsorted(breaks, th, side="right") - 1, 0, len(motions) - 1)
    w = np.where(np.array([motions[k] == "dwell" for k in seg], dtype=bool), float(dwell_weight), 1.0)
    return LawTarget(
        th, s, np.asarray(v, dtype=float), np.asarray(a, dtype=float), output, units, seg, breaks, motions, w, net
    )


class LawKind:
    """A mechanism kind of law synthesis (subclass per kind, one module each, added by :func:`register`).

    Subclasses set :attr:`name`, :attr:`outputs` (the law outputs the kind
    can give), :attr:`names` of the design variables and the box
    ``lo, hi`` (from the target in ``__init__``), :attr:`fixed` (names held
    in the polish: branch signs, teeth), and implement :meth:`generate`,
    :meth:`transmission` and :meth:`model`.

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    >>> kind = kind_class("fourbar")(law_target(th, 0.3 * np.sin(th)))
    >>> kind.name, kind.d, kind.outputs
    ('fourbar', 5, ('angle',))
    """

    name = ""
    outputs: tuple = ("angle",)
    names: tuple = ()
    fixed: tuple = ()
    #: Place among the law kinds (that of ``auto``, smallest first).
    order: float = math.inf
    #: The kind's tiny problem (see :class:`example`): None, a segment law or a sine's power.
    example = None

    def __init__(self, target: LawTarget, teeth=(17, 120)):
        self.target = target
        self.teeth = (int(teeth[0]), int(teeth[1]))
        self.lo = np.zeros(len(self.names))
        self.hi = np.ones(len(self.names))

    @property
    def d(self) -> int:
        return len(self.names)

    def check(self) -> None:
        """Refuse a target this kind cannot give (:class:`GearleverError`)."""
        t = self.target
        if t.output not in self.outputs:
            raise GearleverError(f"a {self.name} gives an output {' or '.join(self.outputs)}, the law is {t.output}")
        if abs(t.net) > 1e-9 * max(t.scale, 1.0):
            raise GearleverError(
                f"the law's output changes by {t.net:.6g} over a cycle; a {self.name} returns to its start every "
                "turn (only a geared-fourbar's output gear turns on)"
            )

    def sample(self, rng, m: int) -> np.ndarray:
        """``m`` candidates of the initial population (uniform in the box by default)."""
        return self.lo + rng.random((m, self.d)) * (self.hi - self.lo)

    def search_box(self):
        """Box ``(lo, hi)`` of the global search's variables (by default the design variables)."""
        return self.lo, self.hi

    def to_full(self, Zs) -> np.ndarray:
        """Design variables ``(n, d)`` of search candidates ``Zs`` (by default the same; NaN rows: none)."""
        return Zs

    def search_sample(self, rng, m: int) -> np.ndarray:
        """``m`` candidates of the search's initial population."""
        return self.sample(rng, m)

    def generate(self, Z, theta):
        """Outputs ``(n, N)`` at law inputs ``theta`` (up to a constant) and feasibility ``(n,)``."""
        raise NotImplementedError

    def transmission(self, Z):
        """Smallest and largest transmission angle over the turn ``(n,), (n,)`` (radians)."""
        raise NotImplementedError

    def evaluate(self, Z, theta):
        """:meth:`generate` and :meth:`transmission` at once (a kind may share the work): ``G, ok, mn, mx``."""
        G, ok = self.generate(Z, theta)
        mn, mx = self.transmission(Z)
        return G, ok, mn, mx

    def model(self, z, k: float) -> dict:
        """Model dict sketched at law input 0 (``k``: the output zero of the fit)."""
        raise NotImplementedError

    def details(self, z) -> dict:
        """Lengths, teeth, branch ... of a design, for the report."""
        return {n: float(v) for n, v in zip(self.names, z)}


class LawProblem:
    """Objective and polish of one kind against one target (the spec is plain data, sent to dask workers).

    The objective of the global search is the weighted RMS of
    ``generate(z) + k - s`` with the output zero ``k`` solved in closed form
    (the weighted mean); the polish minimizes the weighted *maximum* error by
    Lawson's iteratively reweighted least squares with ``k`` a variable and
    the Jacobian by the complex step.  Infeasible candidates are ``inf``.

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    >>> pb = LawProblem("fourbar", law_target(th, 0.3 * np.sin(th)))
    >>> pb.d, pb.kind.names[:3]
    (5, ('b', 'c', 'u2'))
    """

    def __init__(
        self,
        kind: str,
        target: LawTarget,
        min_transmission: float = 0.0,
        teeth=(17, 120),
        dwell_tolerance: float | None = None,
    ):
        self.kind = kind_class(kind)(target, teeth)
        self.target = target
        self.min_transmission = float(min_transmission)
        self.evaluations = 0
        #: Evaluations after which the polish stops (None: no cap); set by the driver to hold the budget.
        self.cap: int | None = None
        self.dwell_tolerance = None if dwell_tolerance is None else float(dwell_tolerance)
        #: Sample indices of each dwell segment (the excursion is measured over each).
        self.dwells = [np.flatnonzero(target.segment == k) for k, m in enumerate(target.motions) if m == "dwell"]
        self.dwells = [idx for idx in self.dwells if idx.size > 1]
        if self.dwell_tolerance is not None:
            if not (math.isfinite(self.dwell_tolerance) and self.dwell_tolerance > 0):
                raise GearleverError(f"dwell_tolerance must be a positive number, got {dwell_tolerance!r}")
            if not self.dwells:
                raise GearleverError("dwell_tolerance bounds the output's excursion over a dwell: the law has no dwell")

    def excursion(self, G) -> np.ndarray:
        """Largest excursion (peak to peak) of outputs ``G (n, N)`` over a dwell segment ``(n,)`` (0: no dwell)."""
        G = np.real(G)
        out = np.zeros(G.shape[0])
        with np.errstate(invalid="ignore"):
            for idx in self.dwells:
                out = np.maximum(out, np.ptp(G[:, idx], axis=1))
        return out

    def violation(self, G, margin: float = DWELL_MARGIN) -> np.ndarray:
        """How far the dwell excursion of ``G`` exceeds ``margin`` times :attr:`dwell_tolerance` (0: within)."""
        if self.dwell_tolerance is None:
            return np.zeros(np.shape(G)[0])
        return np.maximum(self.excursion(G) - margin * self.dwell_tolerance, 0.0)

    @property
    def d(self):
        return self.kind.d

    @property
    def lo(self):
        return self.kind.lo

    @property
    def hi(self):
        return self.kind.hi

    def feasible(self, Z, mn=None, mx=None) -> np.ndarray:
        Z = np.atleast_2d(Z)
        if mn is None:
            self.evaluations += Z.shape[0]
            mn, mx = self.kind.transmission(Z)
        b = self.min_transmission
        with np.errstate(invalid="ignore"):
            return np.isfinite(mn) & (mn >= b - 1e-12) & (mx <= math.pi - b + 1e-12)

    def residuals(self, Z):
        """Unweighted ``generate - s`` (n, N) with the weighted-mean zero, and feasibility."""
        t = self.target
        Z = np.atleast_2d(Z)
        self.evaluations += Z.shape[0]
        G, ok = self.kind.generate(Z, t.theta)
        R = G - t.s
        w2 = t.weight**2
        k = -(R @ w2) / w2.sum()
        return R + k[:, None], k, ok & (self.violation(G) == 0)

    def objective(self, Z) -> np.ndarray:
        Z = np.atleast_2d(Z)
        self.evaluations += Z.shape[0]
        t = self.target
        G, ok, mn, mx = self.kind.evaluate(Z, t.theta)
        w2 = t.weight**2
        with np.errstate(invalid="ignore"):
            R = G - t.s
            R = R - (R @ w2)[:, None] / w2.sum()
            F = np.sqrt((R * R) @ w2 / t.theta.size) + DWELL_PENALTY * self.violation(G, SEARCH_MARGIN)
        ok = ok & self.feasible(Z, mn, mx) & np.isfinite(F)
        return np.where(ok, F, np.inf)

    def sample(self, rng, m):
        return self.kind.sample(rng, m)

    def search_objective(self, Zs) -> np.ndarray:
        """:meth:`objective` of search candidates (mapped by the kind's ``to_full``)."""
        Z = self.kind.to_full(np.atleast_2d(Zs))
        F = self.objective(np.nan_to_num(Z, nan=0.0))
        return np.where(np.all(np.isfinite(Z), axis=1), F, np.inf)

    # --- polish -----------------------------------------------------------------------------------------
    def _free(self):
        return np.array([n not in self.kind.fixed for n in self.kind.names], dtype=bool)

    def weighted_max(self, z, k) -> float:
        """Weighted maximum error of design ``z`` with output zero ``k``; ``inf`` if it breaks a constraint."""
        self.evaluations += 1
        G, ok = self.kind.generate(z[None, :], self.target.theta)
        if not ok[0] or self.violation(G)[0] > 0:
            return math.inf
        return float(np.max(np.abs(G[0] + k - self.target.s) * self.target.weight))

    def jacobian(self, z):
        """``d generate / d z`` (N, d) by the complex step (exact to rounding); ``z`` real (d,).

        Counts ``d`` evaluations (one complex candidate per variable).
        """
        d = z.size
        self.evaluations += d
        Zc = np.tile(z.astype(complex), (d, 1)) + 1j * _H * np.eye(d)
        G, _ = self.kind.generate(Zc, self.target.theta)
        return (np.imag(G) / _H).T

    def remaining(self) -> float:
        """Evaluations left before :attr:`cap` (``inf`` without a cap)."""
        return math.inf if self.cap is None else self.cap - self.evaluations

    def polish(self, z, rounds: int = 25):
        """Minimax polish from ``z``: returns ``(z, k, weighted max error)``.

        Notes
        -----
        Lawson's algorithm (C. L. Lawson, "Contributions to the theory of
        linear least maximum approximation", PhD thesis, UCLA, 1961; as
        iteratively reweighted least squares, Rice and Usow, Math. Comp. 22
        (1968) 118-127): each round solves a weighted least-squares problem
        (:func:`scipy.optimize.least_squares`, trust region in the box, the
        complex-step Jacobian) and multiplies each sample's weight by its
        error, which drives the weighted RMS towards the weighted maximum.
        A step that breaks a constraint (the transmission angle, the dwell
        excursion's bound) is not taken.  Every evaluation counts in
        :attr:`evaluations` (a Jacobian as ``d``); the polish stops before it
        would pass :attr:`cap`.
        """
        from scipy.optimize import least_squares

        t = self.target
        z = np.clip(np.asarray(z, dtype=float), self.lo, self.hi)
        free = self._free()
        R, k0, ok = self.residuals(z[None, :])
        if not ok[0]:
            return z, 0.0, math.inf
        best = (z.copy(), float(k0[0]), self.weighted_max(z, float(k0[0])))
        lam = np.ones(t.theta.size)
        x = np.concatenate([z[free], [k0[0]]])
        lo = np.concatenate([self.lo[free], [-np.inf]])
        hi = np.concatenate([self.hi[free], [np.inf]])
        # keep strictly inside the box for the trust region
        x = np.clip(x, lo, hi)

        def full(x):
            zz = z.copy()
            zz[free] = x[:-1]
            return zz

        for _ in range(rounds):
            # each function evaluation of least_squares may bring a Jacobian (d more) and the round's checks 2
            nfev = min(60, int((self.remaining() - 2) // (1 + z.size))) if self.cap is not None else 60
            if nfev < 2:
                break
            sw = np.sqrt(lam) * t.weight

            def res(x, sw=sw):
                G, _ = self.kind.generate(full(x)[None, :], t.theta)
                return sw * (G[0] + x[-1] - t.s)

            def jac(x, sw=sw):
                J = self.jacobian(full(x))[:, free]
                return sw[:, None] * np.column_stack([J, np.ones(t.theta.size)])

            try:
                with np.errstate(invalid="ignore", divide="ignore"):
                    sol = least_squares(
                        res, x, jac=jac, bounds=(lo, hi), method="trf", x_scale="jac", max_nfev=nfev, xtol=1e-14
                    )
            except (ValueError, np.linalg.LinAlgError):
                break
            self.evaluations += int(sol.nfev)  # the Jacobians were counted by ``jacobian``
            zz = full(sol.x)
            if not (self.feasible(zz)[0] and np.all(np.isfinite(sol.fun))):
                break
            x = sol.x
            e = np.abs(sol.fun / np.where(sw > 0, sw, 1.0))
            m = self.weighted_max(zz, float(x[-1]))
            if m < best[2]:
                best = (zz.copy(), float(x[-1]), m)
            e = e * t.weight
            lam = lam * np.maximum(e, 1e-300)
            lam = lam / lam.sum() * lam.size
        return best
