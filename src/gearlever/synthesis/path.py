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

import functools
import math
import time

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis import path_kinds
from gearlever.synthesis.driver import check_budget, multistart, population
from gearlever.synthesis.path_fourbar import FourBarPathProblem, _targets
from gearlever.synthesis.path_kinds import PathSynthesis

__all__ = [
    "FourBarPathProblem",
    "PathSynthesis",
    "synthesize_path",
    "n_starts",
    "population",
    "search_problem",
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


class PathSearch:
    """A path problem as the driver's :class:`~gearlever.synthesis.driver.Problem`: its box, sampling,
    batched objective and a polish ``polish(z) -> (w, objective, {"mode": sigma})``.

    The search runs over the problem's search vector ``z``; the polish maps
    the search's best to the polish vector ``w`` with its discrete mode
    ``sigma`` (:meth:`FourBarPathProblem.mode_of`, :meth:`FourBarPathProblem.to_w`)
    and polishes it by least squares (:meth:`FourBarPathProblem.polish`).
    """

    def __init__(self, pb):
        self.pb = pb
        self.lo, self.hi = pb.lo, pb.hi

    @property
    def evaluations(self) -> int:
        return self.pb.evaluations

    def sample(self, rng, m):
        return self.pb.sample(rng, m)

    def objective(self, Z):
        return self.pb.objective(Z)

    def polish(self, z, rounds=None) -> tuple:
        """``(w, objective, {"mode": sigma})`` of the search's best ``z`` (the least-squares polish has no rounds)."""
        sigma = float(self.pb.mode_of(z[None, :])[0])
        w, fw = self.pb.polish(self.pb.to_w(z), sigma)
        return w, fw, {"mode": sigma}


def _search_problem(spec: dict) -> PathSearch:
    return PathSearch(make_problem(spec))


def search_problem(spec: dict):
    """A picklable factory of fresh :class:`PathSearch` problems of a spec (one per start of the driver).

    >>> search_problem({"kind": "sixbar", "targets": [[0, 0], [1, 0], [2, 1]]})().lo.size
    16
    """
    return functools.partial(_search_problem, dict(spec))


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
    workers : int, map-like or str, optional
        Local dask threads (default: dask's default), anything with a
        ``.map``, or the address of a running ``dask.distributed`` scheduler
        (see :func:`gearlever.synthesis.driver.multistart`).
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler (the same as ``workers=address``).
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
    known = _kinds()
    if kind not in known:
        raise GearleverError(f"kind must be one of {', '.join(known)}, got {kind!r}")
    kinds = list(known[:-1]) if kind == "auto" else [kind]
    if timing is None:
        timing = "none" if angles is None else "relative"
    base = _base_spec(targets, angles, timing, pivot, ground_angle, length_range, coord_range)
    if min_transmission is not None:
        _check_min_transmission_kind(kind, known)
        base["min_transmission"] = min_transmission
    pb = FourBarPathProblem(**base)  # checks the input before any work
    least = max(min_budget(make_problem({"kind": kd, **base}).d) for kd in kinds)
    budget = check_budget(
        "budget", budget, least, MAX_BUDGET, f"for this problem: at least {STARTS} starts of one population each"
    )
    S2 = float(np.sum(np.ptp(pb.targets, axis=0) ** 2))
    closing = _closes(kind, timing, pb.targets)
    if closing:
        # the first target stands for two (it is met again one turn later): it weighs twice
        n = pb.targets.shape[0] - 1
        base = {**base, "targets": base["targets"][:-1], "weights": [2.0] + [1.0] * (n - 1)}
    t0 = time.perf_counter()
    best_res, tried, evals = _search_kinds(kinds, kind, base, budget, seed, workers, scheduler, progress, method, S2)
    if best_res is None:
        bounds = "length_range, coord_range" + (", min_transmission" if min_transmission else "")
        raise GearleverError(f"no buildable linkage found within the constraints ({bounds})")
    from dataclasses import replace

    if closing:
        best_res, tried = _closed(best_res, pb.targets, tried)
    return replace(best_res, evaluations=evals, seconds=time.perf_counter() - t0, tried=tried)


def _check_min_transmission_kind(kind: str, known: tuple) -> None:
    """Refuses ``min_transmission`` for a kind whose problem does not take it (naming the kinds that do)."""
    takers = [k for k in known[:-1] if "min_transmission" in path_kinds.get(k).options]
    if kind not in takers:
        raise GearleverError(
            f"min_transmission bounds a four-bar's transmission angle only: kind must be "
            f"{' or '.join(repr(k) for k in takers)}, got {kind!r}"
        )


def _closes(kind: str, timing: str, targets) -> bool:
    """A closed path whose last target repeats the first (a full crank turn), for a kind that closes it.

    The crank of a crank-rocker is back at the same pose after 2 pi, so the
    last target is met exactly as well as the first: the search runs without
    it (the counter-clockwise order within one turn could not place it), then
    :func:`_closed` adds it back at the first target's crank angle plus one turn.
    """
    return (
        kind != "auto"
        and path_kinds.get(kind).closed_path
        and timing == "none"
        and targets.shape[0] >= 4
        and bool(np.array_equal(targets[-1], targets[0]))
    )


def _base_spec(targets, angles, timing, pivot, ground_angle, length_range, coord_range) -> dict:
    """The problem arguments shared by every kind tried: targets, timing and the constraints (ranges by default)."""
    targets = _targets(targets)
    dl, dc = default_ranges(targets)
    return {
        "targets": targets.tolist(),
        "timing": timing,
        "angles": None if angles is None or timing == "none" else np.asarray(angles, dtype=float).tolist(),
        "pivot": None if pivot is None else [float(v) for v in pivot],
        "ground_angle": ground_angle,
        "length_range": tuple(length_range) if length_range is not None else dl,
        "coord_range": tuple(coord_range) if coord_range is not None else dc,
    }


def _search_kinds(kinds, kind, base, budget, seed, workers, scheduler, progress, method, S2) -> tuple:
    """``(best feasible result or None, objective per kind tried, evaluations)``: the multistart search of each kind.

    ``auto`` stops at the first kind whose best is within :data:`AUTO_GOOD` of
    the targets' size squared ``S2``.
    """
    best_res, tried, evals = None, {}, 0
    for kd in kinds:
        spec = {"kind": kd, **base}
        pk = make_problem(spec)
        starts = n_starts(budget, pk.d)
        per = max(budget // starts, 1)
        # exact starts (distances below 1e-10 of the targets' size) are equal: the first one is kept
        results = multistart(
            search_problem(spec),
            starts,
            seed,
            budget=starts * per,
            workers=workers if scheduler is None else scheduler,
            progress=progress,
            method=method,
            tie=1e-20 * S2,
        )
        evals += sum(s.evaluations for s in results)
        best = results[0]
        if best.x is None:
            tried[kd] = None
            continue
        res = path_kinds.get(kd).result(pk, best.x, best.info["mode"], evals, seed, starts, 0.0)
        tried[kd] = res.objective if res.feasible else None
        if res.feasible and (best_res is None or res.objective < best_res.objective):
            best_res = res
        # auto: a type is tried only when the ones before it do not reach the targets
        if kind == "auto" and best_res is not None and best_res.objective <= AUTO_GOOD * S2:
            break
    return best_res, tried, evals


def _closed(res: PathSynthesis, targets, tried: dict) -> tuple:
    """The result of a closed path searched without its repeated last target, with that target added back.

    The last target is met at the first one's crank angle plus one turn (the
    crank-rocker repeats its pose), so its error is the first one's.
    """
    from dataclasses import replace

    e0 = float(res.error[0])
    res = replace(
        res,
        target=targets.copy(),
        achieved=np.vstack([res.achieved, res.achieved[:1]]),
        error=np.append(res.error, e0),
        objective=res.objective + e0 * e0,
        crank_angles=np.append(res.crank_angles, res.crank_angles[0] + 2 * math.pi),
        input_angles=np.append(res.input_angles, res.input_angles[0] + 2 * math.pi),
    )
    return res, {k: (v + e0 * e0 if v is not None else None) for k, v in tried.items()}
