"""The driver of law synthesis: seeded starts on dask for each kind of the registry, polish, result.

Pure numpy and scipy (dask through :mod:`gearlever.synthesis._dask`).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass, field

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.synthesis.driver import check_budget, multistart
from gearlever.synthesis.law._core import KINDS, MIN_BUDGET, SAMPLES, LawProblem, LawTarget, kind_class, law_target
from gearlever.synthesis.path import n_starts

__all__ = [
    "LawSynthesis",
    "synthesize_law",
    "target_of_law",
    "search_problem",
    "DEFAULT_BUDGET",
    "MAX_BUDGET",
    "REPORT_SAMPLES",
]

#: Evaluations per kind, searches and polishes together (:func:`budget_split`): the starts' searches get
#: 400 000 of it, as when the polishes were counted apart.
DEFAULT_BUDGET = 800_000
#: Default bound of the transmission angle, degrees (a linkage near a toggle is no design).
MIN_TRANSMISSION_DEG = 20.0
#: Lawson rounds of the final polish of the best start (each start has 25).
FINAL_ROUNDS = 100
#: Largest budget accepted (the smallest is :data:`~gearlever.synthesis.law._core.MIN_BUDGET`).
MAX_BUDGET = 10**7
#: Law inputs at which the result is measured (a tenth of a degree apart).
REPORT_SAMPLES = 3600


def target_of_law(law, samples: int = SAMPLES, dwell_weight: float | None = None) -> LawTarget:
    """The :class:`LawTarget` of a :class:`gearlever.laws.MotionLaw`: ``samples`` inputs evenly over the turn.

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("angle", "deg", [{"to": 120, "motion": "dwell"},
    ...     {"to": 240, "motion": "cycloidal", "rise": 45}, {"to": 360, "motion": "345", "rise": -45}])
    >>> t = target_of_law(law)
    >>> t.theta.size, t.motions, round(math.degrees(t.scale), 6)
    (360, ('dwell', 'cycloidal', '345'), 45.0)
    """
    from gearlever.synthesis.law._core import DWELL_WEIGHT

    th = np.linspace(0.0, 2 * math.pi, int(samples), endpoint=False)
    val = law.evaluate(th)
    return law_target(
        th,
        val.s,
        val.v,
        val.a,
        output=law.output,
        units=law.units,
        breaks=law.breaks,
        motions=law.motions,
        net=law.net_change(),
        dwell_weight=DWELL_WEIGHT if dwell_weight is None else dwell_weight,
    )


def _target_spec(t: LawTarget) -> dict:
    return {
        "theta": t.theta.tolist(),
        "s": t.s.tolist(),
        "v": t.v.tolist(),
        "a": t.a.tolist(),
        "output": t.output,
        "units": t.units,
        "breaks": t.breaks.tolist(),
        "motions": list(t.motions),
        "net": t.net,
        "dwell_weight": float(t.weight.max()) if np.any(t.weight != 1.0) else 1.0,
    }


def _target_of(spec: dict) -> LawTarget:
    return law_target(
        spec["theta"],
        spec["s"],
        spec["v"],
        spec["a"],
        output=spec["output"],
        units=spec["units"],
        breaks=spec["breaks"],
        motions=spec["motions"],
        net=spec["net"],
        dwell_weight=spec["dwell_weight"],
    )


def make_problem(spec: dict) -> LawProblem:
    """The :class:`LawProblem` of a spec (plain data: kind, target, bounds, the polish's cap)."""
    return LawProblem(
        spec["kind"],
        _target_of(spec["target"]),
        spec["min_transmission"],
        tuple(spec["teeth"]),
        dwell_tolerance=spec.get("dwell_tolerance"),
    )


class LawSearch:
    """A law problem as the driver's :class:`~gearlever.synthesis.driver.Problem`.

    The search runs in the kind's reduced box (:meth:`LawKind.search_box`,
    :meth:`LawKind.search_sample`, :meth:`LawProblem.search_objective`); the
    polish takes the search's best to the full design vector and runs the
    minimax polish of :class:`LawProblem`: ``polish(z, rounds) -> (z, objective, {"offset": off})``.
    """

    @property
    def evaluations(self) -> int:
        return self.pb.evaluations

    def sample(self, rng, m):
        return self.pb.kind.search_sample(rng, m)

    def objective(self, Z):
        return self.pb.search_objective(Z)

    def __init__(self, pb: LawProblem, polish_cap: int | None = None):
        self.pb = pb
        self.lo, self.hi = pb.kind.search_box()
        self.polish_cap = polish_cap

    def polish(self, z, rounds=None) -> tuple:
        """``(z, objective, {"offset": off})``: the minimax polish (its default rounds) of the full vector of ``z``.

        The polish spends at most ``polish_cap`` evaluations (the spec's ``polish_cap``).
        """
        if self.polish_cap is not None:
            self.pb.cap = self.pb.evaluations + int(self.polish_cap)
        full = self.pb.kind.to_full(np.asarray(z)[None, :])[0]
        z, off, f = self.pb.polish(full) if rounds is None else self.pb.polish(full, rounds=rounds)
        return np.asarray(z), f, {"offset": off}


def _search_problem(spec: dict) -> LawSearch:
    return LawSearch(make_problem(spec), spec.get("polish_cap"))


def search_problem(spec: dict):
    """A picklable factory of fresh :class:`LawSearch` problems of a spec (one per start of the driver)."""
    return functools.partial(_search_problem, spec)


@dataclass(frozen=True)
class LawSynthesis(Result):
    """A mechanism synthesized for a law, measured over one turn.

    Attributes
    ----------
    kind : str
    z : ndarray
        Design variables (:attr:`~gearlever.synthesis.law._core.LawKind.names`).
    offset : float
        Output zero of the fit: the law's output is the kind's generated output plus ``offset``.
    theta, target, achieved, error : ndarray (REPORT_SAMPLES,)
        Law input (radians), wanted and achieved output, ``achieved - target``.
    objective : float
        Weighted maximum error over the search samples (dwell samples weigh more).
    feasible : bool
    transmission_range : tuple
        Radians.
    details : dict
        Lengths, teeth, branch of the design.
    evaluations, seed, starts : int
        ``evaluations`` counts every evaluation of the searches and the polishes, at most ``budget`` per kind
        tried.
    tried : dict
        Kind -> objective of each kind searched (``auto``), None where none was feasible.
    not_tried : dict
        Kind -> why it gave no design (``auto``): the law it cannot give (not searched), or no design within
        the constraints (searched: a key of ``spent``).
    dwell_tolerance : float or None
        The bound on the output's excursion over each dwell (output units), if one was set.
    budget : int
        Evaluations allowed per kind.
    spent : dict
        Kind -> evaluations it spent (each at most ``budget``).
    law_target : LawTarget
        The law asked for, as sampled (:func:`~gearlever.synthesis.law.law_target`); :attr:`target` is it
        over the report's samples.

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.synthesis.law import law_target
    >>> th = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    >>> res = synthesize_law(law_target(th, np.radians(20) * np.sin(th)), budget=3000, workers=1)
    >>> res.kind, res.feasible, res.theta.shape == res.error.shape
    ('fourbar', True, True)
    """

    kind: str
    z: np.ndarray
    offset: float
    theta: np.ndarray
    target: np.ndarray
    achieved: np.ndarray
    error: np.ndarray
    objective: float
    feasible: bool
    transmission_range: tuple
    details: dict
    evaluations: int
    seed: int
    starts: int
    seconds: float = field(default=0.0, compare=False)
    tried: dict = field(default_factory=dict)
    law_target: LawTarget = field(default=None, compare=False, repr=False)
    not_tried: dict = field(default_factory=dict)
    dwell_tolerance: float | None = None
    budget: int = 0
    spent: dict = field(default_factory=dict)

    def model(self) -> dict:
        """Model dict sketched at law input 0 (output link ``output``)."""
        return kind_class(self.kind)(self.law_target).model(self.z, self.offset)

    def achieved_at(self, theta) -> np.ndarray:
        """The achieved output (with the fit's zero) at law inputs ``theta`` (closed form)."""
        G, _ = kind_class(self.kind)(self.law_target).generate(self.z[None, :], np.asarray(theta, dtype=float))
        return G[0] + self.offset


def _dense(target: LawTarget, law) -> tuple:
    th = np.linspace(0.0, 2 * math.pi, REPORT_SAMPLES, endpoint=False)
    if law is None:
        # periodic interpolation of the target's samples (with the net change removed)
        drift = target.s - target.net * target.theta / (2 * math.pi)
        want = np.interp(th, target.theta, drift, period=2 * math.pi) + target.net * th / (2 * math.pi)
    else:
        want = law(th)
    return th, want


def synthesize_law(
    target: LawTarget,
    *,
    kind: str = "fourbar",
    seed: int = 0,
    budget: int = DEFAULT_BUDGET,
    workers: int | None = None,
    scheduler: str | None = None,
    min_transmission: float = math.radians(MIN_TRANSMISSION_DEG),
    teeth=(17, 120),
    method: str = "de",
    progress=None,
    law=None,
    dwell_tolerance: float | None = None,
) -> LawSynthesis:
    """Synthesize a mechanism of ``kind`` (or every kind: ``"auto"``) whose output follows ``target``.

    Parameters
    ----------
    target : LawTarget or gearlever.laws.MotionLaw
        The law sampled over a turn (:func:`~gearlever.synthesis.law.law_target`), or the law itself
        (sampled by :func:`target_of_law`; the error is then measured against it).
    kind : str
        A law kind of the registry (:func:`gearlever.synthesis.kinds` ``("law")``) or ``"auto"`` (all, the
        best kept).
    seed, budget : int
        The result is fixed by them: start ``k`` draws from ``default_rng([seed, k])``.  ``budget`` caps the
        evaluations of each kind, searches and polishes together.
    workers, scheduler
        Local dask threads (an int), a map-like, or a dask.distributed scheduler address (see
        :func:`gearlever.synthesis.driver.multistart`; the result does not depend on them).
    min_transmission : float
        Smallest transmission angle over the turn, radians, ``0 <= . < pi/2`` (default
        :data:`MIN_TRANSMISSION_DEG` degrees).
    teeth : (int, int)
        Bounds of gear teeth.
    law : callable, optional
        Wanted output at any law input (radians) for the measured error; default: the samples interpolated.
    dwell_tolerance : float, optional
        Largest excursion (peak to peak) of the output over each dwell segment, output units (radians for an
        angle law): a constraint of every kind; a design that breaks it is never returned.

    Returns
    -------
    LawSynthesis

    Notes
    -----
    Global search by differential evolution (Storn and Price 1997) in
    :func:`~gearlever.synthesis.path.n_starts` seeded starts (set by the
    budget and the variables, never by the workers), each polished by the
    minimax polish of :class:`~gearlever.synthesis.law._core.LawProblem`;
    starts are reduced by (objective, start index)
    (:func:`gearlever.synthesis.driver.multistart`) and the best is polished
    further.  The budget is a cap: of each kind's ``budget``,
    :data:`SEARCH_SHARE` goes to the starts' searches, :data:`POLISH_SHARE`
    to their polishes and the rest to the final polish; ``evaluations``
    counts them all (a complex-step Jacobian as one evaluation per
    variable), at most ``budget`` per kind tried.

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.synthesis.law import law_target
    >>> th = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    >>> res = synthesize_law(law_target(th, np.radians(20) * np.sin(th)), kind="fourbar", budget=3000, workers=1)
    >>> bool(np.degrees(np.abs(res.error).max()) < 1.0), res.evaluations <= 3000
    (True, True)
    """
    if not isinstance(target, LawTarget):  # a MotionLaw
        motion_law = target
        target = target_of_law(motion_law)
        if law is None:
            law = lambda th: motion_law.evaluate(th).s  # noqa: E731

    if kind != "auto" and kind not in KINDS:
        raise GearleverError(f"kind must be one of {', '.join(KINDS)}, auto; got {kind!r}")
    if not (math.isfinite(min_transmission) and 0 <= min_transmission < math.pi / 2):
        raise GearleverError(f"min_transmission must be 0 <= . < pi/2 radians, got {min_transmission!r}")
    budget = check_budget("budget", budget, MIN_BUDGET, MAX_BUDGET)
    if dwell_tolerance is not None:
        dwell_tolerance = float(dwell_tolerance)
        LawProblem(next(iter(KINDS)), target, dwell_tolerance=dwell_tolerance)  # the bound's refusals
    kinds = list(KINDS) if kind == "auto" else [kind]
    usable = []
    reasons = {}
    for kd in kinds:
        try:
            KINDS[kd](target, teeth).check()
            usable.append(kd)
        except GearleverError as exc:
            if kind != "auto":
                raise
            reasons[kd] = str(exc)
    if not usable:
        raise GearleverError("no kind can give this law: " + "; ".join(f"{k}: {v}" for k, v in reasons.items()))
    t0 = time.perf_counter()
    spec_target = _target_spec(target)
    best, tried, spent, failed = None, {}, {}, {}
    for kd in usable:
        spec = {
            "kind": kd,
            "target": spec_target,
            "min_transmission": float(min_transmission),
            "teeth": [int(teeth[0]), int(teeth[1])],
            "dwell_tolerance": dwell_tolerance,
        }
        pb = make_problem(spec)
        starts, per, cap = budget_split(budget, pb.kind.search_box()[0].size)
        spec["polish_cap"] = cap
        results = multistart(
            search_problem(spec),
            starts,
            seed,
            budget=starts * per,
            workers=workers if scheduler is None else scheduler,
            progress=progress,
            method=method,
        )
        used = sum(s.evaluations + s.polish_evaluations for s in results)
        top = results[0]
        if top.x is None or not math.isfinite(top.objective):
            tried[kd], spent[kd] = None, used
            failed[kd] = _why_none(min_transmission, dwell_tolerance, target)
            continue
        f, z, off = top.objective, top.x, top.info["offset"]
        # the best start polished further with what is left of the budget (after the reduction: the same
        # for any workers)
        pb.cap = budget - used
        z2, off2, f2 = pb.polish(np.asarray(z), rounds=FINAL_ROUNDS)
        if f2 < f:
            z, off, f = z2, off2, f2
        spent[kd] = used + pb.evaluations
        res = _result(pb, np.asarray(z), off, f, seed, starts, law)
        tried[kd] = res.objective
        if best is None or res.objective < best.objective:
            best = res
    if best is None:
        raise GearleverError(
            "no buildable mechanism found within the constraints ("
            + "; ".join(f"{k}: {v}" for k, v in failed.items())
            + ")"
        )
    from dataclasses import replace

    tried.update({k: None for k in reasons})
    return replace(
        best,
        evaluations=sum(spent.values()),
        seconds=time.perf_counter() - t0,
        tried=tried,
        not_tried={**reasons, **failed},
        dwell_tolerance=dwell_tolerance,
        budget=budget,
        spent=spent,
    )


#: Shares of a kind's budget: the starts' global searches, their polishes; the rest is the final polish's.
SEARCH_SHARE = 0.5
POLISH_SHARE = 0.25
#: Least evaluations of one start's polish (it measures its start and its output zero first).
MIN_POLISH = 2


def budget_split(budget: int, d: int) -> tuple:
    """``(starts, search, polish)``: the starts and each one's search and polish evaluations within ``budget``.

    The starts' searches get :data:`SEARCH_SHARE` of the budget, their polishes :data:`POLISH_SHARE` (at
    least :data:`MIN_POLISH` each); the final polish of the best start gets what they leave.

    >>> budget_split(400_000, 9), budget_split(100, 4)
    ((32, 6250, 3125), (8, 6, 3))
    """
    starts = n_starts(budget, d)
    polish = max(int(POLISH_SHARE * budget) // starts, MIN_POLISH)
    search = max(min(int(SEARCH_SHARE * budget) // starts, budget // starts - polish), 1)
    return starts, search, polish


def _why_none(min_transmission: float, dwell_tolerance, target: LawTarget) -> str:
    why = f"no design within the constraints (transmission angle at least {math.degrees(min_transmission):.6g} deg"
    if dwell_tolerance is not None:
        tol = math.degrees(dwell_tolerance) if target.output == "angle" else dwell_tolerance
        why += f", dwell excursion at most {tol:.6g}" + (" deg" if target.output == "angle" else f" {target.units}")
    return why + ")"


def _result(pb: LawProblem, z, off, f, seed, starts, law) -> LawSynthesis:
    t = pb.target
    th, want = _dense(t, law)
    G, ok = pb.kind.generate(z[None, :], th)
    ach = G[0] + off
    mn, mx = pb.kind.transmission(z[None, :])
    return LawSynthesis(
        kind=pb.kind.name,
        z=z,
        offset=float(off),
        theta=th,
        target=want,
        achieved=ach,
        error=ach - want,
        objective=float(f),
        feasible=bool(ok[0] and pb.feasible(z)[0]),
        transmission_range=(float(mn[0]), float(mx[0])),
        details=pb.kind.details(z),
        evaluations=0,
        seed=int(seed),
        starts=int(starts),
        law_target=t,
    )
