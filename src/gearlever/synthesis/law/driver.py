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
from gearlever.synthesis.law._core import KINDS, SAMPLES, LawProblem, LawTarget, law_target
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

#: Candidate evaluations of the global search per kind (all starts together).
DEFAULT_BUDGET = 400_000
#: Default bound of the transmission angle, degrees (a linkage near a toggle is no design).
MIN_TRANSMISSION_DEG = 20.0
#: Lawson rounds of the final polish of the best start (each start has 25).
FINAL_ROUNDS = 100
#: Smallest and largest budget accepted.
MIN_BUDGET = 100
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


def _sine(power: int = 1, **kwargs):
    """A 20 deg sine of the input (to ``power``) sampled at 72 inputs, and the keyword arguments."""

    def make() -> tuple:
        th = np.linspace(0.0, 2 * math.pi, 72, endpoint=False)
        return (law_target(th, math.radians(20) * np.sin(th) ** power),), dict(kwargs)

    return make


def _segments(output: str, units: str, segments: list):
    def make() -> tuple:
        from gearlever.laws import law_from_segments

        return (law_from_segments(output, units, segments),), {}

    return make


#: Dwell, cycloidal rise of 45 deg, 3-4-5 return (a law with a dwell).
DWELL = [
    {"to": 120, "motion": "dwell"},
    {"to": 240, "motion": "cycloidal", "rise": 45},
    {"to": 360, "motion": "345", "rise": -45},
]

#: The tiny problem of each kind (a law it can give): kind -> ``example()`` giving ``(args, kwargs)``.
EXAMPLES = {
    "fourbar": _sine(),
    "slider-crank": _segments(
        "displacement",
        "mm",
        [{"to": 180, "motion": "harmonic", "rise": 40}, {"to": 360, "motion": "harmonic", "rise": -40}],
    ),
    "geared-fourbar": _segments("angle", "deg", DWELL),
    "sixbar-dwell": _segments("angle", "deg", DWELL),
    "gear-lever": _sine(2, teeth=(20, 40)),
}


def example(kind: str):
    """The tiny problem of law kind ``kind``: ``example()`` gives ``(args, kwargs)`` of :func:`synthesize_law`.

    >>> args, kwargs = example("gear-lever")()
    >>> args[0].theta.size, kwargs
    (72, {'teeth': (20, 40)})
    """
    return EXAMPLES.get(kind, _sine())


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
    """The :class:`LawProblem` of a spec (plain data: kind, target, bounds)."""
    return LawProblem(spec["kind"], _target_of(spec["target"]), spec["min_transmission"], tuple(spec["teeth"]))


class LawSearch:
    """A law problem as the driver's :class:`~gearlever.synthesis.driver.Problem`.

    The search runs in the kind's reduced box (:meth:`LawKind.search_box`,
    :meth:`LawKind.search_sample`, :meth:`LawProblem.search_objective`); the
    polish takes the search's best to the full design vector and runs the
    minimax polish of :class:`LawProblem`: ``polish(z, rounds) -> (z, objective, {"offset": off})``.
    """

    def __init__(self, pb: LawProblem):
        self.pb = pb
        self.lo, self.hi = pb.kind.search_box()

    @property
    def evaluations(self) -> int:
        return self.pb.evaluations

    def sample(self, rng, m):
        return self.pb.kind.search_sample(rng, m)

    def objective(self, Z):
        return self.pb.search_objective(Z)

    def polish(self, z, rounds=None) -> tuple:
        """``(z, objective, {"offset": off})``: the minimax polish (its default rounds) of the full vector of ``z``."""
        full = self.pb.kind.to_full(np.asarray(z)[None, :])[0]
        z, off, f = self.pb.polish(full) if rounds is None else self.pb.polish(full, rounds=rounds)
        return np.asarray(z), f, {"offset": off}


def _search_problem(spec: dict) -> LawSearch:
    return LawSearch(make_problem(spec))


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
        Output zero of the fit: the law's output is ``generated + offset``.
    theta, wanted, achieved, error : ndarray (REPORT_SAMPLES,)
        Law input (radians), wanted and achieved output, ``achieved - wanted``.
    objective : float
        Weighted maximum error over the search samples (dwell samples weigh more).
    feasible : bool
    transmission_range : tuple
        Radians.
    details : dict
        Lengths, teeth, branch of the design.
    evaluations, seed, starts : int
    tried : dict
        Kind -> objective (``auto``), None where none was feasible.

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
    wanted: np.ndarray
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
    target: LawTarget = field(default=None, compare=False, repr=False)

    def model(self) -> dict:
        """Model dict sketched at law input 0 (output link ``output``)."""
        return KINDS[self.kind](self.target).model(self.z, self.offset)

    def generated(self, theta) -> np.ndarray:
        """The achieved output (with the fit's zero) at law inputs ``theta`` (closed form)."""
        G, _ = KINDS[self.kind](self.target).generate(self.z[None, :], np.asarray(theta, dtype=float))
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
) -> LawSynthesis:
    """Synthesize a mechanism of ``kind`` (or every kind: ``"auto"``) whose output follows ``target``.

    Parameters
    ----------
    target : LawTarget or gearlever.laws.MotionLaw
        The law sampled over a turn (:func:`~gearlever.synthesis.law.law_target`), or the law itself
        (sampled by :func:`target_of_law`; the error is then measured against it).
    kind : str
        A kind of :data:`~gearlever.synthesis.law.KINDS` or ``"auto"`` (all, the best kept).
    seed, budget : int
        The result is fixed by them: start ``k`` draws from ``default_rng([seed, k])``.
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
    (:func:`gearlever.synthesis.driver.multistart`).  ``evaluations`` counts
    the global searches (at most ``budget`` per kind tried) and the polishes.

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.synthesis.law import law_target
    >>> th = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    >>> res = synthesize_law(law_target(th, np.radians(20) * np.sin(th)), kind="fourbar", budget=3000, workers=1)
    >>> bool(np.degrees(np.abs(res.error).max()) < 1.0)
    True
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
    best, tried, evals = None, {}, 0
    for kd in usable:
        spec = {
            "kind": kd,
            "target": spec_target,
            "min_transmission": float(min_transmission),
            "teeth": [int(teeth[0]), int(teeth[1])],
        }
        pb = make_problem(spec)
        starts = n_starts(budget, pb.kind.search_box()[0].size)
        per = max(budget // starts, 1)
        results = multistart(
            search_problem(spec),
            starts,
            seed,
            budget=starts * per,
            workers=workers if scheduler is None else scheduler,
            progress=progress,
            method=method,
        )
        evals += sum(s.evaluations + s.polish_evaluations for s in results)
        top = results[0]
        if top.x is None or not math.isfinite(top.objective):
            tried[kd] = None
            continue
        f, z, off = top.objective, top.x, top.info["offset"]
        # the best start polished further (after the reduction: the same for any workers)
        z2, off2, f2 = pb.polish(np.asarray(z), rounds=FINAL_ROUNDS)
        if f2 < f:
            z, off, f = z2, off2, f2
        evals += pb.evaluations
        res = _result(pb, np.asarray(z), off, f, seed, starts, law)
        tried[kd] = res.objective
        if best is None or res.objective < best.objective:
            best = res
    if best is None:
        raise GearleverError("no buildable mechanism found within the constraints (min_transmission, teeth)")
    from dataclasses import replace

    tried.update({k: None for k in reasons})
    return replace(best, evaluations=evals, seconds=time.perf_counter() - t0, tried=tried)


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
        wanted=want,
        achieved=ach,
        error=ach - want,
        objective=float(f),
        feasible=bool(ok[0] and pb.feasible(z)[0]),
        transmission_range=(float(mn[0]), float(mx[0])),
        details=pb.kind.details(z),
        evaluations=0,
        seed=int(seed),
        starts=int(starts),
        target=t,
    )
