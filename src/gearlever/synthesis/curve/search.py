"""Topology synthesis for a traced curve: library, retrieval, NSGA-II, least-squares refinement, scaled copies.

The search, in order (every step seeded from ``numpy.random.default_rng``
with the user's seed, so a fixed ``budget`` gives the same designs on any
machine and any number of workers):

1. **Library** (:func:`gearlever.synthesis.curve.library.build_library`): random dyadic topologies of four-,
   six- and eight-bar size (one to :data:`MAX_LIBRARY_DYADS` dyads on a crank
   and two or three ground pivots), each with random sketches, simulated in
   one batch per topology; every moving joint of a sketch that turns fully is
   a library curve, with the sketch *pruned* to the joints the traced joint
   needs (less material).  Descriptor: the magnitudes of the Fourier
   coefficients of the curve resampled by arc length and scaled to unit RMS
   radius, symmetrised in ``k, -k`` (invariant to rotation, start point,
   direction and size).
2. **Retrieval** (:func:`retrieve`): the nearest library curves to the
   target's descriptor, re-ranked by the challenge's distance after scaling
   each sketch so its curve has the target's RMS radius; the best
   :data:`PRESELECT` distinct ones are refined briefly (tasks, like the
   starts) and :data:`STARTS` of them are the starts (:func:`_portfolio`).
3. **Per start** (:func:`run_start`): least-squares refinement of the
   distance (:func:`refine`: Levenberg-Marquardt of
   :func:`scipy.optimize.least_squares` on the analytic Jacobian of
   :func:`~gearlever.synthesis.curve.simulate.simulate_jacobian` carried through the
   resampling by arc length, the challenge's gaps at the current best
   cyclic shift with the rotation a free parameter, weighted by
   ``1 / sqrt(|g|)`` so that the sum of squares is the mean gap the
   challenge scores (iteratively reweighted least squares,
   :func:`_gap_weights`), then the shift walked
   while the distance falls), topology moves (another
   traced joint, one more dyad on the traced joint), then NSGA-II of pymoo
   (Deb et al. 2002) over the joint positions with distance and material as
   objectives and the challenge's bounds as constraints, seeded with the
   refined sketch and two chains of material-weighted refinements
   (:data:`LAMBDAS`, :data:`LAMBDAS_SQUARED`); then the closest front members are refined again, members
   spread over material are refined with a material-weighted objective
   (:data:`SPREAD`, :data:`SPREAD_WEIGHTS`) and, because
   size counts in the distance, each is offered in scaled copies (a smaller
   copy has less material and more distance).
4. **Front**: the non-dominated feasible designs of every start, with
   crank tips (:func:`_crank_tips`) and refined low-material library entries
   (:func:`_low_end`); its largest gaps and highest cliffs are filled by
   refinements of their ends (:func:`_gap_tasks`, :data:`GAP_ROUNDS` rounds,
   tasks like the starts); a second opinion (:func:`_second_opinion`: the
   entries that step 2's brief refinements by :data:`SECOND_METHOD` rank
   first, not started, refined with :data:`SECOND_WEIGHTS`, then a round of
   gaps); the first :data:`MOVE_RANKS` non-dominated ranks moved onto the
   target's frame and scored again; at most ``designs`` of them (chosen
   evenly along the front when there are more).
5. **On the clock** (``time_limit`` without a budget): passes while time
   remains, the first the search at :data:`DEFAULT_BUDGET`, each further one
   from the next :data:`STARTS` entries of the portfolio (then the first
   again, on the next seed), its gaps and the next second opinion, merged
   (at most :data:`MAX_PASSES`; a pass begins only while half the last
   one's time is left).

The residuals and their Jacobian are compiled kernels
(:mod:`gearlever.synthesis.curve._kernels`), the same arithmetic as
:func:`~gearlever.synthesis.curve.simulate.simulate_jacobian` and
:func:`~gearlever.synthesis.curve.score.resample` for one sketch.

Notes
-----
Scores as :mod:`gearlever.synthesis.curve.score`.  NSGA-II: K. Deb, A. Pratap,
S. Agarwal, T. Meyarivan, "A fast and elitist multiobjective genetic
algorithm: NSGA-II", IEEE Trans. Evol. Comput. 6(2), 2002; Levenberg-Marquardt: J. J. Moré, "The
Levenberg-Marquardt algorithm: implementation and theory", Numerical Analysis, Lecture Notes in Mathematics
630, 1978 (MINPACK, as :func:`scipy.optimize.least_squares` calls it); pymoo: J. Blank,
K. Deb, "pymoo: Multi-objective optimization in Python", IEEE Access 8, 2020.
Retrieval over pre-simulated mechanisms follows the idea of LInK (A. H.
Nobari, A. Srivastava, D. Gutfreund, K. Xu, F. Ahmed, 2024) with a
hand-made descriptor in place of a learned one.
"""

from __future__ import annotations

import contextlib
import functools
import math
import time
from concurrent.futures import ProcessPoolExecutor as _Pool
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.mechanism.linkage import linkage_from_dict
from gearlever.synthesis import _dask
from gearlever.synthesis.curve import library as _library
from gearlever.synthesis.curve.library import Library, build_library, cached_library, descriptor
from gearlever.synthesis.curve.score import (
    MAX_DISTANCE,
    MAX_MATERIAL,
    REFERENCE_RMS,
    RESOLUTION,
    check_scoring,
    distance,
    hypervolume,
    material,
    normalise,
    resample,
    rms_radius,
    scoring_target,
)
from gearlever.synthesis.curve.simulate import simulate
from gearlever.synthesis.curve.targets import check_target
from gearlever.synthesis.curve.topology import Topology, _topology
from gearlever.synthesis.driver import Start, check_budget, multistart, order
from gearlever.synthesis.registry import Kind, register

__all__ = [
    "CurveSynthesis",
    "Design",
    "refine",
    "retrieve",
    "run_start",
    "synthesize_curve",
]

#: Retrieved entries refined briefly, and the best of them kept as starts.
PRESELECT = 100
STARTS = 16
#: The portfolio's narrow strategy: starts picked among the first ``NARROW`` retrieved entries only (the
#: earlier search refined 24), alternating with starts picked among all ``PRESELECT`` (see :func:`_portfolio`).
NARROW = 24
#: Alignments kept by the search's fast distance.
KEEP = 12
#: Variants of the add-a-dyad topology move tried per start.
ADD_MOVES = 1
#: NSGA-II population.
POPULATION = 40
#: Scaled copies of each front member.
SCALES = np.linspace(0.9, 0.99, 10)
#: Least material weight of a refinement (a barrier against sketches growing without bound), and the most a
#: distance-only refinement may multiply the material by.
MATERIAL_FLOOR = 1e-11
MAX_GROWTH = 3.0
#: Least-squares method of the refinements (:func:`scipy.optimize.least_squares`): MINPACK's Levenberg-Marquardt,
#: whose loop runs in compiled code (the trust region reflective method's Python loop took two thirds of a
#: refinement's time once the residuals were compiled).
LSQ_METHOD = "lm"
#: the second opinion's method: the retrieved entries briefly refined by it too
SECOND_METHOD = "trf"
#: entries the second opinion adds (those the first did not start from)
SECOND = 2
#: material weights of their refinements (0: distance alone)
SECOND_WEIGHTS = (0.0, 0.003, 0.01, 0.03, 0.1, 0.3)
#: non-dominated ranks moved onto the target's frame and scored again there
MOVE_RANKS = 5
#: evaluations of each pass on the clock (``time_limit`` without a budget): the default budget
DEFAULT_BUDGET = 20_000
#: most passes on the clock
MAX_PASSES = 64
#: gap rounds after the second opinion
SECOND_GAP_ROUNDS = 1
#: Front members (closest first) polished by a longer refinement.
POLISH = 5
#: Most function evaluations of each least-squares solve of a polish (eight rounds at most).
POLISH_NFEV = 60
#: Low-material library entries (five to :data:`LOW_END_JOINTS` joints, material at most :data:`LOW_END_MATERIAL`
#: RMS radii of the target) refined with each material weight of :data:`LOW_END_WEIGHTS` (:func:`_low_end`).
LOW_END = 3
LOW_END_JOINTS = 6
LOW_END_MATERIAL = 6.3
LOW_END_WEIGHTS = (0.003, 0.01, 0.03, 0.1, 0.3)
#: The merged front's largest gaps (by the area they leave undominated) filled by refinements of their two ends
#: (:func:`_gap_tasks`), for :data:`GAP_ROUNDS` rounds, with the gap's own material weight times each of
#: :data:`GAP_FACTORS`.
GAPS = 8
GAP_ROUNDS = 3
GAP_FACTORS = (0.5, 1.0, 2.0)
CLIFFS = 4
#: Front members (spread over material) refined again with each of the material weights ``SPREAD_WEIGHTS``.
SPREAD = 6
SPREAD_WEIGHTS = (0.0005, 0.005, 0.03, 0.1)
#: Material weights of the refinement chain.
LAMBDAS = np.geomspace(3e-4, 0.3, 12)
#: Material weights of the second chain (squared gaps + weight x squared material).
LAMBDAS_SQUARED = np.geomspace(1e-3, 0.3, 10)
#: Caps (and the least budget).
MIN_BUDGET = 1000
MAX_BUDGET = 10**7
MAX_DESIGNS = 1000
MAX_TIME = 86_400.0
#: Most local processes by default (:func:`default_workers`).
MAX_DEFAULT_WORKERS = 2
#: Environment variables of the linear algebra libraries' thread counts, 1 in the worker processes
#: (:func:`_local_pool`).
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
#: Most local processes (more ``workers`` share them; the preselection has 50 tasks and the starts 4).
MAX_PROCESSES = 32


def _target_rms(target) -> float:
    t = resample(np.asarray(target, dtype=float)[None], RESOLUTION)[0]
    t = t - t.mean(0)
    return float(np.sqrt((t**2).sum(-1).mean()))


def evaluate(topo: Topology, x0s, target, keep: int | None = KEEP):
    """Distance (fast mode unless ``keep`` is None) and material of sketches of one topology."""
    x0s = np.asarray(x0s, dtype=float)
    x = simulate(x0s, topo.plan)
    d = distance(x[:, topo.target], target, keep=keep)
    return d, material(x0s, topo.edges)


def retrieve(library: Library, target, starts: int = STARTS, shortlist: int = 400):
    """The ``starts`` best library entries for ``target``: (topology, sketch scaled to the target's size)."""
    td = descriptor(np.asarray(target, dtype=float)[None])[0]
    dist = np.linalg.norm(library.descriptors - td, axis=1)
    order = np.argsort(dist, kind="stable")[:shortlist]
    trms = _target_rms(target)
    scored = []
    for e in order:
        topo = library.topologies[int(library.entry_topology[e])]
        x0 = library.sketches[e] * (trms / library.rms[e])
        d, m = evaluate(topo, x0[None], target)
        scored.append((float(d[0]), int(e), topo, x0))
    scored.sort(key=lambda s: (s[0], s[1]))
    out, seen = [], set()
    for d, _e, topo, x0 in scored:
        key = (topo.key(), round(d, 6))
        if key in seen or not math.isfinite(d):
            continue
        seen.add(key)
        out.append((topo, x0))
        if len(out) == starts:
            break
    return out


@dataclass(frozen=True)
class _Target:
    z: np.ndarray
    scale: float
    raw: np.ndarray


def _target(target) -> _Target:
    t = resample(np.asarray(target, dtype=float)[None], RESOLUTION)[0]
    t = t - t.mean(0)
    s = float(np.sqrt((t**2).sum(-1).mean()))
    return _Target((t[:, 0] + 1j * t[:, 1]) / s, s, np.asarray(target, dtype=float))


def _best_alignment(tc, curve) -> tuple[int, float]:
    """Index (as :func:`~gearlever.synthesis.curve.score._alignment_indices`) and angle of the best alignment."""
    from gearlever.synthesis.curve.score import _alignment_indices

    n = tc.z.shape[0]
    c = resample(curve[None], n)[0]
    c = c - c.mean(0)
    C = ((c[:, 0] + 1j * c[:, 1]) / tc.scale)[_alignment_indices(n)]
    z = (tc.z * np.conj(C)).sum(-1)
    rot = np.exp(1j * np.angle(z))
    a = int(np.argmin(np.abs(tc.z - rot[:, None] * C).mean(-1)))
    return a, float(np.angle(z[a]))


def _gap_weights(tc, curve, a: int, angle: float, normalise: bool = True) -> np.ndarray:
    """Weights ``1 / sqrt(|g_k|)`` of the point gaps ``g_k`` of a curve at alignment ``a`` and rotation ``angle``.

    Least squares of the weighted gaps ``w_k g_k`` minimises ``sum |g_k|^2 / |g_k| = sum |g_k|`` at the
    current design: the challenge's distance (a mean of gaps, not of squared gaps), by iteratively
    reweighted least squares (each round of :func:`refine` weighs again).  Gaps below a thousandth of
    the mean count as that (no infinite weight).
    """
    from gearlever.synthesis.curve.score import _alignment_indices

    n = tc.z.shape[0]
    c = resample(curve[None], n)[0]
    z = c[:, 0] + 1j * c[:, 1]
    z = (z - z.mean()) / tc.scale
    g = np.abs(np.exp(1j * angle) * z[_alignment_indices(n)[a]] - tc.z)
    if not np.isfinite(g).all():
        return np.ones(n)
    w = 1.0 / np.sqrt(np.maximum(g, 1e-3 * max(float(g.mean()), 1e-300)))
    return w / math.sqrt(float((w**2).mean())) if normalise else w


def _residuals(topo: Topology, tc, a: int, material_weight: float, weights=None, linear: bool = False):
    """Residuals of the distance at alignment ``a`` and their Jacobian; parameters: the sketch, then an angle.

    The residuals are the gaps between the target's points and the design's
    curve resampled by arc length, centred, scaled and turned by the angle
    (the challenge's distance with its cyclic shift and direction ``a``
    fixed, squared), then ``sqrt(w)`` x material.  The Jacobian goes through
    the resampling: a resampled point ``p_lo + w (p_hi - p_lo)`` with
    ``w = (s L - c_lo) / l_lo`` (``L`` the curve's length, ``c_lo`` the
    length up to sample ``lo``, ``l_lo`` the segment's) moves with the
    samples and with the lengths.  Both are compiled kernels
    (:mod:`gearlever.synthesis.curve._kernels`: one sketch a call, where the
    batched numpy simulator spends its time in overhead); a sketch that
    locks gives residuals of 10 and a zero Jacobian.
    """
    from gearlever.synthesis.curve import _kernels
    from gearlever.synthesis.curve.score import _alignment_indices

    N = topo.n
    n = tc.z.shape[0]
    perm = np.ascontiguousarray(_alignment_indices(n)[a], dtype=np.int64)
    s = np.linspace(0.0, 1.0, n)
    lam = math.sqrt(material_weight)
    norm = np.broadcast_to((1.0 if weights is None else np.asarray(weights, dtype=float)) / math.sqrt(n), (n,))
    norm = np.ascontiguousarray(norm, dtype=float)
    extra = 1 if lam else 0
    plan = topo.plan
    dyads = np.ascontiguousarray(plan.dyads, dtype=np.int64).reshape(-1, 4)
    fixed = (dyads, int(plan.pivot), int(plan.tip), int(topo.target), _crank_cs(), s, perm)
    tz = np.ascontiguousarray(np.column_stack([tc.z.real, tc.z.imag]))

    def fun(q):
        x = np.ascontiguousarray(q[:-1].reshape(N, 2))
        g = _kernels.gaps(x, *fixed, tz, tc.scale, float(q[-1]), norm)
        if g is None:
            return np.full(2 * n + extra, 10.0)
        if lam:
            m = material(x[None], topo.edges)[0]
            g = np.append(g, lam * (math.sqrt(m) if linear else m))
        return g

    def jac(q):
        x = np.ascontiguousarray(q[:-1].reshape(N, 2))
        out = _kernels.gaps_jacobian(x, *fixed, tc.scale, float(q[-1]), norm)
        if out is None:
            return np.zeros((2 * n + extra, 2 * N + 1))
        if lam:
            ed = topo.edges
            d = x[ed[:, 0]] - x[ed[:, 1]]
            L = np.hypot(d[:, 0], d[:, 1])
            gm = np.zeros((N, 2))
            np.add.at(gm, ed[:, 0], 2 * d / L[:, None])
            np.add.at(gm, ed[:, 1], -2 * d / L[:, None])
            dm = lam * np.append(gm.reshape(-1), 0.0)[None]
            if linear:
                dm = dm / (2.0 * math.sqrt(max(float(material(x[None], topo.edges)[0]), 1e-300)))
            out = np.vstack([out, dm])
        return out

    return fun, jac


@functools.lru_cache(maxsize=1)
def _crank_cs() -> np.ndarray:
    """Cosines and sines of the simulator's crank angles, (T, 2), read-only (computed once, as numpy does)."""
    from gearlever.synthesis.curve.simulate import crank_angles

    th = crank_angles()
    out = np.ascontiguousarray(np.stack([np.cos(th), np.sin(th)], -1))
    out.setflags(write=False)
    return out


def refine(
    topo: Topology,
    x0,
    target,
    rounds: int = 3,
    nfev: int = 20,
    material_weight: float = 0.0,
    walk: bool = True,
    l1: bool = True,
    method: str | None = None,
):
    """Least-squares refinement of the distance of one sketch (analytic Jacobian); returns (x0, d, m, evals).

    Each round fixes the best cyclic shift and direction of the current
    curve (:func:`_best_alignment`) and solves the least-squares problem of
    the gaps between the target's points and the design's curve resampled
    by arc length (:func:`_residuals`: the challenge's distance, squared,
    with the rotation a free parameter); a round is kept only if the
    challenge's distance decreases (the material-weighted cost, with a
    ``material_weight``), and the rounds stop at the first that is not.
    Then (``walk``, distance only) the cyclic shift is moved one sample at
    a time, each way, while the distance falls: the curve's start is tied to
    the crank angle and its time samples are the polyline's corners, so the
    minimum at one shift is not the minimum at the next.

    With ``l1`` (default) each round weighs the gaps by ``1 / sqrt(|g|)``
    of the current design (:func:`_gap_weights`: iteratively reweighted
    least squares of the mean gap, which the challenge scores, instead of
    the mean squared gap), and a ``material_weight`` ``w`` makes the cost the
    mean gap plus ``w`` x material (a weighted sum of the two objectives);
    without it, the squared gaps plus ``w`` x squared material.  ``method``
    is :func:`scipy.optimize.least_squares`'s (default :data:`LSQ_METHOD`).

    Examples
    --------
    >>> from gearlever.mechanism.linkage import linkage_from_dict
    >>> from gearlever.synthesis.curve.simulate import simulate
    >>> lk = linkage_from_dict({"x0": [[0, 0], [0.3, 0], [1, 0], [0.8, 0.8], [0.5, 1.0]],
    ...     "edges": [[0, 1], [1, 3], [2, 3], [1, 4], [3, 4]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> topo = _topology(5, lk.edges, lk.fixed_joints, lk.motor, 4)
    >>> target = simulate(lk.x0[None], topo.plan)[0, 4]
    >>> x, d, m, evals = refine(topo, lk.x0 + [[0, 0], [0.01, 0], [0, 0], [0, 0.01], [0, 0]], target, rounds=10)
    >>> bool(d < 1e-4)
    True
    """
    from scipy.optimize import least_squares

    tc = target if isinstance(target, _Target) else _target(target)
    x0 = np.asarray(x0, dtype=float)
    best_d, best_m = (float(v[0]) for v in evaluate(topo, x0[None], tc.raw))
    m_start = best_m
    evals = 1
    if not math.isfinite(best_d):
        return x0, best_d, best_m, evals
    best = x0
    N = topo.n
    weight = max(material_weight, MATERIAL_FLOOR)
    n = tc.z.shape[0]

    def solve(a, angle, curve):
        gw = _gap_weights(tc, curve, a, angle, normalise=not material_weight) if l1 else None
        fun, jac = _residuals(topo, tc, a, weight, gw, linear=l1 and bool(material_weight))
        q0 = np.append(best.ravel(), angle)
        try:
            res = least_squares(fun, q0, jac=jac, method=method or LSQ_METHOD, max_nfev=nfev, x_scale="jac")
        except (ValueError, np.linalg.LinAlgError):
            return None, math.inf, math.inf, 0
        cand = res.x[:-1].reshape(N, 2)
        d, m = (float(v[0]) for v in evaluate(topo, cand[None], tc.raw))
        if not material_weight:
            better = d < best_d - 1e-9 and m <= MAX_GROWTH * m_start
        else:
            better = math.isfinite(d) and res.cost < 0.5 * float((fun(q0) ** 2).sum()) - 1e-12
        return (cand if better else None), d, m, int(res.nfev) + int(res.njev or 0) + 1

    a = None
    for _ in range(rounds):
        curve = simulate(best[None], topo.plan)[0, topo.target]
        a, angle = _best_alignment(tc, curve)
        cand, d, m, e = solve(a, angle, curve)
        evals += e
        if cand is None:
            break
        best, best_d, best_m = cand, d, m
    if walk and a is not None and not material_weight:
        # the curve's start point is tied to the crank angle: walk the cyclic shift while the distance falls
        for step in (1, -1):
            while True:
                b = (a + step) % n if a < n else n + (a - n + step) % n
                curve = simulate(best[None], topo.plan)[0, topo.target]
                angle = _alignment_angle(tc, curve, b)
                cand, d, m, e = solve(b, angle, curve)
                evals += e
                if cand is None:
                    break
                best, best_d, best_m, a = cand, d, m, b
    return best, best_d, best_m, evals


def _alignment_angle(tc, curve, a: int) -> float:
    """Best rotation of the curve at alignment ``a``."""
    from gearlever.synthesis.curve.score import _alignment_indices

    n = tc.z.shape[0]
    c = resample(curve[None], n)[0]
    c = c - c.mean(0)
    C = ((c[:, 0] + 1j * c[:, 1]) / tc.scale)[_alignment_indices(n)[a]]
    return float(np.angle((tc.z * np.conj(C)).sum()))


def _moves(rng, topo: Topology, x0, max_joints: int, add: int = ADD_MOVES):
    """Topology moves of a design: another traced joint, one more dyad on the traced joint (x0 extended)."""
    out = []
    fixed = set(topo.fixed.tolist())
    for k in range(topo.n):
        if k != topo.target and k not in fixed and k != topo.motor[1]:
            out.append((_topology(topo.n, topo.edges, topo.fixed, topo.motor, k), x0))
    for _ in range(add if topo.n + 1 <= max_joints else 0):
        k = topo.n
        others = [j for j in range(topo.n) if j != topo.target]
        j = int(rng.choice(others))
        edges = np.vstack([topo.edges, [[topo.target, k], [j, k]]])
        size = np.ptp(x0, axis=0).max()
        new = x0[topo.target] + rng.normal(0.0, 0.3 * size, 2)
        x1 = np.vstack([x0, new])
        try:
            out.append((_topology(k + 1, edges, topo.fixed, topo.motor, k), x1))
        except GearleverError:
            pass
    return out


def _nsga(topo: Topology, x0, target, evals: int, seed: int, deadline, population: int = POPULATION):
    """NSGA-II (pymoo) over the joint positions of one topology, seeded around ``x0``; returns (X, F)."""
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PolynomialMutation
    from pymoo.termination import get_termination

    N = topo.n
    lo = hi = None

    class _P(Problem):
        def __init__(self, lo, hi):
            super().__init__(n_var=2 * N, n_obj=2, n_ieq_constr=2, xl=lo, xu=hi)

        def _evaluate(self, X, out, *args, **kwargs):
            d, m = evaluate(topo, X.reshape(-1, N, 2), target)
            d = np.where(np.isfinite(d), d, 1e6)
            out["F"] = np.column_stack([d, m])
            out["G"] = np.column_stack([d - MAX_DISTANCE, m - MAX_MATERIAL])

    rng = np.random.default_rng(seed)
    seeds = np.asarray(x0, dtype=float).reshape(-1, 2 * N)
    x0 = seeds[0].reshape(N, 2)
    size = float(np.ptp(x0, axis=0).max())
    lo, hi = seeds.min(0) - size, seeds.max(0) + size
    pick = seeds[np.arange(population) % len(seeds)]
    pop = pick + rng.normal(0.0, 0.01 * size, (population, 2 * N))
    pop[: len(seeds)] = seeds[:population]
    pop = np.clip(pop, lo, hi)
    gens = max(1, evals // population)
    algo = NSGA2(
        pop_size=population,
        sampling=pop,
        crossover=SBX(prob=0.9, eta=15),
        mutation=PolynomialMutation(prob=1.0 / (2 * N), eta=20),
        eliminate_duplicates=True,
    )
    from pymoo.optimize import minimize

    term = get_termination("n_gen", gens)
    if deadline is not None:
        from pymoo.termination.collection import TerminationCollection
        from pymoo.termination.max_time import TimeBasedTermination

        term = TerminationCollection(term, TimeBasedTermination(max(1e-3, deadline - time.monotonic())))
    res = minimize(_P(lo, hi), algo, term, seed=int(seed % (2**31)), verbose=False, save_history=False)
    pop = res.pop
    return pop.get("X").reshape(-1, N, 2), pop.get("F"), int(res.algorithm.evaluator.n_eval)


class Design(NamedTuple):
    """A design of one start: exact distance, material, topology (plain data) and sketch (lists)."""

    distance: float
    material: float
    topology: dict
    x0: list


def run_start(spec: dict, seed: int, k: int, evals: int, deadline=None) -> list[Design]:
    """One start: refine, topology moves, NSGA-II, refine the front, scaled copies; its :class:`Design` list."""
    return _run_start(spec, seed, k, evals, deadline)[0]


def _run_start(spec: dict, seed: int, k: int, evals: int, deadline=None) -> tuple[list[Design], int, int]:
    """:func:`run_start` and what it spent: (designs, NSGA-II evaluations, the refinements' and scorings' ones)."""
    rng = np.random.default_rng([seed, k])
    tune = {**_tuning(), **spec.get("tuning", {})}
    target = np.asarray(spec["target"], dtype=float)
    tc = _target(target)
    s = spec["starts"][k]
    topo = _topology(s["n"], s["edges"], s["fixed"], s["motor"], s["target"])
    x0 = np.asarray(s["x0"], dtype=float)
    used = 0
    x0, d, m, e = refine(topo, x0, tc, rounds=6, nfev=40)
    used += e
    cands = [(topo, x0, d)]
    for t2, x2 in _moves(rng, topo, x0, spec["max_joints"], tune["add_moves"]):
        if deadline is not None and time.monotonic() > deadline:
            break
        x2, d2, m2, e2 = refine(t2, x2, tc, rounds=2)
        used += e2
        cands.append((t2, x2, d2))
    cands.sort(key=lambda c: c[2])
    topo, x0, _ = cands[0]
    # material-weighted refinements, continued from one weight to the next: a first front, in two chains (the
    # mean gap + weight x material: the front's close end; the squared gaps + weight x squared material, which
    # pushes harder on material: its low end)
    chain = [x0]
    for weights, l1 in ((tune["lambdas"], True), (tune["lambdas_squared"], False)):
        x = x0
        for lam in weights:
            if deadline is not None and time.monotonic() > deadline:
                break
            x, dl, ml, e = refine(topo, x, tc, rounds=2, material_weight=lam, l1=l1)
            used += e
            if math.isfinite(dl):
                chain.append(x)
    X, F, n_nsga = _nsga(
        topo,
        np.array(chain),
        target,
        max(tune["population"], evals - used),
        int(rng.integers(2**31)),
        deadline,
        tune["population"],
    )
    Xall = np.concatenate([X, np.array(chain)])
    d, m = evaluate(topo, Xall, target)
    used += len(Xall)
    front = _nondominated(d, m)
    # polish the closest designs: more rounds of the distance-only refinement
    polished = []
    for i in front[: tune["polish"]]:
        if deadline is not None and time.monotonic() > deadline:
            break
        xp, dp, mp, e = refine(topo, Xall[i], tc, rounds=8, nfev=tune["polish_nfev"])
        used += e
        polished.append(xp)
    if polished:
        Xall = np.concatenate([Xall, np.array(polished)])
        d, m = evaluate(topo, Xall, target)
        used += len(Xall)
        front = _nondominated(d, m)
    # members spread over material, refined with a material-weighted objective for a few weights: fill the front
    spread = front[np.unique(np.round(np.linspace(0, front.size - 1, min(tune["spread"], front.size))).astype(int))]
    extra = []
    for i in spread:
        for w in tune["spread_weights"]:
            if deadline is not None and time.monotonic() > deadline:
                break
            xw, dw, mw, e = refine(topo, Xall[i], tc, rounds=2, material_weight=w)
            used += e
            if math.isfinite(dw):
                extra.append(xw)
    if extra:
        Xall = np.concatenate([Xall, np.array(extra)])
        d, m = evaluate(topo, Xall, target)
        used += len(Xall)
        front = _nondominated(d, m)
    # each front member and its scaled copies, evaluated in one batch
    X = Xall[front][:, None] * np.concatenate([[1.0], tune["scales"]])[None, :, None, None]
    X = X.reshape(-1, topo.n, 2)
    ds, ms = evaluate(topo, X, target)
    used += len(X) - front.size
    designs = list(zip(ds.tolist(), ms.tolist(), X))
    td = {
        "n": topo.n,
        "edges": topo.edges.tolist(),
        "fixed": topo.fixed.tolist(),
        "motor": list(topo.motor),
        "target": topo.target,
    }
    return [Design(dd, mm, td, xx.tolist()) for dd, mm, xx in designs if math.isfinite(dd)], n_nsga, used


def _pick_starts(refined, count: int) -> list:
    """Half the starts by the area a design alone dominates (distance and material), half by distance."""
    ok = [r for r in refined if math.isfinite(r[0])]
    by_area = sorted(ok, key=lambda r: (-max(0.0, MAX_DISTANCE - r[0]) * max(0.0, MAX_MATERIAL - r[1]), r[0], r[2]))
    by_distance = sorted(ok, key=lambda r: (r[0], r[2]))
    out, seen = [], set()
    for a, b in zip(by_area, by_distance):
        for r in (a, b):
            if r[2] not in seen and len(out) < count:
                seen.add(r[2])
                out.append((r[3], r[4]))
    return out


def _portfolio(refined, count: int) -> list:
    """Starts from two strategies, alternating: the narrow (the first :data:`NARROW` retrieved) and the wide (all).

    The narrow strategy keeps the starts nearest the target's descriptor
    (the earlier search's D shape, 5.323); the wide one the best after
    refinement (better on the challenge's curves).  Each strategy's list
    comes from :func:`_pick_starts`; a start both pick is taken once and the
    next of the other list fills its place.  Deterministic: no draw.
    """
    narrow = _pick_starts([r for r in refined if r[2] < NARROW], count)
    wide = _pick_starts(refined, count)
    out, seen = [], set()
    for pair in zip(wide, narrow):
        for start in pair:
            key = id(start[1])
            if key not in seen and len(out) < count:
                seen.add(key)
                out.append(start)
    for start in wide + narrow:
        if id(start[1]) not in seen and len(out) < count:
            seen.add(id(start[1]))
            out.append(start)
    return out


def _second_opinion(second, taken: set, count: int) -> list:
    """``(entry, topology, sketch)`` of ``count`` entries of ``second`` not in ``taken``, as :func:`_pick_starts` picks.

    ``second`` holds the retrieved entries briefly refined by
    :data:`SECOND_METHOD` (rows ``(distance, material, entry, topology,
    sketch)``, like the starts'); the two methods land in different local
    minima, so an entry the first ranks low can be the best of the second
    (the own suite's kidney: entry 37 at distance 0.217 by Levenberg-Marquardt,
    0.085 by the trust region method).
    """
    rows = {id(r[4]): r for r in second if r[2] not in taken}
    return [(rows[id(x)][2], t, x) for t, x in _pick_starts(list(rows.values()), count)]


def _nondominated(d, m) -> np.ndarray:
    order = np.lexsort((m, d))
    out, best = [], math.inf
    for i in order:
        if math.isfinite(d[i]) and m[i] < best:
            out.append(int(i))
            best = m[i]
    return np.array(out, dtype=int)


def _first_ranks(d, m, idx, ranks: int) -> np.ndarray:
    """The indices ``idx`` on the first ``ranks`` non-dominated fronts of ``(d, m)`` (sorted)."""
    out = []
    idx = np.asarray(idx, dtype=int)
    for _ in range(ranks):
        if not idx.size:
            break
        f = idx[_nondominated(d[idx], m[idx])]
        out.append(f)
        idx = np.setdiff1d(idx, f)
    return np.sort(np.concatenate(out)) if out else idx


def _spec(spec: dict) -> dict:
    return spec


def curve_start(make, seed: int, k: int, evals: int, method: str = "nsga2") -> Start:
    """Start ``k`` of the driver (:func:`gearlever.synthesis.driver.multistart`): :func:`run_start` as a record.

    ``make()`` gives the spec; the start's designs are in ``info["designs"]``,
    its objective the smallest distance among them; ``evaluations`` is the
    count of NSGA-II's evaluations (at most the start's share of the budget;
    fewer when the clock stops it), ``polish_evaluations`` that of the
    refinements (function and Jacobian calls) and of the scorings of front
    members and their scaled copies: each one simulation of one sketch over a
    crank turn.
    """
    spec = make()
    designs, n_nsga, n_polish = _run_start(spec, seed, k, evals, spec.get("deadline"))
    best = min(designs, key=lambda d: d.distance, default=None)
    return Start(
        index=k,
        x=None if best is None else np.asarray(best.x0, dtype=float),
        objective=math.inf if best is None else best.distance,
        feasible=any(d.distance < MAX_DISTANCE and d.material < MAX_MATERIAL for d in designs),
        evaluations=int(n_nsga),
        polish_evaluations=int(n_polish),
        info={"designs": designs},
    )


@dataclass(frozen=True, eq=False)
class CurveSynthesis(Result):
    """Result of :func:`synthesize_curve`: the Pareto designs (error ascending) and the run's facts.

    Attributes
    ----------
    designs : tuple of gearlever.mechanism.linkage.Linkage
        The front, error (distance) ascending.
    error, material : ndarray
        Their error (the challenge's distance of the traced curve to the target) and material
        (:mod:`gearlever.synthesis.curve.score`).
    hypervolume : float
        Of the front against the reference (:data:`~gearlever.synthesis.curve.score.MAX_DISTANCE`,
        :data:`~gearlever.synthesis.curve.score.MAX_MATERIAL`).
    evaluations : int
        NSGA-II's evaluations, all starts together: at most the budget, the
        real count when the clock stops the search.
    seed, starts, library_size : int
    seconds : float
    scoring : str
        ``"relative"`` or ``"challenge"`` (:mod:`gearlever.synthesis.curve.score`).
    material_scale : float
        The scoring's material per unit of material in the target's units
        (``REFERENCE_RMS / r`` in the relative scoring, 1 in the challenge's):
        ``material / material_scale`` is the designs' material in the target's units.
    transforms : ndarray, shape (D, 4)
        Per design, ``(rotation, scale, tx, ty)``: the similarity that moved
        the sketch the search found onto the target where it was drawn,
        ``x = scale R(rotation) x_found + (tx, ty)`` (rotation in radians);
        ``designs`` are the moved sketches.
    polish_evaluations : int
        Evaluations of the refinements and of the scorings of front members,
        outside the budget.
    """

    designs: tuple
    error: np.ndarray
    material: np.ndarray
    hypervolume: float
    evaluations: int
    seed: int
    starts: int
    library_size: int
    seconds: float = field(default=0.0)
    scoring: str = "challenge"
    material_scale: float = 1.0
    transforms: np.ndarray | None = None
    polish_evaluations: int = 0

    def summary(self) -> dict:
        """Strict-JSON-ready summary: hypervolume, reference, scoring, counts and the front (with each transform)."""
        tf = np.zeros((len(self.designs), 4)) if self.transforms is None else np.asarray(self.transforms)
        if self.scoring == "relative":
            rule = (
                f"relative: distance to the closed target; material x {REFERENCE_RMS:g} / (the target's RMS "
                f"radius), that is x {self.material_scale:.6g} (material measured at the size of the MIT 2.156 "
                "challenge's targets)"
            )
        else:
            rule = "challenge: distance to the open polyline of the target's points; material as it is (absolute)"
        return {
            "hypervolume": self.hypervolume,
            "reference": [MAX_DISTANCE, MAX_MATERIAL],
            "scoring": self.scoring,
            "scoring_rule": rule,
            "material_scale": self.material_scale,
            "designs": len(self.designs),
            "empty": not len(self.designs),
            "evaluations": self.evaluations,
            "polish_evaluations": self.polish_evaluations,
            "seed": self.seed,
            "starts": self.starts,
            "library_size": self.library_size,
            "best_distance": float(self.error[0]) if len(self.designs) else None,
            "least_material": float(self.material.min()) if len(self.designs) else None,
            "front": [
                {
                    "distance": float(d),
                    "material": float(m),
                    "material_in_target_units": float(m) / self.material_scale,
                    "joints": lk.n_joints,
                    "links": len(lk.edges),
                    "transform": {
                        "rotation_deg": math.degrees(t[0]),
                        "scale": float(t[1]),
                        "translation": [float(t[2]), float(t[3])],
                    },
                }
                for d, m, lk, t in zip(self.error, self.material, self.designs, tf)
            ],
        }


def synthesize_curve(
    target,
    *,
    max_joints: int = 20,
    designs: int = MAX_DESIGNS,
    budget: int | None = DEFAULT_BUDGET,
    time_limit: float | None = None,
    seed: int = 0,
    workers: int | None = None,
    scheduler: str | None = None,
    progress=None,
    library_size: int | None = None,
    library_seed: int = 0,
    use_cache: bool = True,
    scoring: str = "relative",
) -> CurveSynthesis:
    """Linkages (topology and dimensions) whose traced joint follows ``target``, on the distance-material front.

    Parameters
    ----------
    target : array_like, shape (K, 2)
        Target curve (checked by :func:`gearlever.synthesis.curve.targets.check_target`).
    max_joints : int
        4 to 20.
    designs : int
        Most designs returned (1 to 1000).
    budget : int, optional
        Evaluations of the search after retrieval (reproducible), :data:`MIN_BUDGET` to
        :data:`MAX_BUDGET` (:func:`gearlever.synthesis.driver.check_budget`).
    time_limit : float, optional
        Seconds: the search stops on the clock (not reproducible); without a ``budget``, passes at
        :data:`DEFAULT_BUDGET` run while time remains and their designs are merged.
    seed : int
    workers, scheduler
        Local processes (an int; 1 runs in this process; default :func:`default_workers`, the cores this
        process may use, at most :data:`MAX_DEFAULT_WORKERS`), a map-like, or the address of a
        dask.distributed scheduler (:func:`gearlever.synthesis.driver.multistart`).  The designs are the
        same for any of them.  Processes are started by ``spawn``: a script calling this with more than
        one worker needs the ``if __name__ == "__main__":`` guard.
    progress : callable, optional
        ``progress(label, done, total)``.
    library_size : int, optional
        Mechanisms of the retrieval library, 1 to :data:`~gearlever.synthesis.curve.library.MAX_LIBRARY_SIZE`
        (default :data:`~gearlever.synthesis.curve.library.LIBRARY_TOPOLOGIES` x
        :data:`~gearlever.synthesis.curve.library.LIBRARY_SKETCHES`).
    library_seed : int
        Seed of the library's draws (0 to 2^31 - 1).
    use_cache : bool
        Load the library from the user's cache folder when one of this size,
        seed and format is stored there (:mod:`gearlever.synthesis.curve.library`);
        otherwise, or if False, build it in memory.  The designs are the same
        either way.
    scoring : {"relative", "challenge"}
        ``"relative"`` (default, for a user's curve): the target is closed and
        material is measured at the size of the challenge's targets (the
        search runs on the target moved to its centre and scaled to RMS radius
        :data:`~gearlever.synthesis.curve.score.REFERENCE_RMS`); ``"challenge"``: the
        MIT 2.156 challenge's rules as they are, for its own targets
        (:mod:`gearlever.synthesis.curve.score`).

    Returns
    -------
    CurveSynthesis
        Every design moved (rotated, translated and, in the relative scoring,
        scaled) so that its traced joint runs on the target where it was drawn.

    Notes
    -----
    The steps and their sources are in the module docstring.
    """
    t0 = time.monotonic()
    target = user_target = check_target(target)
    scoring = check_scoring(scoring)
    scored = scoring_target(target, scoring)  # the polyline the distance is measured to, in the user's frame
    if scoring == "relative":
        centre = resample(scored[None], RESOLUTION)[0].mean(0)
        k = REFERENCE_RMS / rms_radius(scored)
        target = (scored - centre) * k
    else:
        centre, k, target = np.zeros(2), 1.0, scored
    if not 4 <= int(max_joints) <= 20:
        raise GearleverError(f"max_joints must be 4 to 20, got {max_joints}")
    if not 1 <= int(designs) <= MAX_DESIGNS:
        raise GearleverError(f"designs must be 1 to {MAX_DESIGNS}, got {designs}")
    if budget is not None:
        budget = check_budget("budget", budget, MIN_BUDGET, MAX_BUDGET)
    if time_limit is not None and not 1.0 <= float(time_limit) <= MAX_TIME:
        raise GearleverError(f"time_limit must be 1 to {MAX_TIME:g} seconds, got {time_limit}")
    size = _library.LIBRARY_TOPOLOGIES * _library.LIBRARY_SKETCHES if library_size is None else library_size
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or not 1 <= size <= _library.MAX_LIBRARY_SIZE:
        raise GearleverError(f"library_size must be an integer 1 to {_library.MAX_LIBRARY_SIZE}, got {library_size!r}")
    if isinstance(library_seed, bool) or not isinstance(library_seed, (int, np.integer)):
        raise GearleverError(f"library_seed must be an integer 0 to 2^31 - 1, got {library_seed!r}")
    if not 0 <= library_seed < 2**31:
        raise GearleverError(f"library_seed must be an integer 0 to 2^31 - 1, got {library_seed!r}")
    lib = cached_library(int(size), int(library_seed)) if use_cache else None
    if lib is not None:
        lib = lib.limited(int(max_joints))
    else:
        lib = build_library(int(library_seed), max_joints=int(max_joints), size=int(size))
    shortlist = retrieve(lib, target, PRESELECT)
    low_end = _low_end(lib, target)
    if not shortlist:
        raise GearleverError("target: no library mechanism traces a curve of this kind")
    settings = _Settings(
        target,
        user_target,
        scoring,
        centre,
        float(k),
        tuple(shortlist),
        tuple(low_end),
        int(lib.descriptors.shape[0]),
        t0,
        time_limit,
        budget,
        int(max_joints),
        int(designs),
        int(seed),
    )
    with _local_pool(workers, scheduler) as pool:
        return _search(
            settings, pool if pool is not None else (scheduler or (1 if workers is None else workers)), progress
        )


@dataclass(frozen=True, eq=False)
class _Settings:
    """What :func:`_search` needs of :func:`synthesize_curve`'s checked arguments and retrieval, as one record.

    ``target`` is the search's target (the user's, in the relative scoring,
    moved by ``-centre`` and scaled by ``k``), ``user_target`` the polyline
    the user's scoring measures; ``shortlist`` the retrieved
    ``(topology, sketch)`` pairs and ``low_end`` those of :func:`_low_end`;
    ``t0`` the clock's start (``time.monotonic``).
    """

    target: np.ndarray
    user_target: np.ndarray
    scoring: str
    centre: np.ndarray
    k: float
    shortlist: tuple
    low_end: tuple
    library_size: int
    t0: float
    time_limit: float | None
    budget: int | None
    max_joints: int
    designs: int
    seed: int


def _search(settings: _Settings, workers, progress) -> CurveSynthesis:
    """The search of :func:`synthesize_curve` after retrieval: preselection, starts, the front moved and scored."""
    target, user_target, scoring, centre, k = (
        settings.target,
        settings.user_target,
        settings.scoring,
        settings.centre,
        settings.k,
    )
    shortlist, t0, time_limit, budget = settings.shortlist, settings.t0, settings.time_limit, settings.budget
    max_joints, designs, seed = settings.max_joints, settings.designs, settings.seed
    # a short refinement of every retrieved entry by each method (tasks, like the starts): by the first, the best
    # refined ones are the starts; by the second, the second opinion
    entries = {
        "target": target.tolist(),
        "entries": [_plain(t, x) for t, x in shortlist],
        "deadline": None if time_limit is None else t0 + 0.5 * float(time_limit),
        "methods": [LSQ_METHOD, SECOND_METHOD],
    }
    pre = _dask.run_tasks(_preselect_chunk, (entries,), len(shortlist), 0, workers=workers)
    refined, second = (
        [
            (r[j], r[j + 1], r[0], shortlist[r[0]][0], np.asarray(r[j + 2], dtype=float))
            for r in pre
            if r[j + 2] is not None
        ]
        for j in (1, 4)
    )
    deadline = None if time_limit is None else t0 + float(time_limit)
    # on the clock without a budget: passes at the default budget while time remains (the first is the default
    # search), each from the next starts of the portfolio (then the first again, on the next seed), merged
    clocked = time_limit is not None and budget is None
    total = budget if budget is not None else (DEFAULT_BUDGET if clocked else 10**6)
    queue = _portfolio(refined, len(refined))
    started: set = set()
    seconded: set = set()
    res: list = []
    runs: list = []
    for p in range(MAX_PASSES if clocked else 1):
        began = time.monotonic()
        starts = _portfolio(refined, STARTS) if p == 0 else [s for s in queue if id(s[1]) not in started][:STARTS]
        if not starts:
            started = set()
            starts = queue[:STARTS]
        started |= {id(x) for _, x in starts}
        spec = {
            "target": target.tolist(),
            "max_joints": int(max_joints),
            "starts": [_plain(t, x) for t, x in starts],
            "deadline": deadline,
            "tuning": _tuning(),
        }
        evals = max(POPULATION * 2, total // len(starts))
        done = multistart(
            functools.partial(_spec, spec),
            len(starts),
            seed + p,
            budget=evals * len(starts),
            workers=_PerStart(workers, [t.n for t, _ in starts]) if isinstance(workers, _Pool) else workers,
            progress=progress,
            method="nsga2",
            start=curve_start,
        )
        # every design of every start (in start order), by exact distance then start
        done = sorted(done, key=lambda r: r.index)
        runs += done
        got = order([(d, r.index) for r in done for d in r.info["designs"]], lambda t: t[0].distance, lambda t: t[1])
        res += [d for d, _ in got]
        if p == 0:
            res += _crank_tips(target)
            res += _weighted(
                target, deadline, workers, [(_plain(t, x), w) for t, x in settings.low_end for w in LOW_END_WEIGHTS]
            )
        res = _fill_gaps(res, target, deadline, workers, GAP_ROUNDS)
        extra = _second_opinion(second, {r[2] for r in refined if id(r[4]) in started} | seconded, SECOND)
        seconded |= {n for n, _, _ in extra}
        if extra:
            pairs = [(_plain(t, x), w) for _, t, x in extra for w in SECOND_WEIGHTS]
            res = _fill_gaps(
                res + _weighted(target, deadline, workers, pairs), target, deadline, workers, SECOND_GAP_ROUNDS
            )
        if deadline is None or deadline - time.monotonic() < 0.5 * (time.monotonic() - began):
            break
    # the non-dominated feasible ones, moved onto the target's frame (where they are scored again: the crank's
    # angles are absolute, so a moved linkage is sampled at other phases of its motion), evenly thinned to `designs`
    dd = np.array([r.distance for r in res])
    mm = np.array([r.material for r in res])
    feas = (dd < MAX_DISTANCE) & (mm < MAX_MATERIAL)
    front = _first_ranks(dd, mm, np.flatnonzero(feas), MOVE_RANKS)
    moved, transforms, dist, mat = [], [], [], []
    for i in front:
        td, xx = res[i].topology, res[i].x0
        lk = linkage_from_dict(
            {
                "x0": xx,
                "edges": td["edges"],
                "fixed_joints": td["fixed"],
                "motor": td["motor"],
                "target_joint": td["target"],
            }
        )
        lk2, tf = _to_target_frame(lk, target, centre, k, rotate=scoring == "relative")
        d, m = _score_linkage(lk2, user_target, scoring, k)
        moved.append(lk2)
        transforms.append(tf)
        dist.append(d)
        mat.append(m)
    dist, mat = np.array(dist, dtype=float), np.array(mat, dtype=float)
    idx = np.flatnonzero((dist < MAX_DISTANCE) & (mat < MAX_MATERIAL))
    front = idx[_nondominated(dist[idx], mat[idx])] if idx.size else idx
    if front.size > designs:
        pick = np.unique(np.round(np.linspace(0, front.size - 1, designs)).astype(int))
        front = front[pick]
    moved = [moved[i] for i in front]
    transforms = [transforms[i] for i in front]
    dist, mat = dist[front], mat[front]
    hv = hypervolume(np.column_stack([dist, mat])) if front.size else 0.0
    return CurveSynthesis(
        tuple(moved),
        dist,
        mat,
        hv,
        int(sum(r.evaluations for r in runs)),
        int(seed),
        len(runs),
        settings.library_size,
        time.monotonic() - t0,
        scoring,
        float(k),
        np.array(transforms, dtype=float).reshape(-1, 4),
        int(sum(r.polish_evaluations for r in runs)),
    )


def _weighted(target, deadline, workers, pairs) -> list:
    """Designs of :func:`_weighted_chunk` for ``(sketch as plain data, material weight)`` pairs, as tasks."""
    if not pairs:
        return []
    spec = {"target": target.tolist(), "entries": [{**p, "weight": float(w)} for p, w in pairs], "deadline": deadline}
    chunks = _dask.run_tasks(_weighted_chunk, (spec,), len(pairs), 0, workers=workers)
    return [d for pair in chunks for d in pair]


def _fill_gaps(res: list, target, deadline, workers, rounds: int) -> list:
    """``res`` and the refinements of :func:`_gap_tasks`, ``rounds`` times (fewer when the front has no gap)."""
    for _ in range(rounds):
        gaps = _gap_tasks(res, GAPS)
        if not gaps:
            break
        res = res + _weighted(target, deadline, workers, [({**d.topology, "x0": d.x0}, w) for d, w in gaps])
    return res


def _tuning() -> dict:
    """The per-start settings as plain data: sent with the spec, so every worker process runs the caller's."""
    return {
        "lambdas": np.asarray(LAMBDAS, dtype=float).tolist(),
        "lambdas_squared": np.asarray(LAMBDAS_SQUARED, dtype=float).tolist(),
        "spread": int(SPREAD),
        "spread_weights": [float(w) for w in SPREAD_WEIGHTS],
        "polish": int(POLISH),
        "polish_nfev": int(POLISH_NFEV),
        "scales": np.asarray(SCALES, dtype=float).tolist(),
        "population": int(POPULATION),
        "add_moves": int(ADD_MOVES),
    }


def _plain(topo: Topology, x0) -> dict:
    """A topology and a sketch as plain data (sent to the workers)."""
    return {
        "n": topo.n,
        "edges": topo.edges.tolist(),
        "fixed": topo.fixed.tolist(),
        "motor": list(topo.motor),
        "target": topo.target,
        "x0": np.asarray(x0, dtype=float).tolist(),
    }


def _low_end(library: Library, target, count: int = LOW_END) -> list:
    """The ``count`` closest library entries at the front's low end: (topology, sketch scaled to the target's size).

    Retrieval ranks entries by shape, whatever their material, and the
    refinements from there rarely come down to the least material a linkage
    can have: on challenge curve 1 the front jumped from the crank tip
    (distance 0.587, material 0.38) to four-bars of material 1.5.  Here
    every entry of five to :data:`LOW_END_JOINTS` joints is scaled to the
    target's RMS radius and scored (fast distance); of those with material
    at most :data:`LOW_END_MATERIAL` RMS radii, the non-dominated ones, the
    ``count`` closest.  Deterministic: no draw.
    """
    rms = _target_rms(target)
    rows = []
    for t, topo in enumerate(library.topologies):
        ents = np.flatnonzero(library.entry_topology == t)
        if not 5 <= topo.n <= LOW_END_JOINTS or not ents.size:  # (a crank tip is a circle: see _crank_tips)
            continue
        x0 = np.stack([library.sketches[int(e)] for e in ents]) * (rms / library.rms[ents])[:, None, None]
        d, m = evaluate(topo, x0, target)
        ok = np.isfinite(d) & (d < MAX_DISTANCE) & (m <= LOW_END_MATERIAL * rms)
        rows += [(float(d[i]), float(m[i]), int(ents[i]), topo, x0[i]) for i in np.flatnonzero(ok)]
    if not rows:
        return []
    keep = _nondominated(np.array([r[0] for r in rows]), np.array([r[1] for r in rows]))
    return [(rows[i][3], rows[i][4]) for i in keep[:count]]


def _gap_tasks(res: list, count: int = GAPS) -> list:
    """Refinements that fill the ``count`` largest gaps of the front of ``res``: ``(design, material weight)`` each.

    Between neighbours ``(d1, m1)`` and ``(d2, m2)`` of the front (``d1 <
    d2``, ``m1 > m2``) the rectangle ``(d2 - d1) (m1 - m2)`` is left
    undominated; the weight that makes the two equally good in the
    refinement's cost (mean gap, the distance over ``2 pi``, plus weight x
    material) is ``w = (d2 - d1) / (2 pi (m1 - m2))``.  The closer end is
    refined with ``w`` times :data:`GAP_FACTORS` (it gives material for
    distance), the other end with the least of them (it takes distance back).
    A crank tip (two joints) is no end: it has no shape to trade.
    Deterministic: no draw.
    """
    d = np.array([r.distance for r in res])
    m = np.array([r.material for r in res])
    ok = np.flatnonzero((d < MAX_DISTANCE) & (m < MAX_MATERIAL))
    if ok.size < 2:
        return []
    front = ok[_nondominated(d[ok], m[ok])]
    rows = []
    for a, b in zip(front[:-1], front[1:]):
        area = (d[b] - d[a]) * (m[a] - m[b])
        if area > 0:
            rows.append((-area, int(a), int(b), (d[b] - d[a]) / (2.0 * math.pi * (m[a] - m[b]))))
    out = []
    for _, a, b, w in sorted(rows)[:count]:
        if res[a].topology["n"] > 2:
            out += [(res[a], w * f) for f in GAP_FACTORS]
        if res[b].topology["n"] > 2:
            out.append((res[b], w * min(GAP_FACTORS)))
    # the foot of each of the highest cliffs (a drop in material over a small step in distance), on distance alone
    cliffs = sorted((-(m[a] - m[b]), int(b)) for a, b in zip(front[:-1], front[1:]) if res[int(b)].topology["n"] > 2)
    out += [(res[b], 0.0) for _, b in cliffs[:CLIFFS]]
    return out


def _weighted_chunk(spec: dict, ks, evals: int, method: str) -> list:
    """Refinements of the spec's entries ``ks`` (a sketch and a material weight each): two designs a task.

    A material-weighted refinement (the mean gap + the entry's weight x
    material) from the entry's sketch, then one on distance alone from
    there; both results are designs (the low-end entries of :func:`_low_end`
    with each of :data:`LOW_END_WEIGHTS`, the ends of :func:`_gap_tasks`).
    A task not reached before the spec's deadline gives none.
    """
    tc = _target(np.asarray(spec["target"], dtype=float))
    out = []
    for k in ks:
        designs = []
        if spec["deadline"] is None or time.monotonic() <= spec["deadline"]:
            s = spec["entries"][k]
            topo = _topology(s["n"], s["edges"], s["fixed"], s["motor"], s["target"])
            td = {key: s[key] for key in ("n", "edges", "fixed", "motor", "target")}
            x0 = np.asarray(s["x0"], dtype=float)
            x, d, m, _ = refine(topo, x0, tc, rounds=4, nfev=30, material_weight=s["weight"])
            x2, d2, m2, _ = refine(topo, x, tc, rounds=3, nfev=30, walk=False)
            designs = [Design(float(a), float(b), td, np.asarray(c).tolist()) for a, b, c in ((d, m, x), (d2, m2, x2))]
        out.append([dd for dd in designs if math.isfinite(dd.distance)])
    return out


def _preselect_chunk(spec: dict, ks, evals: int, method: str) -> list:
    """Short refinements of the retrieved entries ``ks``: ``(k, distance, material, sketch or None, ...)`` each.

    One ``(distance, material, sketch)`` per method of the spec's ``methods``
    (default :data:`LSQ_METHOD`), in that order.  An entry not reached before
    the spec's deadline (half the time limit) has ``None`` sketches; the
    first entry is always refined, so that a start exists.
    """
    tc = _target(np.asarray(spec["target"], dtype=float))
    out = []
    for k in ks:
        if k and spec["deadline"] is not None and time.monotonic() > spec["deadline"]:
            out.append((k,) + (math.inf, math.inf, None) * len(spec.get("methods", [LSQ_METHOD])))
            continue
        s = spec["entries"][k]
        topo = _topology(s["n"], s["edges"], s["fixed"], s["motor"], s["target"])
        x = np.asarray(s["x0"], dtype=float)
        row = [k]
        for meth in spec.get("methods", [LSQ_METHOD]):
            x1, d1, m1, _ = refine(topo, x, tc, rounds=3, nfev=15, walk=False, method=meth)
            row += [d1, m1, x1.tolist()]
        out.append(tuple(row))
    return out


@contextlib.contextmanager
def _local_pool(workers, scheduler):
    """A pool of ``workers`` local processes (an int from 2; default :func:`default_workers`), else None.

    Python threads share one interpreter lock, and the search's arrays are
    small (a few hundred points), so threads run it little faster than one;
    processes run it as many times faster as there are free cores.  Each
    task is a pure function of plain data, so the designs are the same for
    any number of processes.

    Each process runs its linear algebra on one thread (:data:`THREAD_VARIABLES`
    set to 1 while the pool lives, so the processes it starts inherit them;
    a value the user set is kept): the least-squares steps are small, and
    two processes each threading OpenBLAS over two cores ran curve 5 of the
    challenge in 75 s instead of 45 s.
    """
    n = default_workers() if workers is None and scheduler is None else workers
    if scheduler is not None or isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        yield None
        return
    import multiprocessing
    import os
    from concurrent.futures.process import BrokenProcessPool

    saved = {v: os.environ.get(v) for v in THREAD_VARIABLES}
    os.environ.update({v: "1" for v, old in saved.items() if old is None})
    pool = _Pool(min(int(n), MAX_PROCESSES), mp_context=multiprocessing.get_context("spawn"))
    try:
        yield pool
    except BrokenProcessPool:
        raise GearleverError(
            "workers: the worker processes could not start (a script calling synthesize_curve needs "
            "`if __name__ == '__main__':`; or pass workers=1)"
        ) from None
    finally:
        pool.shutdown(wait=False, cancel_futures=True)
        for v, old in saved.items():
            if old is None:
                os.environ.pop(v, None)


class _PerStart:
    """A pool whose ``map`` runs each start of a chunk as its own task, the largest linkages first.

    The driver hands chunks of two starts; a chunk's result is the list of
    its starts' results, so running the starts one by one and joining them
    gives the same lists (the same designs).  Taken one at a time, largest
    first (``cost``: the start's joints), the processes share the work as
    it comes: challenge curve 1's starts took 6 to 22 CPU seconds, and fixed
    pairs kept one process busy 51 s against 45 s balanced.
    """

    def __init__(self, pool, cost):
        self.pool, self.cost = pool, list(cost)

    def map(self, fn, chunks):
        chunks = [list(c) for c in chunks]
        flat = [k for c in chunks for k in c]
        futures = {k: self.pool.submit(fn, [k]) for k in sorted(flat, key=lambda k: (-self.cost[k], k))}
        for c in chunks:
            yield [x for k in c for x in futures[k].result()]


def default_workers() -> int:
    """Local processes of a search when ``workers`` is not given: the cores this process may use, at most 2."""
    import os

    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(MAX_DEFAULT_WORKERS, cores))


#: Radii of the crank-tip designs, in RMS radii of the target.
CRANK_TIP_RADII = np.geomspace(0.05, 2.0, 80)


def _crank_tips(target) -> list[Design]:
    """Two-joint designs (a crank whose tip is traced: a circle) of :data:`CRANK_TIP_RADII`, scored.

    A circle is often close enough to a closed target, at the least material
    of any design (twice the radius): these seed the low-material end of the
    front so that it is never empty when a circle is feasible.
    """
    rms = _target_rms(target)
    r = CRANK_TIP_RADII * rms
    x0 = np.zeros((r.size, 2, 2))
    x0[:, 1, 0] = r
    topo = _topology(2, [[0, 1]], [0], (0, 1), 1)
    d, m = evaluate(topo, x0, target, keep=None)
    td = {"n": 2, "edges": [[0, 1]], "fixed": [0], "motor": [0, 1], "target": 1}
    return [Design(float(a), float(b), td, x.tolist()) for a, b, x in zip(d, m, x0) if math.isfinite(a)]


def _score_linkage(lk, user_target, scoring: str, k: float) -> tuple[float, float]:
    """The scoring's distance to the user's target and material (``k`` x the material) of a linkage."""
    from gearlever.mechanism.linkage import solve_plan
    from gearlever.synthesis.curve.score import score_distance

    x = simulate(lk.x0[None], solve_plan(lk))[:, lk.target_joint]
    return float(score_distance(x, user_target, scoring)[0]), float(material(lk.x0[None], lk.edges)[0]) * k


def _to_target_frame(lk, target, centre, k: float, rotate: bool = True):
    """The linkage moved onto the target's frame, and its transform ``(rotation, scale, tx, ty)``.

    ``target`` is the search's target (the user's moved by ``-centre`` and
    scaled by ``k``); the best alignment of the distance (cyclic shift,
    direction, least-squares rotation ``R`` about the curves' means ``c`` and
    ``t``) maps a sketch point ``p`` to ``t + R (p - c)`` there, so to
    ``centre + (t + R (p - c)) / k`` in the user's frame.  Without
    ``rotate`` (the challenge's scoring) ``R`` is the identity: the crank's
    angles are absolute, so a turned linkage is sampled at other phases of its
    motion and scores differently (0.01 to 0.11 worse for exact recoveries
    turned by 0.3 to 2 rad); a translated or scaled one scores the same.
    """
    from gearlever.mechanism.linkage import solve_plan
    from gearlever.synthesis.curve.score import _alignment_indices

    curve = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint]
    theta = 0.0
    if rotate:
        cz, tz = normalise(curve[None], target)
        n = tz.shape[0]
        C = cz[0][_alignment_indices(n)]
        z = (tz * np.conj(C)).sum(-1)
        rot = np.exp(1j * np.angle(z))
        a = int(np.argmin(np.abs(tz - rot[:, None] * C).mean(-1)))
        theta = float(np.angle(z[a]))
    c = resample(curve[None], RESOLUTION)[0].mean(0)
    t = resample(np.asarray(target, dtype=float)[None], RESOLUTION)[0].mean(0)
    R = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    scale = 1.0 / k
    shift = np.asarray(centre, dtype=float) + scale * (t - R @ c)
    if theta:
        # a turned linkage is sampled at other phases of its crank, so its resampled centre moves a little:
        # translated once more (a translation samples it at the same phases) onto the target's centre
        turned = simulate((scale * (lk.x0 @ R.T) + shift)[None], solve_plan(lk))[0, lk.target_joint]
        drift = (np.asarray(centre, dtype=float) + scale * t) - resample(turned[None], RESOLUTION)[0].mean(0)
        if np.isfinite(drift).all():  # (a linkage that locks once turned is dropped by its score)
            shift = shift + drift
    x = scale * (lk.x0 @ R.T) + shift
    moved = linkage_from_dict(
        {
            "x0": x.tolist(),
            "edges": lk.edges.tolist(),
            "fixed_joints": lk.fixed_joints.tolist(),
            "motor": list(lk.motor),
            "target_joint": lk.target_joint,
        }
    )
    return moved, (theta, scale, float(shift[0]), float(shift[1]))


def _example() -> tuple:
    """The tiny problem of the curve synthesis: an egg-shaped closed curve, a library of 600 mechanisms."""
    t = np.linspace(0, 2 * np.pi, 120)
    egg = np.stack([0.3 * np.cos(t) * (1 + 0.2 * np.sin(t)), 0.24 * np.sin(t)], -1)
    return (egg,), {"library_size": 600, "designs": 20, "use_cache": False}


register(
    Kind(
        "curve",
        "topology",
        "linkage topology and dimensions tracing a closed curve: library retrieval, refinement, NSGA-II front",
        "gearlever.synthesis.curve.search:synthesize_curve",
        kind_arg=None,
        min_budget=MIN_BUDGET,
        example=_example,
    )
)
