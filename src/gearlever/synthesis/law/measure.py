"""The law a mechanism produces (the inverse use), its segments, and the report of a law synthesis.

:func:`mechanism_law` solves a model with the mechanism engine over one
turn of its (single, link) input, counter-clockwise from the sketch, and
returns the output link's rotation (or the output slider's travel) and its
velocity and acceleration analogues; :func:`fit_segments` splits it into
dwells (speed below a threshold), rises and returns; :func:`law_report`
measures a :class:`~gearlever.synthesis.law.driver.LawSynthesis` against
its law.

Numeric core: numpy, :mod:`gearlever.mechanism` and :mod:`gearlever.cams` (the cam comparison).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = [
    "MechanismLaw",
    "mechanism_law",
    "fit_segments",
    "law_report",
    "cam_comparison",
    "time_ratio",
    "DWELL_THRESHOLD",
    "MISS_FRACTION",
]

#: A dwell: the output's speed analogue below this fraction of its peak.
DWELL_THRESHOLD = 0.01
#: A design misses its law when its largest error exceeds this fraction of the law's range (2 %): the report
#: says so (``misses_law``) and the command line warns on stderr.
MISS_FRACTION = 0.02
#: Shortest dwell reported (degrees of input).
MIN_DWELL_DEG = 10.0


@dataclass(frozen=True)
class MechanismLaw(Result):
    """The output of a mechanism over one input turn.

    Attributes
    ----------
    theta : ndarray (N,)
        Input rotation from the sketch, radians.
    s, v, a : ndarray (N,)
        Output rotation (radians) or travel from the sketch, and its
        velocity and acceleration analogues (per radian of input).
    output : str
        The output link (or slider) name.
    kind : {"angle", "displacement"}
    closed : ndarray (N,) of bool
    net : float
        Output change over the whole turn (0 when it returns).
    """

    theta: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    output: str
    kind: str
    closed: np.ndarray
    net: float = 0.0


def mechanism_law(mech, output: str, samples: int = 3600) -> MechanismLaw:
    """Solve ``mech`` (a :class:`~gearlever.mechanism.Mechanism`) over one ccw turn of its input; read ``output``.

    ``output`` names a link (its rotation) or a slider (its travel).  The
    mechanism must have one input, a link.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({
    ...     "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 0], "B": [4.5, 2.8]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "output": ["O4", "B"]},
    ...     "inputs": [{"link": "crank"}]})
    >>> r = mechanism_law(m, "output", 3600)
    >>> bool(r.closed.all()), round(float(np.degrees(np.ptp(r.s))), 3)  # the rocker's swing by the cosine law
    (True, 46.918)
    """
    model = mech.model
    if len(model.inputs) != 1 or model.inputs[0].kind != "link":
        raise GearleverError("the mechanism must have one input, a link, to be turned through one cycle")
    samples = int(samples)
    if not 8 <= samples <= 100_000:
        raise GearleverError(f"samples must be 8..100000, got {samples}")
    spec = model.inputs[0]
    sliders = {s.name: s for s in model.sliders}
    if output in sliders:
        kind = "displacement"
    elif output in model.links and output != "ground":
        kind = "angle"
    else:
        names = sorted(set([k for k in model.links if k != "ground"] + list(sliders)))
        raise GearleverError(f"output {output!r} is not a moving link or slider of the model ({', '.join(names)})")
    q0 = model.links[spec.name].angle0
    if spec.relative_to is not None:
        q0 -= model.links[spec.relative_to].angle0
    theta = np.linspace(0.0, 2 * math.pi, samples, endpoint=False)
    res = mech.solve((q0 + np.append(theta, 2 * math.pi))[:, None])
    if kind == "angle":
        s = res.angle[output] - model.links[output].angle0
        v, a = res.omega[output], res.alpha[output]
    else:
        s, v, a = res.displacement[output], res.slider_velocity[output], res.slider_acceleration[output]
    net = float(s[-1] - s[0])
    net = 0.0 if abs(net) <= 1e-9 * max(1.0, float(np.ptp(s))) else net
    return MechanismLaw(theta, s[:-1], v[:-1], a[:-1], output, kind, res.closed[:-1] & res.closed[-1], net)


def fit_segments(
    theta, s, v, threshold: float = DWELL_THRESHOLD, min_dwell_deg: float = MIN_DWELL_DEG, net: float = 0.0
) -> list:
    """Dwells, rises and returns of a periodic output over one turn.

    A sample dwells when ``|v|`` is below ``threshold`` times the peak
    ``|v|``; runs of samples of one class (dwell, rise ``v > 0``, return
    ``v < 0``) are the segments, joined across the end of the turn; a
    dwell shorter than ``min_dwell_deg`` (a reversal's stationary point) is
    counted with the motion around it.  ``net`` is the output's net change
    over the turn (nonzero for an output that turns fully, as a crank): the
    rise of a single segment that fills the whole turn.

    Returns
    -------
    list of dict
        ``motion, from_deg, to_deg, rise, excursion`` per segment (output units), the one holding input 0
        first (``from_deg > to_deg`` when it wraps).

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> s = np.where(th < np.pi, 0.0, 1 - np.cos(2 * th))
    >>> [g["motion"] for g in fit_segments(th, s, np.gradient(s, th))]
    ['dwell', 'rise', 'return']
    """
    theta, s, v = (np.asarray(x, dtype=float) for x in (theta, s, v))
    vmax = float(np.max(np.abs(v))) if v.size else 0.0
    cls = np.where(np.abs(v) <= threshold * vmax, 0, np.where(v > 0, 1, -1)) if vmax > 0 else np.zeros(v.size, int)
    n = cls.size
    width = max(1, int(math.ceil(math.radians(min_dwell_deg) / (2 * math.pi / max(n, 1)))))
    runs = _runs(cls)
    for st, ln in runs:
        if cls[st] == 0 and ln < width and ln < n:
            idx = (st + np.arange(ln)) % n
            cls[idx] = np.where(v[idx] >= 0, 1, -1)
    # start at a change of class so that no run wraps
    change = np.flatnonzero(cls != np.roll(cls, 1))
    if change.size == 0:
        motion = "dwell" if cls[0] == 0 else ("rise" if cls[0] > 0 else "return")
        rise = 0.0 if motion == "dwell" else float(net)
        return [{"motion": motion, "from_deg": 0.0, "to_deg": 360.0, "rise": rise, "excursion": float(np.ptp(s))}]
    start = int(change[0])
    order = (np.arange(n) + start) % n
    out = []
    i = 0
    names = {0: "dwell", 1: "rise", -1: "return"}
    step = 2 * math.pi / n
    while i < n:
        j = i
        while j + 1 < n and cls[order[j + 1]] == cls[order[i]]:
            j += 1
        idx = order[i : j + 1]
        end = order[(j + 1) % n]
        rise = float(s[end] - s[idx[0]])
        out.append(
            {
                "motion": names[int(cls[idx[0]])],
                "from_deg": round(math.degrees(theta[idx[0]]), 9),
                "to_deg": round(math.degrees(theta[idx[-1]] + step), 9) % 360.0 or 360.0,
                "rise": rise,
                "excursion": float(np.ptp(s[idx])),
            }
        )
        i = j + 1
    # the segment holding input 0 first (it may start before 360 and wrap)
    return sorted(out, key=lambda g: -1.0 if g["from_deg"] > g["to_deg"] else g["from_deg"])


def _runs(cls) -> list:
    """(start, length) of the runs of equal values of a periodic class array."""
    n = cls.size
    change = np.flatnonzero(cls != np.roll(cls, 1))
    if change.size == 0:
        return [(0, n)]
    ends = np.append(change[1:], change[0] + n)
    return [(int(a), int(b - a)) for a, b in zip(change, ends)]


def time_ratio(theta, s, net: float = 0.0, threshold: float = 0.0) -> dict:
    """Quick-return time ratio of a periodic output: the input spent rising over the input spent returning.

    The speed analogue is the periodic central difference of ``s`` (evenly
    spaced ``theta`` over one turn); a sample rises where it is above
    ``threshold`` times its peak, returns where it is below minus that,
    dwells otherwise (dwells count in neither; the report takes
    :data:`DWELL_THRESHOLD` for a law with a dwell, else 0).  The time ratio of a
    quick-return mechanism is the crank angle of its working stroke over
    that of its return at a uniform crank speed (Shigley and Uicker,
    *Theory of Machines and Mechanisms*, quick-return mechanisms).

    Returns
    -------
    dict
        ``rise_deg``, ``return_deg`` (input spans) and ``ratio`` (None for an output that does not both rise
        and return, or that turns on: ``net != 0``).

    Examples
    --------
    >>> th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> s = np.where(th < 4 * np.pi / 3, th / (4 * np.pi / 3), 1 - (th - 4 * np.pi / 3) / (2 * np.pi / 3))
    >>> r = time_ratio(th, s)
    >>> r["rise_deg"], r["return_deg"], r["ratio"]
    (239.0, 121.0, 1.975206611570248)
    """
    theta, s = np.asarray(theta, dtype=float), np.asarray(s, dtype=float)
    h = 2 * math.pi / theta.size
    drift = s - net * theta / (2 * math.pi)
    v = (np.roll(drift, -1) - np.roll(drift, 1)) / (2 * h) + net / (2 * math.pi)
    top = float(np.max(np.abs(v))) if v.size else 0.0
    rise = int(np.count_nonzero(v > threshold * top)) if top > 0 else 0
    ret = int(np.count_nonzero(v < -threshold * top)) if top > 0 else 0
    deg = 360.0 / theta.size
    ok = rise > 0 and ret > 0 and net == 0.0
    return {"rise_deg": rise * deg, "return_deg": ret * deg, "ratio": rise / ret if ok else None}


def _segment_time_ratio(t) -> dict | None:
    """The time ratio of a segment law from its segments (rises over returns), or None for a sampled law."""
    if t.motions == ("samples",):
        return None
    rise = ret = 0.0
    for k, motion in enumerate(t.motions):
        m = t.segment == k
        if motion == "dwell" or not m.any():
            continue
        span = math.degrees(t.breaks[k + 1] - t.breaks[k])
        idx = np.flatnonzero(m)
        nxt = (idx[-1] + 1) % t.s.size
        change = t.s[nxt] - t.s[idx[0]] + (t.net if nxt == 0 else 0.0)
        if change > 0:
            rise += span
        elif change < 0:
            ret += span
    ok = rise > 0 and ret > 0 and t.net == 0.0
    return {"rise_deg": rise, "return_deg": ret, "ratio": rise / ret if ok else None}


def law_report(res, *, degrees: bool = True) -> dict:
    """Strict-JSON-ready measures of a :class:`~gearlever.synthesis.law.driver.LawSynthesis` against its law.

    Error (max, RMS, per segment), dwell excursion per dwell segment (the
    achieved output's range over the segment) and the largest of them against
    the bound set (``dwell_tolerance``), peak velocity and acceleration
    analogues achieved against wanted, transmission angle range, the time
    ratio achieved against wanted (:func:`time_ratio`), whether the design
    misses the law (``misses_law``: its largest error above
    :data:`MISS_FRACTION` of the law's range), the design's details, the
    evaluations against the budget and, for ``auto``, why each kind not
    kept gave no design.
    """
    t = res.law_target
    ang = t.output == "angle"
    conv = math.degrees if ang else float
    unit = "_deg" if ang else ""
    th, err, ach = res.theta, res.error, res.achieved
    n = th.size
    h = 2 * math.pi / n
    drift = ach - t.net * th / (2 * math.pi)
    va = (np.roll(drift, -1) - np.roll(drift, 1)) / (2 * h) + t.net / (2 * math.pi)
    aa = (np.roll(drift, -1) - 2 * drift + np.roll(drift, 1)) / (h * h)
    seg = np.clip(np.searchsorted(t.breaks, th, side="right") - 1, 0, len(t.motions) - 1)
    wv = np.interp(th, t.theta, t.v, period=2 * math.pi)
    wa = np.interp(th, t.theta, t.a, period=2 * math.pi)
    segments = []
    for k, motion in enumerate(t.motions):
        m = seg == k
        if not m.any():
            continue
        rec = {
            "segment": k + 1,
            "motion": motion,
            "from_deg": math.degrees(t.breaks[k]),
            "to_deg": math.degrees(t.breaks[k + 1]),
            f"error_max{unit}": conv(float(np.max(np.abs(err[m])))),
        }
        if motion == "dwell":
            rec[f"dwell_excursion{unit}"] = conv(float(np.ptp(ach[m])))
        segments.append(rec)
    mn, mx = res.transmission_range
    emax = float(np.max(np.abs(err)))
    scale = t.scale
    excursions = [float(np.ptp(ach[seg == k])) for k, m in enumerate(t.motions) if m == "dwell" and (seg == k).any()]
    thr = DWELL_THRESHOLD if "dwell" in t.motions else 0.0
    tr_want = _segment_time_ratio(t) or time_ratio(th, res.target, t.net, thr)
    tr_got = time_ratio(th, ach, t.net, thr)
    tol = res.dwell_tolerance
    return {
        "kind": res.kind,
        "feasible": res.feasible,
        "misses_law": bool(emax > MISS_FRACTION * scale),
        "miss_fraction_limit": MISS_FRACTION,
        "error_fraction_of_range": emax / scale,
        "range" + unit: conv(scale),
        "time_ratio": {
            "achieved": tr_got["ratio"],
            "wanted": tr_want["ratio"],
            "rise_deg": {"achieved": tr_got["rise_deg"], "wanted": tr_want["rise_deg"]},
            "return_deg": {"achieved": tr_got["return_deg"], "wanted": tr_want["return_deg"]},
        },
        "dwell_excursion" + unit: conv(max(excursions)) if excursions else None,
        "dwell_tolerance" + unit: None if tol is None else conv(tol),
        f"error_max{unit}": conv(emax),
        f"error_rms{unit}": conv(float(np.sqrt(np.mean(err**2)))),
        "objective_weighted_max" + unit: conv(res.objective),
        "segments": segments,
        f"peak_velocity{unit}_per_rad": {
            "achieved": conv(float(np.max(np.abs(va)))),
            "wanted": conv(float(np.max(np.abs(wv)))),
        },
        f"peak_acceleration{unit}_per_rad2": {
            "achieved": conv(float(np.max(np.abs(aa)))),
            "wanted": conv(float(np.max(np.abs(wa)))),
        },
        "transmission_deg": [math.degrees(mn), math.degrees(mx)],
        "design": res.details,
        "output_offset" + unit: conv(res.offset),
        "output_at_input_0" + unit: conv(float(ach[0])),
        "evaluations": res.evaluations,
        "budget_per_type": res.budget,
        "evaluations_per_type": dict(res.spent),
        "seed": res.seed,
        "starts": res.starts,
        "types_tried": {k: (None if v is None else conv(v)) for k, v in res.tried.items()},
        "types_not_tried": {k: v for k, v in res.not_tried.items() if k not in res.spent},
        "types_without_design": {k: v for k, v in res.not_tried.items() if k in res.spent},
        "samples": int(n),
    }


#: The default cam of the comparison: a roller follower sized for this largest pressure angle (deg).  Oscillating,
#: for an angle law: arm :data:`~gearlever.synthesis.law.fourbar.SIZE`, a roller of a quarter of it and the first
#: pivot distance of :data:`CAM_PIVOT_DISTANCES` (times the arm) at which a base radius meets the pressure angle
#: with the pivot outside the cam; translating, for a displacement law: a roller of a fifth of the stroke.
CAM_PRESSURE_ANGLE_DEG = 30.0
#: Pivot distances (times the arm) the comparison's oscillating roller follower tries, in turn.
CAM_PIVOT_DISTANCES = (2.0, 2.5, 3.0, 4.0, 6.0, 8.0)


def _cam_layout(law, pmax: float):
    """(follower, dims, base radius) of the comparison's cam, or the last refusal (a GearleverError)."""
    from gearlever.cams import size_base_radius
    from gearlever.synthesis.law.fourbar import SIZE

    if law.output != "angle":
        dims = {"roller_radius": law.scale / 5}
        return "translating-roller", dims, size_base_radius(law, "translating-roller", max_pressure_angle=pmax, **dims)
    # the pivot must stay outside the cam (cams.followers.oscillating_roller): sizing only returns such layouts,
    # and a layout whose pressure angle cannot be met below that bound is refused, so the next distance is tried
    last = None
    for k in CAM_PIVOT_DISTANCES:
        dims = {"roller_radius": SIZE / 4, "arm": SIZE, "pivot_distance": k * SIZE}
        try:
            return (
                "oscillating-roller",
                dims,
                size_base_radius(law, "oscillating-roller", max_pressure_angle=pmax, **dims),
            )
        except GearleverError as exc:
            last = exc
    raise GearleverError(f"{last} (pivot distances tried: {', '.join(f'{k:g}' for k in CAM_PIVOT_DISTANCES)} arms)")


def cam_comparison(law) -> dict:
    """The cam giving ``law`` with the default roller follower: its size, pressure angle and curvature.

    A cam meets its law exactly (its profile is computed from it), so the
    comparison with a linkage is of size, pressure angle (against the
    linkage's transmission angle: ``90 deg - pressure angle``) and curvature.
    For an angle law the follower is an oscillating roller whose pivot lies
    outside the cam (the cam's largest radius ``cam_radius_max`` below the
    pivot distance, ``pivot_clearance`` the difference): the layout is the
    first of :data:`CAM_PIVOT_DISTANCES` where sizing meets the pressure angle.
    Returns ``{"available": False, "note": ...}`` when the cam cannot be
    made (a law that does not return to its start, no layout meeting the
    pressure angle).

    Examples
    --------
    >>> from gearlever.data import example_path
    >>> from gearlever.laws import load_law
    >>> c = cam_comparison(load_law(example_path("law_dwell_rocker.toml")))  # 45 deg swing, 120 deg dwell
    >>> c["follower"], c["pivot_distance"], round(c["pressure_angle_max_deg"], 6), c["pivot_clearance"] > 0
    ('oscillating-roller', 250.0, 30.0, True)
    """
    from gearlever.cams import design_cam

    pmax = math.radians(CAM_PRESSURE_ANGLE_DEG)
    follower = "oscillating-roller" if law.output == "angle" else "translating-roller"
    try:
        follower, dims, rb = _cam_layout(law, pmax)
        cam = design_cam(law, follower, base_radius=rb, **dims)
    except GearleverError as exc:
        return {"available": False, "follower": follower, "note": str(exc)}
    out = {
        "available": True,
        "follower": follower,
        **{k: float(v) for k, v in dims.items()},
        "base_radius": float(cam.base_radius),
        "pressure_angle_max_deg": math.degrees(cam.pressure_angle_max),
        "transmission_min_deg": 90.0 - math.degrees(cam.pressure_angle_max),
        "curvature_radius_min": float(cam.curvature_radius_min),
        "undercut": bool(cam.undercut),
        "error_max": 0.0,
        "note": f"sized for a largest pressure angle of {CAM_PRESSURE_ANGLE_DEG:g} deg; a cam meets its law exactly",
    }
    if follower == "oscillating-roller":
        from gearlever.cams.followers import FollowerParams
        from gearlever.cams.followers.oscillating_roller import cam_radius_max

        r_max = cam_radius_max(FollowerParams(**dims), cam.base_radius, cam.stroke)
        out["cam_radius_max"] = r_max
        out["pivot_clearance"] = dims["pivot_distance"] - r_max
    return out
