"""Path generation: the driver of every linkage kind, a seeded global search on dask and a polish.

:func:`synthesize_path` finds a linkage whose traced point passes through
target points.  It knows no linkage by name: the kinds are those of the
registry :mod:`gearlever.synthesis.path_kinds` (``fourbar``,
:mod:`~gearlever.synthesis.path_fourbar`, whose formulation, after Cabrera,
Simon and Prado, "Optimal synthesis of mechanisms with genetic algorithms",
Mech. Mach. Theory 37 (2002) 1165-1177, is in its docstring;
``geared-fivebar``, :mod:`~gearlever.synthesis.fivebar`; ``sixbar``,
:mod:`~gearlever.synthesis.sixbar`), each giving the problem (search space,
exact constraints, objective, polish), the result and the model writer;
``auto`` tries them in the registry's order, and ``KINDS`` (read from the
registry) lists them and ``auto``.  The four-bar problem
(:class:`FourBarPathProblem`) and the result (:class:`PathSynthesis`) are
also importable from here; the four-bar's limits and private helpers are in
:mod:`~gearlever.synthesis.path_fourbar`.

Search of the four-bar (measured by ``benchmarks/bench_synthesis.py`` on the cases of
``gearlever/data/path_benchmarks.toml``, 2-core machine, budget 200 000
evaluations split into :func:`n_starts` starts (32 here), the same polish;
median final objective over seeds 0, 1, 2 and median wall time with 2
threads; "published" is the objective of the best published design of the
case that lies in the same constraint set, recomputed from the design:
Acharyya and Mandal, Mech. Mach. Theory 44 (2009) 1784-1794, for the line;
Cabrera, Simon and Prado (2002) for the five-point and eighteen-point cases;
Lin, Mech. Mach. Theory 45 (2010) 1096-1107, for the ellipse):

=========================  ============  ============  ============  ======  ======
case                       DE            CMA-ES        published     DE s    CMA s
=========================  ============  ============  ============  ======  ======
line6                      8.83524e-28   4.47668e-09   0.0150647     13.9    15.6
five_points_timed          7.41575e-07   7.41575e-07   1.82703e-06   4.1     5.5
kunjur_closed18_timed      0.00979883    0.00979883    0.033748      6.2     10.9
ellipse10                  0.000401992   0.000401992   0.000401992   10.0    14.1
=========================  ============  ============  ============  ======  ======

The ellipse's tenth target repeats the first, a full crank turn later:
:func:`synthesize_path` searches a four-bar on the nine distinct targets with
the first weighted twice (the objective Lin's design minimizes) and meets the
tenth at the first one's crank angle plus 2 pi (the crank-rocker repeats its
pose); its result, 4.0199205e-4, is just below Lin's design (4.0199219e-4).
On that case each start lands in the best basin about 1 time in 8, with
6 250 evaluations as with 25 000, which is why the budget goes to many
short starts rather than a few long ones (with 8 starts of 25 000, seed 0
ended at 4.53e-4).

Differential evolution (:func:`gearlever.synthesis._search.differential_evolution`)
is the default: it was better on the line, equal on the other three cases
and faster on all four, and its one-to-one selection keeps the population
feasible (a rejected infeasible trial costs only its evaluation), where CMA-ES ranks
infeasible samples last and loses them.  Each start's best
is then polished by :func:`scipy.optimize.least_squares` with the analytic
Jacobian of the coupler point (:meth:`FourBarPathProblem.jacobian`, checked
against finite differences in the tests).

Pure numpy and scipy.
"""

from __future__ import annotations

import math
import time

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis import path_kinds
from gearlever.synthesis.path_fourbar import FourBarPathProblem, _targets
from gearlever.synthesis.path_kinds import PathSynthesis

__all__ = [
    "FourBarPathProblem",
    "PathSynthesis",
    "synthesize_path",
    "n_starts",
    "population",
    "min_budget",
    "DEFAULT_BUDGET",
    "MAX_BUDGET",
]

#: Candidate evaluations by default (all starts together).
DEFAULT_BUDGET = 200_000
#: Most candidate evaluations: an evaluation costs ~0.1-2 us per target, so
#: 10^7 of them on 18 targets take about a minute per core.
MAX_BUDGET = 10**7
#: Fewest independent starts (each a seeded DE run, then a polish).
STARTS = 8
#: Most independent starts.
MAX_STARTS = 32
#: Evaluations per search variable that one start needs to settle into a basin:
#: a budget that allows more starts of at least this size is split into more
#: starts (on the ellipse case each four-bar start lands in the best basin with
#: about the same chance, 1 in 8, at 6 250 evaluations as at 25 000).
START_EVALS_PER_VAR = 625
#: ``auto`` stops at the first type whose objective is below this fraction of the targets' size squared.
AUTO_GOOD = 1e-12


def __getattr__(name):
    # KINDS: the linkage types of :func:`synthesize_path`, read from the registry each time (so a kind
    # registered later is one of them): the registered kinds in ``auto`` order, then "auto".
    if name == "KINDS":
        return (*path_kinds.names(), "auto")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def run_start(spec: dict, seed: int, k: int, evals: int, method: str = "de") -> tuple:
    """One start: a seeded global search (``default_rng([seed, k])``) and its polish.

    Returns ``(objective, k, w, sigma, evaluations)`` (the candidate
    evaluations of the global search, at most ``evals``; the polish's are not
    counted); the same for the same arguments on any machine, thread or process.
    """
    from gearlever.synthesis import _search

    pb = make_problem(spec)
    rng = np.random.default_rng([seed, k])
    pop = population(pb.d)
    if method == "de":
        z, _, _ = _search.differential_evolution(pb.objective, pb.lo, pb.hi, rng, budget=evals, pop=pop, init=pb.sample)
    elif method == "cma":
        z, _, _ = _search.cma_es(pb.objective, pb.lo, pb.hi, rng, budget=evals, pop=pop, init=pb.sample)
    else:
        raise GearleverError(f"method must be 'de' or 'cma', got {method!r}")
    searched = pb.evaluations  # the global search's candidate evaluations (at most ``evals``); the polish is apart
    if z is None:
        return (math.inf, k, None, 1.0, searched)
    sigma = float(pb.mode_of(z[None, :])[0])
    w = pb.to_w(z)
    w, fw = pb.polish(w, sigma)
    return (fw, k, w, sigma, searched)


def make_problem(spec: dict):
    """The problem object of a spec (``kind``, a registered kind, default "fourbar", then the problem's arguments).

    Examples
    --------
    >>> make_problem({"kind": "sixbar", "targets": [[0, 0], [1, 0], [2, 1]]}).d
    16
    """
    spec = dict(spec)
    kind = spec.pop("kind", "fourbar")
    if kind not in path_kinds.names():
        raise GearleverError(f"kind must be one of {', '.join(_kinds())}, got {kind!r}")
    return path_kinds.get(kind).make_problem(**spec)


def _kinds() -> tuple:
    """The ``kind`` values of :func:`synthesize_path`: the registered kinds in ``auto`` order, then ``auto``."""
    return (*path_kinds.names(), "auto")


def run_chunk(spec: dict, seed: int, ks, evals: int, method: str = "de") -> list:
    """:func:`run_start` for each start in ``ks`` (one dask task)."""
    return [run_start(spec, seed, k, evals, method) for k in ks]


def population(d: int) -> int:
    """Population of one start's search over ``d`` variables: ``max(24, 6 d)``."""
    return max(24, 6 * int(d))


def min_budget(d: int) -> int:
    """Fewest evaluations a search over ``d`` variables accepts: :data:`STARTS` starts of one population each.

    A smaller budget could not even evaluate every start's first population,
    so it is refused naming this number rather than overrun.

    >>> min_budget(10)
    480
    """
    return STARTS * population(d)


def n_starts(budget: int, d: int) -> int:
    """Independent starts of a search of ``budget`` evaluations over ``d`` variables.

    :data:`STARTS` to :data:`MAX_STARTS`, as many as give each start at least
    :data:`START_EVALS_PER_VAR` evaluations per variable; it depends on the
    problem alone, so a seed gives the same result on any number of workers.

    Examples
    --------
    >>> n_starts(200_000, 10), n_starts(4000, 10), n_starts(10**7, 16)
    (32, 8, 32)
    """
    return int(min(MAX_STARTS, max(STARTS, int(budget) // (START_EVALS_PER_VAR * int(d)))))


def default_ranges(targets) -> tuple:
    """Default length and coordinate ranges from the targets' extent ``S`` and centre ``c``.

    Lengths ``[S/20, 5 S]``; coordinates ``[min(c) - 3 S, max(c) + 3 S]``.

    >>> default_ranges([[0, 0], [2, 0], [2, 1]])
    ((0.1, 10.0), (-5.5, 7.0))
    """
    T = np.asarray(targets, dtype=float)
    ext = T.max(axis=0) - T.min(axis=0)
    S = float(max(ext.max(), 1e-12))
    c = (T.max(axis=0) + T.min(axis=0)) / 2
    return (S / 20, 5 * S), (float(c.min() - 3 * S), float(c.max() + 3 * S))


def synthesize_path(
    targets,
    angles=None,
    *,
    timing=None,
    pivot=None,
    ground_angle=None,
    length_range=None,
    coord_range=None,
    kind: str = "fourbar",
    seed: int = 0,
    budget: int = DEFAULT_BUDGET,
    workers: int | None = None,
    scheduler: str | None = None,
    method: str = "de",
    progress=None,
    min_transmission: float | None = None,
) -> PathSynthesis:
    """Synthesize a linkage (a four-bar by default) whose traced point passes through ``targets``.

    A seeded global search on dask, then a least-squares polish, for each
    linkage kind tried (:mod:`gearlever.synthesis.path_kinds`).

    Parameters
    ----------
    targets : array_like (N, 2)
    angles : array_like (N,), optional
        Crank angles at the targets, radians (see :class:`FourBarPathProblem`).
    timing : {"none", "relative", "absolute"}, optional
        Default ``"relative"`` when ``angles`` are given, else ``"none"``.
    pivot, ground_angle, length_range, coord_range, min_transmission
        Constraints (see :class:`FourBarPathProblem`); ranges default to
        :func:`default_ranges`.
    kind : {"fourbar", "geared-fivebar", "sixbar", "auto"}
        Linkage type, a registered kind
        (:func:`gearlever.synthesis.path_kinds.names`); ``"auto"`` tries them
        in the registry's order, the four-bar, then the geared five-bar
        (:mod:`gearlever.synthesis.fivebar`), then the Stephenson six-bar
        (:mod:`gearlever.synthesis.sixbar`), each only while the best so far
        is above :data:`AUTO_GOOD` times the targets' size squared, and keeps
        the best (``tried`` records each type's objective).
    seed : int
        Fixes the result (each start ``k`` draws from ``default_rng([seed, k])``).
    budget : int
        Candidate evaluations of the global search, all starts together (a
        cap: ``evaluations`` of the result never exceeds it, per linkage type
        tried; the least-squares polish of each start is not counted); it is
        split into :func:`n_starts` starts (8 to 32, set by the budget and the
        number of variables, never by the workers).  At least
        :func:`min_budget` (480 for a four-bar without timing), at most
        :data:`MAX_BUDGET`.
    workers : int, optional
        Local dask threads (default: dask's default).
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler instead.
    method : {"de", "cma"}
        Global search (``"cma"`` only for comparison).
    progress : callable, optional
        ``progress(stage, done, total)``.

    Returns
    -------
    PathSynthesis

    Notes
    -----
    The formulation and constraints are those of the kind's module
    (the four-bar's: :mod:`gearlever.synthesis.path_fourbar`, after Cabrera,
    Simon and Prado, Mech. Mach. Theory 37 (2002) 1165-1177);
    starts are reduced by (objective, start index), so the result does not
    depend on ``workers`` or ``scheduler``.

    Examples
    --------
    >>> import numpy as np
    >>> t = [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5]]
    >>> r = synthesize_path(t, length_range=(0.2, 5), coord_range=(-5, 5), budget=4000, workers=1)
    >>> r.grashof, r.feasible, bool(r.objective < 1e-3)
    ('crank-rocker', True, True)
    """
    from gearlever.synthesis._dask import run_starts

    known = _kinds()
    if kind not in known:
        raise GearleverError(f"kind must be one of {', '.join(known)}, got {kind!r}")
    kinds = list(known[:-1]) if kind == "auto" else [kind]
    if timing is None:
        timing = "none" if angles is None else "relative"
    targets = _targets(targets)
    dl, dc = default_ranges(targets)
    base = {
        "targets": targets.tolist(),
        "timing": timing,
        "angles": None if angles is None or timing == "none" else np.asarray(angles, dtype=float).tolist(),
        "pivot": None if pivot is None else [float(v) for v in pivot],
        "ground_angle": ground_angle,
        "length_range": tuple(length_range) if length_range is not None else dl,
        "coord_range": tuple(coord_range) if coord_range is not None else dc,
    }
    if min_transmission is not None:
        takers = [k for k in known[:-1] if "min_transmission" in path_kinds.get(k).options]
        if kind not in takers:
            raise GearleverError(
                f"min_transmission bounds a four-bar's transmission angle only: kind must be "
                f"{' or '.join(repr(k) for k in takers)}, got {kind!r}"
            )
        base["min_transmission"] = min_transmission
    pb = FourBarPathProblem(**base)  # checks the input before any work
    budget = int(budget)
    least = max(min_budget(make_problem({"kind": kd, **base}).d) for kd in kinds)
    if not least <= budget <= MAX_BUDGET:
        raise GearleverError(
            f"budget must be {least}..{MAX_BUDGET} for this problem (at least {STARTS} starts of one "
            f"population each), got {budget}"
        )
    S2 = float(np.sum(np.ptp(pb.targets, axis=0) ** 2))
    # A closed path whose last target repeats the first (a full crank turn): the crank of a
    # crank-rocker is back at the same pose after 2 pi, so the last target is met exactly as
    # well as the first. Search without it (the ccw order within one turn could not place it),
    # then add it back at the first target's crank angle plus one turn.
    closing = (
        kind != "auto"
        and path_kinds.get(kind).closed_path
        and timing == "none"
        and pb.targets.shape[0] >= 4
        and bool(np.array_equal(pb.targets[-1], pb.targets[0]))
    )
    if closing:
        # the first target stands for two (it is met again one turn later): it weighs twice
        n = pb.targets.shape[0] - 1
        base = {**base, "targets": base["targets"][:-1], "weights": [2.0] + [1.0] * (n - 1)}
    t0 = time.perf_counter()
    best_res, tried, evals = None, {}, 0
    for kd in kinds:
        spec = {"kind": kd, **base}
        pk = make_problem(spec)
        starts = n_starts(budget, pk.d)
        per = max(budget // starts, 1)
        # exact starts (distances below 1e-10 of the targets' size) are equal: the first one is kept
        results = run_starts(
            spec, seed, starts, per, method, workers=workers, scheduler=scheduler, progress=progress, tie=1e-20 * S2
        )
        evals += sum(r[4] for r in results)
        best = results[0]
        if best[2] is None:
            tried[kd] = None
            continue
        res = path_kinds.get(kd).result(pk, best[2], best[3], evals, seed, starts, 0.0)
        tried[kd] = res.objective if res.feasible else None
        if res.feasible and (best_res is None or res.objective < best_res.objective):
            best_res = res
        # auto: a type is tried only when the ones before it do not reach the targets
        if kind == "auto" and best_res is not None and best_res.objective <= AUTO_GOOD * S2:
            break
    if best_res is None:
        bounds = "length_range, coord_range" + (", min_transmission" if min_transmission else "")
        raise GearleverError(f"no buildable linkage found within the constraints ({bounds})")
    from dataclasses import replace

    if closing:
        e0 = float(best_res.errors[0])
        best_res = replace(
            best_res,
            targets=pb.targets.copy(),
            traced=np.vstack([best_res.traced, best_res.traced[:1]]),
            errors=np.append(best_res.errors, e0),
            objective=best_res.objective + e0 * e0,
            crank_angles=np.append(best_res.crank_angles, best_res.crank_angles[0] + 2 * math.pi),
            input_angles=np.append(best_res.input_angles, best_res.input_angles[0] + 2 * math.pi),
        )
        tried = {k: (v + e0 * e0 if v is not None else None) for k, v in tried.items()}
    return replace(best_res, evaluations=evals, seconds=time.perf_counter() - t0, tried=tried)
