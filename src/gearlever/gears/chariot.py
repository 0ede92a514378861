"""The Nuttall south-pointing chariot: sized by the network solver, then driven.

The chariot's three differentials are the constraints (a)-(i) of the Nuttall
source, kept as data in ``gearlever/data/nuttall_network.csv`` and solved by
:mod:`gearlever.gears.networks`; relation (l) between the pointer (7) and the road
wheels (1, 12) comes out of the solver, not out of hand algebra.

Sign conventions (stated here once, used everywhere in gearlever)
------------------------------------------------------------------
* Ground frame: x, y horizontal, z up; every heading is an angle in radians
  measured counterclockwise from the ground x axis, seen from above.
* Chassis: x forward, y to the left.  Wheel 1 is the RIGHT road wheel,
  wheel 12 the LEFT one, a track ``t`` apart (between contact points).
* ``rot1``, ``rot12`` (turns) are positive when the wheel rolls forward
  (both seen from the far right, as in the source).  A contact point that
  travels a signed distance ``s`` (positive forward) turns its wheel
  ``s / (pi*d)`` turns.
* ``rot7`` (turns) is the pointer's rotation relative to the chassis,
  positive counterclockwise seen from above (the source's "POV from top").
* The chassis heading changes by ``(s_right - s_left) / t`` (turning left is
  positive); the pointer's ground heading is chassis heading + ``2*pi*rot7``.

With these conventions the source's results hold as printed: holding
``rot12 = 0`` and asking ``rot7 = 1`` gives ``rot1 < 0`` and
``d1 = 2t/|rot1|``; holding ``rot1 = 0`` gives ``rot12 > 0`` and
``d12 = 2t/rot12``.  Turning on the spot to the left (left wheel back, right
wheel forward) raises the chassis heading and leaves the pointer's heading
unchanged (tested).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from gearlever import _validate as V
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.networks import Network, NetworkSolution, parse_network

#: The tooth numbers a Nuttall design is given by (source parts table).
TEETH = ("n2", "n5", "n6", "n7", "n8", "n9", "n11")
#: Names of the right road wheel, the left road wheel and the pointer in the network.
RIGHT_WHEEL, LEFT_WHEEL, POINTER = "1", "12", "7"


@dataclass(frozen=True)
class NuttallTeeth:
    """Tooth numbers of a Nuttall chariot (all positive integers).

    Examples
    --------
    >>> NuttallTeeth.uniform(30).n7
    30
    """

    n2: int
    n5: int
    n6: int
    n7: int
    n8: int
    n9: int
    n11: int

    def __post_init__(self):
        for name in TEETH:
            object.__setattr__(self, name, V.positive_int(name, getattr(self, name)))

    @classmethod
    def uniform(cls, n: int) -> NuttallTeeth:
        """All seven gears with ``n`` teeth."""
        return cls(*([n] * len(TEETH)))

    def as_dict(self) -> dict[str, int]:
        return {name: getattr(self, name) for name in TEETH}


@functools.lru_cache(maxsize=1)
def _network_text() -> str:
    """The Nuttall data file (read on first use only)."""
    from gearlever.data import read_text

    return read_text("nuttall_network.csv")


def nuttall_network(teeth: NuttallTeeth) -> Network:
    """The Nuttall chariot as a :class:`~gearlever.gears.networks.Network`, built from the data file.

    Examples
    --------
    >>> a = nuttall_network(NuttallTeeth.uniform(20)).analyse()
    >>> (a.unknowns, a.rank, a.dof, a.redundant)
    (10, 8, 2, ('e',))

    Notes
    -----
    Rows (a)-(i) of the Nuttall source: three differentials (a), (b), (c)
    (carrier of (c) is the frame), two bevel meshes (d), (e) and four rigid
    couplings (f)-(i).
    """
    if not isinstance(teeth, NuttallTeeth):
        raise GearleverError(f"teeth must be NuttallTeeth, got {teeth!r}")
    return parse_network(_network_text(), teeth=teeth.as_dict())


@dataclass(frozen=True)
class NuttallDesign(Result):
    """A sized Nuttall chariot.

    Attributes
    ----------
    teeth, track : the given tooth numbers and track width ``t``.
    solution : the network solved for inputs (rot1, rot12).
    pointer_per_right, pointer_per_left : exact ``d rot7/d rot1`` and ``d rot7/d rot12`` (relation (l)).
    d1_over_t, d12_over_t : exact wheel diameters in units of ``t``.
    """

    teeth: NuttallTeeth
    track: float
    solution: NetworkSolution
    pointer_per_right: Fraction
    pointer_per_left: Fraction
    d1_over_t: Fraction
    d12_over_t: Fraction

    @property
    def d1(self) -> float:
        """Right wheel diameter, in the units of the track."""
        return float(self.d1_over_t) * self.track

    @property
    def d12(self) -> float:
        """Left wheel diameter, in the units of the track."""
        return float(self.d12_over_t) * self.track

    @property
    def rot1_per_pointer_turn(self) -> Fraction:
        """Turns of wheel 1 for one pointer turn with wheel 12 held (source (l=>))."""
        return 1 / self.pointer_per_right

    @property
    def rot12_per_pointer_turn(self) -> Fraction:
        """Turns of wheel 12 for one pointer turn with wheel 1 held (source (l=>))."""
        return 1 / self.pointer_per_left


def design_nuttall(teeth: NuttallTeeth, track: float = 1.0) -> NuttallDesign:
    """Solve the Nuttall network and size the road wheels so that the pointer keeps its heading.

    Parameters
    ----------
    teeth : NuttallTeeth
    track : float
        Track width ``t`` (distance between the wheels' contact points), > 0.

    Returns
    -------
    NuttallDesign

    Examples
    --------
    >>> d = design_nuttall(NuttallTeeth.uniform(24))
    >>> d.d1_over_t, d.d12_over_t
    (Fraction(1, 1), Fraction(1, 1))
    >>> d.solution.relation("7")
    'rot_7 = -1/2*rot_1 + 1/2*rot_12'

    Notes
    -----
    The solver gives ``rot7 = c1*rot1 + c12*rot12`` (Nuttall (l)).  Holding
    wheel 12 (source (m)-(o)): ``rot7 = 1`` needs ``rot1 = 1/c1`` and
    ``d1 = 2t/|rot1|``; holding wheel 1 (source (p), (q)): ``rot12 = 1/c12``
    and ``d12 = 2t/rot12``.
    """
    track = V.positive("track", track)
    solution = nuttall_network(teeth).solve([RIGHT_WHEEL, LEFT_WHEEL])
    c1, c12 = solution.coefficients[POINTER]
    if c1 == 0 or c12 == 0:
        raise GearleverError("teeth: the pointer does not depend on both road wheels in this design")
    rot1, rot12 = 1 / c1, 1 / c12
    if rot1 >= 0 or rot12 <= 0:
        raise GearleverError(f"teeth: design turns the pointer the wrong way (rot1={rot1}, rot12={rot12})")
    d1 = 2 / abs(rot1)
    d12 = 2 / rot12
    return NuttallDesign(
        teeth=teeth,
        track=track,
        solution=solution,
        pointer_per_right=c1,
        pointer_per_left=c12,
        d1_over_t=d1,
        d12_over_t=d12,
    )


def nuttall_closed_form(teeth: NuttallTeeth) -> dict[str, Fraction]:
    """The source's hand-derived results, exactly: rot1, rot12 per pointer turn, d1/t, d12/t.

    Used only to cross-check :func:`design_nuttall` (which does not use it).

    >>> nuttall_closed_form(NuttallTeeth(20, 20, 20, 40, 20, 20, 20))["d1_over_t"]
    Fraction(1, 2)

    Notes
    -----
    Nuttall (l=>): ``rot1 = -((n2+n5)/n2) K``, ``rot12 = ((n9+n11)/n11) K`` with
    ``K = (n5/(n2+n5))(n7/n6) + (n9/(n9+n11))(n7/n8)``; (m=>) ``d1 = 2t/|rot1|``;
    (p=>) ``d12 = 2t/rot12``.
    """
    n = {k: Fraction(v) for k, v in teeth.as_dict().items()}
    K = n["n5"] / (n["n2"] + n["n5"]) * n["n7"] / n["n6"] + n["n9"] / (n["n9"] + n["n11"]) * n["n7"] / n["n8"]
    rot1 = -(n["n2"] + n["n5"]) / n["n2"] * K
    rot12 = (n["n9"] + n["n11"]) / n["n11"] * K
    return {"K": K, "rot1": rot1, "rot12": rot12, "d1_over_t": 2 / abs(rot1), "d12_over_t": 2 / rot12}


# ---------------------------------------------------------------------------
# paths
# ---------------------------------------------------------------------------

#: Most steps a path may have (:func:`random_path`, :func:`waypoint_path`).
#: Memory: a random path and its :func:`simulate` run peak at about 55 bytes
#: per step (the two step arrays and their temporaries, the two N+1 heading
#: arrays, the summary's temporaries), so 10^7 steps take ~0.6 GB; time is
#: ~0.15 us per step, ~1.5 s for 10^7 steps on one core.  Above this a path
#: is refused before anything is allocated.
MAX_STEPS = 10**7
#: Most way-points :func:`parse_waypoints` reads: parsing costs ~2 us and each
#: point adds at least two steps, so 10^6 points stay within a few seconds
#: and well under :data:`MAX_STEPS`.
MAX_WAYPOINTS = 10**6


def random_path(
    turns: float, seed: int = 0, steps_per_turn: int = 1000, track: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """A random drive whose chassis turns ``turns`` full turns in all (sum of ``|heading changes|``).

    Returns the per-step signed distances travelled by the left and right
    contact points, ``(ds_left, ds_right)``, ``round(turns*steps_per_turn)`` steps
    (at most :data:`MAX_STEPS`).
    The drive is made of runs of 50 steps of constant speed and turn rate
    (arcs, spins on the spot, reversing), reproducible from ``seed``.

    >>> dl, dr = random_path(2, seed=1, steps_per_turn=100)
    >>> dl.shape, round(float(np.abs(dr - dl).sum()) / (2 * np.pi), 12)
    ((200,), 2.0)
    """
    turns = V.positive("turns", turns)
    seed = V.nonnegative_int("seed", seed)
    steps_per_turn = V.positive_int("steps_per_turn", steps_per_turn)
    track = V.positive("track", track)
    steps = turns * steps_per_turn
    if not steps <= MAX_STEPS:
        raise GearleverError(
            f"turns: turns*steps_per_turn must be at most {MAX_STEPS:,} steps (memory and time cap), "
            f"got {turns:g}*{steps_per_turn} = {steps:.3g}"
        )
    n = max(1, int(round(steps)))
    rng = np.random.default_rng(seed)
    run = 50
    runs = -(-n // run)
    rate = np.repeat(rng.normal(size=runs), run)[:n]
    speed = np.repeat(rng.uniform(-0.3, 1.0, size=runs), run)[:n]
    rate[np.abs(rate) < 1e-3] = 1e-3  # keep every step turning a little: turns stay well defined
    dpsi = rate * (2 * np.pi * turns / np.abs(rate).sum())
    ds_mid = speed * (4 * np.pi * track / steps_per_turn)
    half = dpsi * (track / 2)
    return ds_mid - half, ds_mid + half


def parse_waypoints(text: str) -> np.ndarray:
    """Parse ``x y`` pairs (comma or whitespace separated, ``#`` comments, optional ``x,y`` header).

    >>> parse_waypoints("x,y\\n0,0\\n1 0  # east\\n")
    array([[0., 0.],
           [1., 0.]])
    """
    pts = []
    for k, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        tokens = line.replace(",", " ").split()
        if not pts and [t.lower() for t in tokens] == ["x", "y"]:
            continue
        try:
            pair = [float(t) for t in tokens]
        except ValueError:
            pair = None
        if pair is None or len(pair) != 2 or not all(math.isfinite(v) for v in pair):
            raise GearleverError(f"waypoints line {k}: expected two finite numbers 'x y', got {raw.strip()!r}")
        pts.append(pair)
        if len(pts) > MAX_WAYPOINTS:
            raise GearleverError(f"waypoints must hold at most {MAX_WAYPOINTS:,} points (time cap), line {k}")
    if len(pts) < 2:
        raise GearleverError(f"waypoints must hold at least two points, got {len(pts)}")
    return np.array(pts, dtype=float)


def waypoint_path(points, track: float = 1.0, step: float = 0.01):
    """Drive straight from way-point to way-point, turning on the spot at each one.

    Returns ``(ds_left, ds_right, heading0)``: per-step contact distances (no
    step longer than ``step``) and the starting heading (towards the second
    distinct point).  Repeated consecutive points are skipped.  A path of
    more than :data:`MAX_STEPS` steps is refused before it is allocated.

    >>> dl, dr, h0 = waypoint_path([[0, 0], [1, 0], [1, 1]], step=0.5)
    >>> h0, len(dl)
    (0.0, 6)
    """
    pts = V.finite_array("points", points)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise GearleverError(f"points must be an (n, 2) array of x y pairs, got shape {pts.shape}")
    track = V.positive("track", track)
    step = V.positive("step", step)
    keep = np.ones(len(pts), bool)
    keep[1:] = np.any(np.diff(pts, axis=0) != 0, axis=1)
    pts = pts[keep]
    if len(pts) < 2:
        raise GearleverError("points must hold at least two distinct consecutive points")
    seg = np.diff(pts, axis=0)
    length = np.hypot(seg[:, 0], seg[:, 1])
    heading = np.arctan2(seg[:, 1], seg[:, 0])
    spin = np.angle(np.exp(1j * np.diff(heading)))  # wrapped to (-pi, pi]
    # interleave: run 0, spin 0, run 1, spin 1, ..., run m-1
    mid = np.zeros(2 * len(length) - 1)
    dpsi = np.zeros_like(mid)
    mid[0::2] = length
    dpsi[1::2] = spin
    size = np.maximum(np.abs(mid), np.abs(dpsi) * track / 2)
    with np.errstate(over="ignore"):
        count_f = np.maximum(1, np.ceil(size / step))
        total = float(count_f[size > 0].sum())
    if not total <= MAX_STEPS:
        raise GearleverError(
            f"step: the way-points need {total:.3g} steps of at most {step:g}, more than the cap "
            f"{MAX_STEPS:,} (memory and time); give a longer step"
        )
    count = count_f.astype(int)
    keep = size > 0
    mid, dpsi, count = mid[keep], dpsi[keep], count[keep]
    ds_mid = np.repeat(mid / count, count)
    half = np.repeat(dpsi / count, count) * (track / 2)
    return ds_mid - half, ds_mid + half, float(heading[0])


# ---------------------------------------------------------------------------
# simulation
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class ChariotRun(Result):
    """Result of :func:`simulate`: chassis and pointer along the path (N steps, N+1 states).

    Attributes
    ----------
    ds_left, ds_right : per-step contact distances (N,).
    chassis_heading : chassis heading in the ground frame, rad (N+1,).
    drift : pointer's ground heading minus its starting value, rad (N+1,).
    track, start : track width and starting point ``(x, y)``.
    """

    ds_left: np.ndarray
    ds_right: np.ndarray
    chassis_heading: np.ndarray
    drift: np.ndarray
    track: float
    start: tuple[float, float] = (0.0, 0.0)

    @property
    def pointer_heading(self) -> np.ndarray:
        """Pointer's heading in the ground frame (it starts along the chassis), rad."""
        return self.chassis_heading[0] + self.drift

    @property
    def max_drift(self) -> float:
        return float(np.max(np.abs(self.drift)))

    @property
    def final_drift(self) -> float:
        return float(self.drift[-1])

    @property
    def distance(self) -> float:
        """Path length of the axle's mid-point (0 for spinning on the spot)."""
        return float(np.abs(self.ds_left + self.ds_right).sum() / 2)

    @property
    def turns(self) -> float:
        """Total turning of the chassis, sum of ``|heading changes|`` / 2 pi."""
        return float(np.abs(self.ds_right - self.ds_left).sum() / self.track / (2 * np.pi))

    def mid_distance(self) -> np.ndarray:
        """Cumulative path length of the axle mid-point (N+1,)."""
        out = np.zeros(self.ds_left.size + 1)
        np.cumsum(np.abs(self.ds_left + self.ds_right) / 2, out=out[1:])
        return out

    def positions(self) -> tuple[np.ndarray, np.ndarray]:
        """Axle mid-point ``(x, y)`` along the path (N+1,), exact for each step's arc.

        Notes
        -----
        A step with heading change ``dpsi`` and mid-point distance ``ds`` is an
        arc; its chord has length ``ds*sin(dpsi/2)/(dpsi/2)`` and points along
        the mean heading of the step.
        """
        h = self.chassis_heading
        dpsi = np.diff(h)
        chord = (self.ds_left + self.ds_right) / 2 * np.sinc(dpsi / (2 * np.pi))
        mean = h[:-1] + dpsi / 2
        x = np.empty(h.size)
        y = np.empty(h.size)
        x[0], y[0] = self.start
        np.cumsum(chord * np.cos(mean), out=x[1:])
        np.cumsum(chord * np.sin(mean), out=y[1:])
        x[1:] += self.start[0]
        y[1:] += self.start[1]
        return x, y


#: Steps per block in :func:`simulate` (blocks of 2**14 float64 stay in cache).
_BLOCK = 1 << 14


def _float_1d(name, values) -> np.ndarray:
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be an array of finite numbers") from None
    if arr.ndim != 1:
        raise GearleverError(f"{name} must be a 1-D array, got shape {arr.shape}")
    return arr


def simulate(
    design: NuttallDesign,
    ds_left,
    ds_right,
    d1: float | None = None,
    d12: float | None = None,
    heading0: float = 0.0,
    start=(0.0, 0.0),
) -> ChariotRun:
    """Roll the road wheels along a path and carry their rotations through the solved network.

    Parameters
    ----------
    design : NuttallDesign
        Gives the network (pointer per wheel turn) and the track ``t``.
    ds_left, ds_right : array_like (N,)
        Signed distances travelled by the left (12) and right (1) contact
        points in each step (positive forward).
    d1, d12 : float, optional
        Actual wheel diameters; default the design's (exact) ones.
    heading0 : float
        Starting chassis heading, rad.  The pointer starts along the chassis.

    Returns
    -------
    ChariotRun

    Examples
    --------
    Spin on the spot a quarter turn to the left: the chassis turns +pi/2, the
    pointer keeps its heading.

    >>> d = design_nuttall(NuttallTeeth(30, 24, 18, 36, 20, 25, 40))
    >>> s = np.full(100, np.pi / 4 / 100)       # quarter turn: each wheel rolls pi*t/4
    >>> r = simulate(d, -s, s)
    >>> round(float(r.chassis_heading[-1]), 12), r.max_drift < 1e-12
    (1.570796326795, True)

    Notes
    -----
    Per step: wheel turns ``rot1 = ds_right/(pi d1)``, ``rot12 = ds_left/(pi d12)``;
    pointer ``rot7 = c1 rot1 + c12 rot12`` (Nuttall (l), from the solver);
    chassis ``dpsi = (ds_right - ds_left)/t``; pointer heading change
    ``dpsi + 2 pi rot7 = ds_right (1/t + 2 c1/d1) + ds_left (2 c12/d12 - 1/t)``
    (summed per step before accumulating, so that no rounding of the large
    heading enters the drift).  Headings are cumulative sums, computed block
    by block in cache; there is no Python loop over steps.
    """
    if not isinstance(design, NuttallDesign):
        raise GearleverError(f"design must be a NuttallDesign, got {type(design).__name__}")
    dl = _float_1d("ds_left", ds_left)
    dr = _float_1d("ds_right", ds_right)
    if dl.shape != dr.shape:
        raise GearleverError(f"ds_left and ds_right must have one length, got {dl.size} and {dr.size}")
    d1 = design.d1 if d1 is None else V.positive("d1", d1)
    d12 = design.d12 if d12 is None else V.positive("d12", d12)
    heading0 = V.finite("heading0", heading0)
    start = tuple(float(v) for v in V.finite_array("start", start).reshape(2))
    t = design.track
    # pointer angle (rad) per unit of contact distance:
    # 2 pi * (wheel turns per unit length = 1/(pi d)) * (pointer turns per wheel turn, from the solver)
    k_right = 2 * np.pi * float(design.pointer_per_right) / (np.pi * d1)
    k_left = 2 * np.pi * float(design.pointer_per_left) / (np.pi * d12)
    n = dl.size
    # Two output buffers, every pass in place, block by block so that the
    # passes over a block run in cache (fresh arrays and memory traffic cost
    # more than the arithmetic).  The loop is over blocks, not steps.
    heading = np.empty(n + 1)
    heading[0] = heading0
    drift = np.empty(n + 1)
    drift[0] = 0.0
    # pointer's ground heading change per step = chassis dpsi + 2 pi rot7
    #   = ds_right*(1/t + k_right) + ds_left*(k_left - 1/t)   (same sum, one pass fewer)
    g_right = 1.0 / t + k_right
    g_left = k_left - 1.0 / t
    m = min(n, _BLOCK)
    scratch_a, scratch_b, scratch_c = np.empty(m), np.empty(m), np.empty(m)
    for lo in range(0, n, _BLOCK):
        hi = min(n, lo + _BLOCK)
        dpsi, turn, tmp = scratch_a[: hi - lo], scratch_b[: hi - lo], scratch_c[: hi - lo]
        np.subtract(dr[lo:hi], dl[lo:hi], out=dpsi)
        dpsi *= 1.0 / t  # chassis heading change per step
        np.multiply(dr[lo:hi], g_right, out=turn)
        np.multiply(dl[lo:hi], g_left, out=tmp)
        turn += tmp  # pointer's ground heading change per step
        dpsi[0] += heading[lo]  # carry the running sums into the block
        turn[0] += drift[lo]
        np.cumsum(dpsi, out=heading[lo + 1 : hi + 1])  # separate buffers: no overlap copy
        np.cumsum(turn, out=drift[lo + 1 : hi + 1])
    if not (math.isfinite(heading[-1]) and math.isfinite(drift[-1])):
        # a NaN or inf anywhere in the input propagates to the end of a cumulative sum
        V.finite_array("ds_left", dl)
        V.finite_array("ds_right", dr)
        raise GearleverError(
            "ds_left, ds_right: the path is too long for these wheels (d1, d12): the headings overflow"
        )
    return ChariotRun(ds_left=dl, ds_right=dr, chassis_heading=heading, drift=drift, track=t, start=start)


def drift_on_the_spot(design: NuttallDesign, d1: float, d12: float | None = None) -> float:
    """Closed-form pointer drift (rad) for one full left turn on the spot with wheels ``d1``, ``d12``.

    Each contact point rolls ``pi t`` (right forward, left back); the pointer
    drifts by ``pi t (1/t + 2 c1/d1) - pi t (2 c12/d12 - 1/t)``.

    >>> d = design_nuttall(NuttallTeeth.uniform(20))
    >>> round(drift_on_the_spot(d, d.d1 * 1.01), 6)
    0.031105
    """
    d1 = V.positive("d1", d1)
    d12 = design.d12 if d12 is None else V.positive("d12", d12)
    t = design.track
    s = np.pi * t
    return float(
        s * (1 / t + 2 * float(design.pointer_per_right) / d1) - s * (2 * float(design.pointer_per_left) / d12 - 1 / t)
    )
