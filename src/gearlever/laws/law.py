"""Motion laws over one input turn: segments of standard motions, or samples.

A :class:`MotionLaw` gives the output (an angle or a displacement) as a
function of the input angle theta over one turn, 0 .. 2 pi, either as
consecutive segments of the motions of :mod:`gearlever.laws.motions` or as a
periodic cubic spline through samples.  :meth:`MotionLaw.evaluate` gives the
displacement s and its derivatives v, a, j per radian of input (a
:class:`LawValues`), :meth:`MotionLaw.continuity` reports the jumps at segment
boundaries (the fundamental law of cam design: s, v, a continuous, jerk
finite; R. L. Norton, *Design of Machinery*, sec. 8.3).

Files: :func:`load_law` reads LAW.toml::

    [law]
    output = "angle"          # or "displacement"
    units = "deg"             # deg (or rad) for angle; mm, m, in ... for displacement
    [[law.segment]]
    to = 120
    motion = "dwell"
    [[law.segment]]
    to = 240
    motion = "cycloidal"
    rise = 45

or ``[law] samples = "law.csv"`` (columns input_deg, output).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gearlever._io import did_you_mean as _did_you_mean
from gearlever._io import read_csv_table, read_toml_table
from gearlever._result import Result
from gearlever._validate import finite, finite_array
from gearlever.errors import GearleverError, a
from gearlever.laws.motions import MOTIONS

__all__ = [
    "ANGLE_UNITS",
    "LENGTH_UNITS",
    "ContinuityReport",
    "LawValues",
    "MotionLaw",
    "law_from_samples",
    "law_from_segments",
    "load_law",
]

TWO_PI = 2 * math.pi
#: Units of angle outputs and their size in radians.
ANGLE_UNITS = {"deg": math.pi / 180, "rad": 1.0}
#: Units of displacement outputs (kept as given: the law is in these units).
LENGTH_UNITS = ("mm", "cm", "m", "in", "ft", "um")
#: Narrowest segment (deg): below it the derivatives h / beta**k overflow long before a cam could follow.
MIN_SEGMENT_DEG = 1e-6
#: Most segments a law may have.
MAX_SEGMENTS = 10_000
#: Most samples (rows of the samples CSV) a law may have.
MAX_SAMPLES = 1_000_000


def _check_kind(output, units, where: str) -> tuple[str, str]:
    if output not in ("angle", "displacement"):
        raise GearleverError(
            f"{where}: output must be 'angle' or 'displacement', got {output!r}"
            + _did_you_mean(output, ("angle", "displacement"))
        )
    known = tuple(ANGLE_UNITS) if output == "angle" else LENGTH_UNITS
    if units not in known:
        raise GearleverError(
            f"{where}: units of {a(output)} law must be one of {', '.join(known)}, got {units!r}"
            + _did_you_mean(units, known)
        )
    return output, units


@dataclass(frozen=True)
class LawValues(Result):
    """Displacement and derivatives of a law at input angles.

    Attributes
    ----------
    theta : ndarray
        Input angles (rad), as given.
    s, v, a, j : ndarray
        Output displacement and its first three derivatives per radian of
        input (``per == "rad"``) or per second (``per == "s"``, from
        :meth:`per_second`).  Angle outputs are in radians.
    output, units, per : str
        What the output is, its units in the law file, and the derivative base.

    Examples
    --------
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> vals = law.evaluate([0.0, math.pi / 2])
    >>> [round(float(x), 6) for x in vals.s]
    [0.0, 5.0]
    >>> round(float(vals.per_second(60).v[1]), 6)  # 2 h / beta * omega = 2 * 10 / pi * 2 pi
    40.0
    """

    theta: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    j: np.ndarray
    output: str = "displacement"
    units: str = "mm"
    per: str = "rad"

    def per_second(self, rpm: float) -> LawValues:
        """Time derivatives for an input turning at ``rpm`` revolutions per minute."""
        if self.per != "rad":
            raise GearleverError("per_second needs values per radian of input")
        rpm = finite("rpm", rpm)
        if rpm <= 0:
            raise GearleverError(f"rpm must be a positive finite number, got {rpm!r}")
        w = TWO_PI * rpm / 60.0
        return LawValues(self.theta, self.s, self.v * w, self.a * w**2, self.j * w**3, self.output, self.units, "s")

    def _frame_columns(self) -> dict:
        u = "rad" if self.output == "angle" else self.units
        p = self.per
        return {
            "theta_rad": self.theta,
            f"s_{u}": self.s,
            f"v_{u}_per_{p}": self.v,
            f"a_{u}_per_{p}2": self.a,
            f"j_{u}_per_{p}3": self.j,
        }


@dataclass(frozen=True)
class ContinuityReport(Result):
    """Jumps of s, v, a, j at the segment boundaries of a law.

    At a boundary where v jumps the acceleration is infinite (an impulse);
    where a jumps the jerk is infinite.  Norton's fundamental law of cam
    design asks for neither: s, v, a continuous over the whole cycle.

    Attributes
    ----------
    at : ndarray
        Boundary input angles (rad), 0 standing for the 360 deg / 0 joint.
    jump_s, jump_v, jump_a, jump_j : ndarray
        Right limit minus left limit at each boundary (per radian of input);
        at 0, the joint of the cycle's end with its start, net change removed.
    tolerance : float
        Size below which a jump counts as none.

    Examples
    --------
    >>> law = law_from_segments("displacement", "mm", [{"to": 90, "motion": "dwell"},
    ...     {"to": 180, "motion": "linear", "rise": 10}, {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> law.continuity().problems()[0]
    'at 90 deg: velocity jumps by 6.3662 mm/rad (acceleration infinite)'
    """

    at: np.ndarray
    jump_s: np.ndarray
    jump_v: np.ndarray
    jump_a: np.ndarray
    jump_j: np.ndarray
    tolerance: float = 1e-9
    units: str = "mm"

    @property
    def ok(self) -> bool:
        """True when s, v and a are continuous (the fundamental law of cam design holds)."""
        t = self.tolerance
        return bool(
            np.all(np.abs(self.jump_s) <= t) and np.all(np.abs(self.jump_v) <= t) and np.all(np.abs(self.jump_a) <= t)
        )

    @property
    def infinite_acceleration(self) -> np.ndarray:
        """Boundaries (rad) where v jumps: the acceleration is an impulse there."""
        return self.at[np.abs(self.jump_v) > self.tolerance]

    @property
    def infinite_jerk(self) -> np.ndarray:
        """Boundaries (rad) where a jumps: the jerk is an impulse there."""
        return self.at[np.abs(self.jump_a) > self.tolerance]

    def problems(self) -> list[str]:
        """One sentence per discontinuity, in boundary order."""
        out = []
        u = self.units
        for k, at in enumerate(self.at):
            deg = f"{math.degrees(at):.6g}"
            if abs(self.jump_s[k]) > self.tolerance:
                out.append(f"at {deg} deg: displacement jumps by {self.jump_s[k]:.6g} {u}")
            if abs(self.jump_v[k]) > self.tolerance:
                out.append(f"at {deg} deg: velocity jumps by {self.jump_v[k]:.6g} {u}/rad (acceleration infinite)")
            elif abs(self.jump_a[k]) > self.tolerance:
                out.append(f"at {deg} deg: acceleration jumps by {self.jump_a[k]:.6g} {u}/rad^2 (jerk infinite)")
        return out


@dataclass(frozen=True, eq=False)
class MotionLaw:
    """An output law over one input turn.

    Attributes
    ----------
    output : str
        ``"angle"`` (rocker or gear; values in radians) or ``"displacement"``.
    units : str
        Units of the law file: ``"deg"``/``"rad"`` for angles, a length unit otherwise.
    breaks : ndarray
        Segment boundaries (rad), 0 .. 2 pi, ``n_segments + 1`` values.
    motions : tuple of str
        Motion name per segment (``"samples"`` for a sampled law's one segment).
    rises : ndarray
        Output change per segment (rad for angle laws, length units otherwise).
    start : float
        Output at input 0.
    source : str
        Where the law came from (file name), used in messages.
    knots : tuple or None
        For a sampled law, (theta_knots, values) of the periodic spline
        (values with the net change over the turn removed).

    Examples
    --------
    >>> law = law_from_segments("angle", "deg", [{"to": 120, "motion": "dwell"},
    ...     {"to": 240, "motion": "cycloidal", "rise": 45}, {"to": 360, "motion": "345", "rise": -45}])
    >>> round(math.degrees(float(law.evaluate(math.radians(180)).s)), 6)
    22.5
    >>> law.net_change(), law.continuity().ok
    (0.0, True)
    """

    output: str
    units: str
    breaks: np.ndarray
    motions: tuple
    rises: np.ndarray
    start: float = 0.0
    source: str = "law"
    knots: tuple | None = field(default=None, repr=False)
    _spline: object = field(default=None, repr=False, compare=False)

    @property
    def scale(self) -> float:
        """Largest output excursion over the turn (the stroke), in law units (rad for angles)."""
        if self.knots is None:
            cum = np.concatenate([[0.0], np.cumsum(self.rises)])
            return float(cum.max() - cum.min())
        vals = self.evaluate(np.linspace(0.0, TWO_PI, 3601)).s
        return float(vals.max() - vals.min())

    def to_dict(self) -> dict:
        """The ``[law]`` table of LAW.toml for this law (segments, in the file's units).

        A sampled law gives ``samples`` as the source it was read from, or
        ``None`` when it was built in memory.

        Examples
        --------
        >>> law = law_from_segments("angle", "deg", [{"to": 120, "motion": "dwell"},
        ...     {"to": 360, "motion": "cycloidal", "rise": 0}])
        >>> law.to_dict()["segment"][1]
        {'to': 360.0, 'motion': 'cycloidal', 'rise': 0.0}
        """
        factor = ANGLE_UNITS.get(self.units, 1.0) if self.output == "angle" else 1.0
        out = {"output": self.output, "units": self.units}
        if self.knots is not None:
            out["samples"] = None
            return out
        if self.start != 0.0:
            out["start"] = float(f"{self.start / factor:.12g}")
        segs = []
        for k, name in enumerate(self.motions):
            seg = {"to": float(f"{math.degrees(self.breaks[k + 1]):.12g}"), "motion": name}
            if MOTIONS[name].rises:
                seg["rise"] = float(f"{self.rises[k] / factor:.12g}")
            segs.append(seg)
        out["segment"] = segs
        return out

    def net_change(self) -> float:
        """Output change over one turn (0 for a law that returns to its start)."""
        total = float(np.sum(self.rises))
        return 0.0 if abs(total) <= 1e-12 * max(1.0, float(np.sum(np.abs(self.rises)))) else total

    def evaluate(self, theta) -> LawValues:
        """s, v, a, j per radian of input at the input angles ``theta`` (rad, wrapped mod 2 pi)."""
        th = finite_array("theta", theta)
        shape = th.shape
        th = th.ravel()
        w = np.mod(th, TWO_PI)
        s, v, a, j = (np.zeros_like(w) for _ in range(4))
        if self.knots is not None:
            x0 = float(self.knots[0][0])
            x = x0 + np.mod(w - x0, TWO_PI)
            slope = float(self.rises[0]) / TWO_PI
            sp = self._spline
            s[:] = sp(x) + slope * (x - x0)
            v[:] = sp(x, 1) + slope
            a[:] = sp(x, 2)
            j[:] = sp(x, 3)
        else:
            n = len(self.motions)
            idx = np.clip(np.searchsorted(self.breaks, w, side="right") - 1, 0, n - 1)
            cum = self.start + np.concatenate([[0.0], np.cumsum(self.rises)])
            for k, name in enumerate(self.motions):
                m = idx == k
                if not np.any(m):
                    continue
                beta = self.breaks[k + 1] - self.breaks[k]
                h = self.rises[k]
                y, dy, d2y, d3y = MOTIONS[name].derivs((w[m] - self.breaks[k]) / beta)
                s[m] = cum[k] + h * y
                v[m] = h * dy / beta
                a[m] = h * d2y / beta**2
                j[m] = h * d3y / beta**3
        return LawValues(
            th.reshape(shape),
            s.reshape(shape),
            v.reshape(shape),
            a.reshape(shape),
            j.reshape(shape),
            self.output,
            self.units,
        )

    def _ends(self, k: int, side: int) -> np.ndarray:
        """(s, v, a, j) of segment k at its start (side 0) or end (side 1)."""
        beta = self.breaks[k + 1] - self.breaks[k]
        h = self.rises[k]
        y = [float(np.asarray(d)) for d in MOTIONS[self.motions[k]].derivs(float(side))]
        base = self.start + float(np.sum(self.rises[:k]))
        return np.array([base + h * y[0], h * y[1] / beta, h * y[2] / beta**2, h * y[3] / beta**3])

    def continuity(self, tolerance: float | None = None) -> ContinuityReport:
        """Jumps of s, v, a, j at every segment boundary, the cycle's joint included."""
        unit = "rad" if self.output == "angle" else self.units
        if tolerance is None:
            tolerance = 1e-9 * max(self.scale, 1e-300)
        if self.knots is not None:
            z = np.zeros(0)
            return ContinuityReport(z, z, z, z, z, tolerance, unit)
        n = len(self.motions)
        at, jumps = [], []
        for k in range(n):
            prev = (k - 1) % n
            left = self._ends(prev, 1)
            right = self._ends(k, 0)
            if k == 0:
                left[0] -= float(np.sum(self.rises))
            at.append(self.breaks[k])
            jumps.append(right - left)
        jumps = np.array(jumps)
        return ContinuityReport(
            np.array(at), jumps[:, 0], jumps[:, 1], jumps[:, 2], jumps[:, 3], float(tolerance), unit
        )


def law_from_segments(output: str, units: str, segments, *, start: float = 0.0, source: str = "law") -> MotionLaw:
    """A :class:`MotionLaw` from segment dicts like LAW.toml's ``[[law.segment]]`` tables.

    Parameters
    ----------
    output : {"angle", "displacement"}
    units : str
        ``"deg"``/``"rad"`` for angle laws (rises given in these units), a length unit otherwise.
    segments : list of dict
        Each with ``to`` (input angle in degrees where it ends; the first
        starts at 0, the last must end at 360), ``motion`` (a name of
        :data:`gearlever.laws.motions.MOTIONS`) and ``rise`` (output change;
        absent or 0 for a dwell, negative for a return).
    start : float
        Output at input 0, in ``units``.
    source : str
        Named in error messages (the file).

    Raises
    ------
    GearleverError
        Segments not covering 0 .. 360 or overlapping, an unknown motion, a
        rise on a dwell, a missing rise, an unknown key; the message names
        ``source``, the segment and the key.

    Examples
    --------
    >>> law_from_segments("angle", "deg", [{"to": 360, "motion": "cycloid", "rise": 0}])
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: law: segment 1: motion 'cycloid' is not known (did you mean 'cycloidal'?); ...
    """
    output, units = _check_kind(output, units, source)
    if not isinstance(segments, list | tuple) or not segments:
        raise GearleverError(f"{source}: law.segment must be a non-empty list of segments")
    if len(segments) > MAX_SEGMENTS:
        raise GearleverError(f"{source}: at most {MAX_SEGMENTS} segments, got {len(segments)}")
    factor = ANGLE_UNITS.get(units, 1.0) if output == "angle" else 1.0
    ends, names, rises = [0.0], [], []
    for i, seg in enumerate(segments, 1):
        where = f"{source}: segment {i}"
        if not isinstance(seg, dict):
            raise GearleverError(f"{where}: must be a table with to, motion and rise")
        for key in seg:
            if key not in ("to", "motion", "rise"):
                raise GearleverError(
                    f"{where}: unknown key {key!r}{_did_you_mean(key, ('to', 'motion', 'rise'))}; "
                    "a segment has to, motion, rise"
                )
        if "to" not in seg:
            raise GearleverError(f"{where}: to (input angle in deg where the segment ends) is missing")
        to = seg["to"]
        if isinstance(to, bool) or not isinstance(to, int | float) or not math.isfinite(to):
            raise GearleverError(f"{where}: to must be a finite number of degrees, got {to!r}")
        to = float(to)
        if to <= ends[-1]:
            if i == 1:
                raise GearleverError(f"{where}: to must be > 0 deg (the first segment starts at 0), got {to:g}")
            raise GearleverError(
                f"{where}: to = {to:g} deg does not pass the end of segment {i - 1} at {ends[-1]:g} deg "
                "(segments overlap; each to must be larger than the one before)"
            )
        if to > 360:
            raise GearleverError(f"{where}: to = {to:g} deg is past 360 (segments must cover 0 .. 360 exactly)")
        if to - ends[-1] < MIN_SEGMENT_DEG:
            raise GearleverError(
                f"{where}: spans {to - ends[-1]:g} deg (from {ends[-1]:g} to {to:g}); a segment must span at least "
                f"{MIN_SEGMENT_DEG:g} deg"
            )
        name = seg.get("motion")
        if name is None:
            raise GearleverError(f"{where}: motion is missing; known: {', '.join(MOTIONS)}")
        if name not in MOTIONS:
            raise GearleverError(
                f"{where}: motion {name!r} is not known{_did_you_mean(name, MOTIONS)}; known: {', '.join(MOTIONS)}"
            )
        rise = seg.get("rise")
        if MOTIONS[name].rises:
            if rise is None:
                raise GearleverError(f"{where}: rise (output change over the {name} segment) is missing")
            if isinstance(rise, bool) or not isinstance(rise, int | float) or not math.isfinite(rise):
                raise GearleverError(f"{where}: rise must be a finite number, got {rise!r}")
        elif rise is not None and rise != 0:
            raise GearleverError(f"{where}: rise = {rise!r} on a dwell (a dwell does not move; remove rise)")
        ends.append(to)
        names.append(name)
        rises.append(float(rise or 0.0) * factor)
    if ends[-1] != 360:
        raise GearleverError(
            f"{source}: segment {len(segments)}: to = {ends[-1]:g} deg, the last segment must end at 360 "
            "(segments must cover 0 .. 360)"
        )
    start = finite(f"{source}: start", start) * factor
    return MotionLaw(output, units, np.radians(np.array(ends)), tuple(names), np.array(rises), start, source)


def law_from_samples(
    output: str, units: str, input_deg, values, *, source: str = "law", column: str = "output"
) -> MotionLaw:
    """A sampled :class:`MotionLaw`: a periodic cubic spline through (input_deg, values).

    The inputs must increase strictly within 0 .. 360.  If they span both 0
    and 360 the two end values may differ: the difference is the net change
    over a turn (a gear output), added as a linear term; otherwise the law
    closes on itself (the first sample repeated at +360).  The spline is
    :class:`scipy.interpolate.CubicSpline` with ``bc_type="periodic"``:
    s, v, a continuous over the whole cycle.

    Examples
    --------
    >>> x = np.arange(0, 360, 30.0)
    >>> law = law_from_samples("displacement", "mm", x, 5 - 5 * np.cos(np.radians(x)))
    >>> round(float(law.evaluate(math.pi).s), 6), law.net_change()
    (10.0, 0.0)
    """
    from scipy.interpolate import CubicSpline

    output, units = _check_kind(output, units, source)
    x = _sample_column(input_deg, source, "input_deg")
    y = _sample_column(values, source, column)
    if x.shape != y.shape or x.ndim != 1:
        raise GearleverError(f"{source}: input_deg and {column} must be two columns of equal length")
    if x.size < 4:
        raise GearleverError(f"{source}: at least 4 samples are needed, got {x.size}")
    if x.size > MAX_SAMPLES:
        raise GearleverError(f"{source}: at most {MAX_SAMPLES:,} samples, got {x.size:,}")
    dx = np.diff(x)
    if np.any(dx == 0):
        k = int(np.argmax(dx == 0)) + 1
        raise GearleverError(f"{source}: row {k + 1}: input_deg {x[k]:g} duplicates the row before")
    if np.any(dx < 0):
        k = int(np.argmax(dx < 0)) + 1
        raise GearleverError(f"{source}: row {k + 1}: input_deg {x[k]:g} after {x[k - 1]:g} (input_deg must increase)")
    if x[0] < 0 or x[-1] > 360:
        raise GearleverError(f"{source}: input_deg must lie in 0 .. 360, got {x[0]:g} .. {x[-1]:g}")
    factor = ANGLE_UNITS.get(units, 1.0) if output == "angle" else 1.0
    y = y * factor
    if x[0] == 0 and x[-1] == 360:
        net = float(y[-1] - y[0])
    else:
        x = np.append(x, x[0] + 360)
        y = np.append(y, y[0])
        net = 0.0
    th = np.radians(x)
    detr = y - net * (th - th[0]) / TWO_PI
    detr[-1] = detr[0]
    spline = CubicSpline(th, detr, bc_type="periodic")
    law = MotionLaw(
        output,
        units,
        np.array([0.0, TWO_PI]),
        ("samples",),
        np.array([net]),
        0.0,
        source,
        (th, detr),
        spline,
    )
    s0 = float(law.evaluate(0.0).s)
    return MotionLaw(output, units, law.breaks, law.motions, law.rises, s0, source, (th, detr), spline)


def _sample_column(values, source: str, column: str) -> np.ndarray:
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise GearleverError(f"{source}: column {column} must hold numbers") from None
    if arr.ndim == 1 and not np.all(np.isfinite(arr)):
        k = int(np.argmax(~np.isfinite(arr)))
        raise GearleverError(f"{source}: row {k + 1}: {column} is {float(arr[k])} (samples must be finite numbers)")
    return arr


def _read_samples(path: Path, source: str) -> tuple[np.ndarray, np.ndarray]:
    where = f"{source}: samples {str(path)!r}"
    table = read_csv_table(path, f"{source}: samples", header=None, comments=True, max_rows=MAX_SAMPLES, where=where)
    if not table.rows:
        raise GearleverError(f"{where}: no samples (rows input_deg,output)")
    # the package's one rule for a user's CSV (header optional, no column dropped silently);
    # nan and inf are refused with their sample row
    cols = table.only(("input_deg", "output"), 2).columns(("input_deg", "output"), finite=False)
    return np.array(cols["input_deg"]), np.array(cols["output"])


def load_law(path) -> MotionLaw:
    """Read a LAW.toml file (segments, or samples from a CSV beside it).

    Raises
    ------
    GearleverError
        The message starts with the file and names the table, segment or key.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "law.toml"
    >>> _ = p.write_text('[law]\\noutput = "angle"\\nunits = "deg"\\n'
    ...                  '[[law.segment]]\\nto = 360\\nmotion = "dwel"\\n')
    >>> load_law(p)
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: ...law.toml: segment 1: motion 'dwel' is not known (did you mean 'dwell'?...
    """
    p = Path(path)
    source = str(path)
    law = read_toml_table(p, "LAW", "law", ("output", "units", "segment", "samples", "start"))
    for key in ("output", "units"):
        if key not in law:
            raise GearleverError(f"{source}: [law] {key} is missing")
    output, units = _check_kind(law["output"], law["units"], source)
    if "segment" in law and "samples" in law:
        raise GearleverError(f'{source}: [law] has both [[law.segment]] tables and samples = "FILE.csv": give one')
    if "segment" not in law and "samples" not in law:
        raise GearleverError(f'{source}: [law] needs either [[law.segment]] tables or samples = "FILE.csv"')
    if "samples" in law:
        if not isinstance(law["samples"], str):
            raise GearleverError(f"{source}: [law] samples must be a CSV file name")
        x, y = _read_samples(p.parent / law["samples"], source)
        return law_from_samples(output, units, x, y, source=f"{source}: samples {law['samples']!r}")
    start = law.get("start", 0.0)
    if isinstance(start, bool) or not isinstance(start, int | float):
        raise GearleverError(f"{source}: [law] start must be a number, got {start!r}")
    return law_from_segments(output, units, law["segment"], start=start, source=source)
