"""Function generation: a four-bar (crank angle -> rocker angle) or a slider-crank (crank angle -> slider travel).

Angles are measured counter-clockwise from the ground line: for the
four-bar the line from the crank pivot ``O2`` (origin) to the rocker pivot
``O4`` (on +x); for the slider-crank the slider's line of travel (+x).  The
slider's travel ``s`` is measured along that line from the foot of the
perpendicular from ``O2``.  Three targets are met exactly, more by least
squares on the linear design equation.  Every result is checked by solving
the model as its file holds it with the mechanism engine over the whole input
range, driven from the sketch along its assembly branch.

Numeric core: numpy, :mod:`gearlever.loops`, :mod:`gearlever.mechanism`.
"""

from __future__ import annotations

import math
import numbers
import tomllib
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite_array, positive
from gearlever.errors import GearleverError, GearleverWarning
from gearlever.loops.fourbar import fourbar, grashof, transmission_angle
from gearlever.mechanism.modelfile import model_toml
from gearlever.synthesis.expr import parse_expression, shown
from gearlever.synthesis.model import fourbar_model, slider_crank_model
from gearlever.synthesis.registry import Kind, register

__all__ = [
    "FunctionTargets",
    "FunctionSynthesis",
    "precision_points",
    "function_targets",
    "synthesize_function",
    "MAX_TARGETS",
    "DENSE_POINTS",
    "MAX_DENSE_POINTS",
    "PRACTICAL_LINK_RATIO",
]

#: Most targets accepted (pairs or precision points).
MAX_TARGETS = 10_000
#: Input angles at which the synthesized linkage is solved to measure the structural error.
DENSE_POINTS = 721
#: Most input angles solved for the structural error (one batched engine call of this many rows).
MAX_DENSE_POINTS = 100_000
#: Longest over shortest link above which a synthesized linkage is reported as impractically
#: proportioned (a warning; the model is still written).  gearlever's rule of thumb, not a published
#: limit: past twenty to one the short link's pins and bearings are hard to fit against the long
#: link's loads and the output is sensitive to its length (the textbook three-position problem of
#: Su's lecture, tables/synthesis_checks.csv, has 11.3 and passes).
PRACTICAL_LINK_RATIO = 20.0
#: Longest over shortest link beyond which the targets are refused: far past any practical linkage,
#: and within the mechanism engine's own limit (a link shorter than 1e-6 of the model's size).
MAX_LINK_RATIO = 1e4
#: Largest angle (rad) and length accepted as a target, range end or ground.
MAX_ANGLE = 1e3
MAX_LENGTH = 1e12
#: An exact (three-target) synthesis must meet its targets to this fraction of the output range
#: (or of a radian); more is a branch defect.
_EXACT_TOL = 1e-9
#: A four-bar target missed by more than a quarter turn (rad) is refused: its rocker is then nearer the
#: wanted angle reversed than the wanted angle, so the half turn between the rocker link and the output
#: (:attr:`FunctionSynthesis.output_offset`) is no longer told by the motion, and the least squares has not
#: followed the output range (e.g. a rocker turning the other way from the targets over more than half a turn).
_MAX_TARGET_MISS = math.pi / 2
KINDS = ("fourbar", "slider-crank")


def precision_points(a: float, b: float, n: int, spacing: str = "chebyshev") -> np.ndarray:
    """Precision points in ``[a, b]``: Chebyshev or even spacing.

    Notes
    -----
    Chebyshev spacing ``x_j = (a + b)/2 - (b - a)/2 cos((2j - 1) pi / (2n))``,
    ``j = 1..n`` (Freudenstein, "Approximate synthesis of four-bar
    linkages", Trans. ASME 77, 1955, pp. 853-861, where the precision points
    are spaced by the zeros of a Chebyshev polynomial); even spacing puts the points
    at the ends and evenly between.

    Examples
    --------
    >>> np.round(precision_points(1.0, 2.0, 3), 4).tolist()
    [1.067, 1.5, 1.933]
    >>> precision_points(0.0, 1.0, 3, "even").tolist()
    [0.0, 0.5, 1.0]
    """
    a, b = _range("the range [a, b]", (a, b))
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 2 <= n <= MAX_TARGETS:
        raise GearleverError(f"points must be an integer from 2 to {MAX_TARGETS}, got {n!r}")
    if spacing == "chebyshev":
        j = np.arange(1, n + 1)
        return (a + b) / 2 - (b - a) / 2 * np.cos((2 * j - 1) * np.pi / (2 * n))
    if spacing == "even":
        return np.linspace(a, b, n)
    raise GearleverError(f"spacing must be 'chebyshev' or 'even', got {spacing!r}")


@dataclass(frozen=True)
class FunctionTargets(Result):
    """Targets of a function generator taken from a formula ``y = f(x)``.

    The input angle and the output map linearly on ``x`` and ``y``:
    ``phi = phi_a + (x - x_a)/(x_b - x_a) (phi_b - phi_a)`` and
    ``out = out_a + (y - y_a)/(y_b - y_a) (out_b - out_a)`` with
    ``y_a = f(x_a)``, ``y_b = f(x_b)``.

    Attributes
    ----------
    expression : str
    x : ndarray
        Precision points.
    input_angle : ndarray
        Crank angles at the precision points, radians.
    target : ndarray
        Wanted outputs there (radians for a four-bar, length for a slider).
    x_range, input_range, output_range : tuple of float

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> np.round(t.x, 3).tolist()
    [1.067, 1.5, 1.933]
    """

    expression: str
    x: np.ndarray
    input_angle: np.ndarray
    target: np.ndarray
    x_range: tuple
    input_range: tuple
    output_range: tuple

    def target_at(self, input_angle) -> np.ndarray:
        """The wanted output at crank angles (radians) by the formula and the two linear maps."""
        f = parse_expression(self.expression)
        (xa, xb), (pa, pb), (oa, ob) = self.x_range, self.input_range, self.output_range
        x = xa + (np.asarray(input_angle, dtype=float) - pa) / (pb - pa) * (xb - xa)
        ya, yb = f(np.array([xa, xb]))
        return oa + (f(x) - ya) / (yb - ya) * (ob - oa)


def _range(name: str, r) -> tuple:
    """Two different finite numbers ``(from, to)``: text and bools are refused, not read as numbers."""
    try:
        if isinstance(r, (str, bytes)):
            raise TypeError
        a, b = r
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be two numbers (from, to), got {r!r:.60}") from None
    for v in (a, b):
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise GearleverError(f"{name} must be two numbers (from, to), got {v!r:.40} in {r!r:.60}")
    a, b = float(a), float(b)
    if not (math.isfinite(a) and math.isfinite(b)):
        raise GearleverError(f"{name} must be finite, got {r!r}")
    if a == b:
        raise GearleverError(f"{name} must have a non-zero width, got [{a!r}, {b!r}]")
    return a, b


def function_targets(
    expression: str, x_range, input_range, output_range, points: int = 3, spacing: str = "chebyshev"
) -> FunctionTargets:
    """Precision points of ``y = f(x)`` mapped onto crank angles and outputs.

    Parameters
    ----------
    expression : str
        Formula in ``x`` (:func:`~gearlever.synthesis.expr.parse_expression`).
    x_range : pair of float
        ``x`` from, to.
    input_range : pair of float
        Crank angle at ``x`` from, to (radians).
    output_range : pair of float
        Output at ``f(x_from)``, ``f(x_to)``: radians (four-bar) or length (slider-crank).
    points : int
        Number of precision points (at least 3).
    spacing : {"chebyshev", "even"}

    Returns
    -------
    FunctionTargets

    Notes
    -----
    The linear maps and Chebyshev spacing of Freudenstein, "Approximate
    synthesis of four-bar linkages", Trans. ASME 77 (1955) 853-861.

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> np.round(np.degrees(t.input_angle), 3).tolist(), np.round(np.degrees(t.target), 3).tolist()
    ([49.019, 75.0, 100.981], [143.419, 187.647, 220.577])
    """
    f = parse_expression(expression)
    xr, ir, orng = _range("x_range", x_range), _range("input_range", input_range), _range("output_range", output_range)
    if abs(ir[1] - ir[0]) >= 2 * math.pi or max(abs(ir[0]), abs(ir[1])) > MAX_ANGLE:
        raise GearleverError(
            "input_range must span less than a full turn (the crank is back in the same pose after it) within "
            f"{MAX_ANGLE:g} rad of zero, got {math.degrees(ir[0]):.6g} .. {math.degrees(ir[1]):.6g} deg"
        )
    if not isinstance(spacing, str):
        raise GearleverError(f"spacing must be 'chebyshev' or 'even', got {spacing!r}")
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not 3 <= points <= MAX_TARGETS:
        raise GearleverError(f"points must be an integer from 3 to {MAX_TARGETS}, got {points!r}")
    x = precision_points(xr[0], xr[1], int(points), spacing)
    ends = f(np.array(xr))
    if not np.all(np.isfinite(ends)):
        raise GearleverError(f"expression {shown(expression)!r} is not finite at the ends of x_range {xr}")
    if ends[0] == ends[1]:
        raise GearleverError(f"expression {shown(expression)!r} has the same value at both ends of x_range {xr}")
    dense = f(np.linspace(xr[0], xr[1], DENSE_POINTS))
    if not np.all(np.isfinite(dense)):
        raise GearleverError(f"expression {shown(expression)!r} is not finite everywhere in x_range {xr}")
    t = FunctionTargets(expression, x, np.empty(0), np.empty(0), xr, ir, orng)
    phi = ir[0] + (x - xr[0]) / (xr[1] - xr[0]) * (ir[1] - ir[0])
    return FunctionTargets(expression, x, phi, t.target_at(phi), xr, ir, orng)


@dataclass(frozen=True)
class FunctionSynthesis(Result):
    """A synthesized function generator, checked by the mechanism engine on the model as written.

    Attributes
    ----------
    kind : {"fourbar", "slider-crank"}
    input_angle : ndarray
        Crank angles of the targets, radians (the design's input angle).
    target : ndarray
        Wanted outputs: rocker angle (radians) or slider travel (length).
    achieved : ndarray
        The engine's output at the targets (solving :attr:`model`).
    error : ndarray
        ``achieved - target`` (four-bar: wrapped to ``(-pi, pi]``, a rocker
        angle being a pose).
    coefficients : ndarray
        ``(K1, K2, K3)`` of the design equation (see :func:`synthesize_function`).
    lengths : dict
        ``ground, crank, coupler, rocker`` (four-bar) or ``crank, rod, offset``:
        the model's lengths, all positive except the slider's offset (signed).
    branch : str
        ``"open"``/``"crossed"`` (four-bar, :mod:`gearlever.loops.fourbar`) or
        ``"+"``/``"-"`` (slider ahead of or behind the crank pin).
    model : dict
        Model dict assembled at the first target (:mod:`gearlever.synthesis.model`),
        exactly as :func:`~gearlever.mechanism.modelfile.model_toml` writes it (coordinates at 10 digits of the size).
    dense_input, dense_target, dense_achieved : ndarray
        The input range sampled, wanted output and engine output there.
    structural_error_max, structural_error_rms : float
        Over the dense samples (output units); NaN only with a :attr:`defect`.
    transmission_range : tuple
        Smallest and largest transmission angle over the dense samples, radians
        (NaN where no sample assembles).
    grashof : str
        Grashof type (four-bar), ``"crank turns fully"`` / ``"crank rocks"`` (slider).
    defect : str
        Empty, or why the linkage cannot meet its targets on one assembly
        branch while the crank moves continuously through the range.
    exact : bool
        Three targets (met exactly).
    size : float
        Largest link length (or offset), for relative tolerances.
    evaluations : int
        Input rows solved by the mechanism engine.
    input_offset : float
        The model's crank input (the engine's absolute crank angle, radians)
        minus the design's input angle: ``0`` or ``pi`` (a crank pointing the
        other way, Freudenstein's negative ``a``) less the whole turns that
        put the sketch's angle in ``(-pi, pi]``.  Solve :attr:`model` at
        ``input_angle + input_offset``.
    output_offset : float
        Four-bar: the model's rocker angle minus the output angle, ``0`` or
        ``pi`` (Freudenstein's negative ``c``); slider-crank: ``0``.
    link_ratio : float
        Longest over shortest link (the slider's offset counts only as a
        longest); above :data:`PRACTICAL_LINK_RATIO` the proportions are
        impractical (:func:`synthesize_function` warns).

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    >>> r.kind, r.exact, r.grashof
    ('fourbar', True, 'triple-rocker')
    """

    kind: str
    input_angle: np.ndarray
    target: np.ndarray
    achieved: np.ndarray
    error: np.ndarray
    coefficients: np.ndarray
    lengths: dict
    branch: str
    model: dict
    dense_input: np.ndarray
    dense_target: np.ndarray
    dense_achieved: np.ndarray
    structural_error_max: float
    structural_error_rms: float
    transmission_range: tuple
    grashof: str
    defect: str
    exact: bool
    size: float
    evaluations: int
    input_offset: float = 0.0
    output_offset: float = 0.0
    link_ratio: float = 1.0

    def _frame_columns(self) -> dict:
        unit = "rad" if self.kind == "fourbar" else "length"
        return {
            "input_angle_rad": self.input_angle,
            f"output_{unit}": self.target,
            f"achieved_{unit}": self.achieved,
            f"error_{unit}": self.error,
        }

    def proportions(self) -> str:
        """``""``, or a sentence naming the link ratio when it exceeds :data:`PRACTICAL_LINK_RATIO`.

        Examples
        --------
        >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
        >>> synthesize_function(t.input_angle, t.target, target_at=t.target_at).proportions()
        ''
        """
        if not self.link_ratio > PRACTICAL_LINK_RATIO:
            return ""
        named = {k: v for k, v in self.lengths.items() if k != "offset" or v != 0.0}
        longest = max(named, key=lambda k: abs(named[k]))
        shortest = min((k for k in named if k != "offset"), key=lambda k: named[k])
        return (
            f"impractical proportions: the {longest} is {abs(named[longest]) / named[shortest]:.3g} times the "
            f"{shortest} (longest/shortest link {self.link_ratio:.3g}, above {PRACTICAL_LINK_RATIO:g})"
        )


def _length(name: str, v) -> float:
    """A positive finite length up to :data:`MAX_LENGTH`: a bool is not a length, text is not a number."""
    if isinstance(v, bool):
        raise GearleverError(f"{name} must be a positive length (a number), got {v!r}: a bool is not a length")
    if isinstance(v, (str, bytes)):
        raise GearleverError(f"{name} must be a positive length (a number), got the text {v!r:.40}")
    x = positive(name, v)
    if x > MAX_LENGTH:
        raise GearleverError(f"{name} must be a positive length of at most {MAX_LENGTH:g}, got {v!r}")
    return x


def _wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def _targets(input_angle, output, kind):
    phi = finite_array("input_angle", input_angle).reshape(-1)
    out = finite_array("output", output).reshape(-1)
    if phi.shape != out.shape:
        raise GearleverError(f"input_angle and output must have the same length, got {phi.size} and {out.size}")
    if phi.size < 3:
        raise GearleverError(f"function generation needs at least 3 targets, got {phi.size}")
    if phi.size > MAX_TARGETS:
        raise GearleverError(f"at most {MAX_TARGETS} targets, got {phi.size}")
    if np.abs(phi).max() > MAX_ANGLE:
        raise GearleverError(f"input_angle must be angles in radians of at most {MAX_ANGLE:g} in size")
    if kind == "fourbar" and np.abs(out).max() > MAX_ANGLE:
        raise GearleverError(f"output must be rocker angles in radians of at most {MAX_ANGLE:g} in size")
    if kind != "fourbar" and np.abs(out).max() > MAX_LENGTH:
        raise GearleverError(f"output must be slider travels of at most {MAX_LENGTH:g} in size")
    order = np.argsort(phi, kind="stable")
    if np.any(np.diff(phi[order]) == 0):
        j = int(order[int(np.flatnonzero(np.diff(phi[order]) == 0)[0]) + 1])
        raise GearleverError(f"input_angle: target {j + 1} repeats the input angle {phi[j]!r} of another target")
    return phi, out


def _error_and_angle_stats(derr, mu) -> tuple:
    """Max and RMS of the structural error, ``(min, max)`` transmission angle (NaN rows ignored; NaN if none)."""
    e, m = np.isfinite(derr).any(), np.isfinite(mu).any()
    return (
        float(np.nanmax(np.abs(derr))) if e else math.nan,
        float(np.sqrt(np.nanmean(derr**2))) if e else math.nan,
        (float(np.nanmin(mu)) if m else math.nan, float(np.nanmax(mu)) if m else math.nan),
    )


def _solve_linear(M, rhs, what):
    if not np.all(np.isfinite(M)) or not np.all(np.isfinite(rhs)):
        raise GearleverError(f"{what}: the design equations overflow (targets too large)")
    if np.linalg.matrix_rank(M, tol=1e-12 * max(1.0, np.abs(M).max())) < 3:
        raise GearleverError(f"{what}: the targets do not determine the three design coefficients (degenerate)")
    K, *_ = np.linalg.lstsq(M, rhs, rcond=None)
    return K


def _target_values(target_at, dense):
    """The wanted output over ``dense`` from the caller's ``target_at``, refused naming it when it is not usable."""
    if isinstance(target_at, str) or not callable(target_at):
        hint = (
            " (for a formula in x, pass function_targets(expression, ...).target_at)"
            if isinstance(target_at, str)
            else ""
        )
        raise GearleverError(
            "target_at must be a callable giving the wanted output at an array of crank angles (radians), "
            f"e.g. FunctionTargets.target_at, or None; got {type(target_at).__name__} {target_at!r:.40}{hint}"
        )
    try:
        want = np.asarray(target_at(dense), dtype=float)
    except (TypeError, ValueError, ArithmeticError) as exc:
        raise GearleverError(
            f"target_at must give a number at every crank angle of the range (it raised {type(exc).__name__})"
        ) from None
    if want.shape != dense.shape or not np.all(np.isfinite(want)):
        raise GearleverError("target_at must give a finite output at every crank angle of the range")
    return want


def synthesize_function(
    input_angle,
    output,
    *,
    kind: str = "fourbar",
    ground: float = 1.0,
    target_at: Callable | None = None,
    input_range=None,
    dense_points: int = DENSE_POINTS,
    name: str = "",
) -> FunctionSynthesis:
    """Synthesize a function generator through targets (exact for three, least squares for more).

    Parameters
    ----------
    input_angle : array_like
        Crank angles of the targets, radians from the ground line (any
        start, either direction; the targets and ``input_range`` together
        span less than a full turn).
    output : array_like
        Wanted rocker angles (radians from the ground line O2->O4) for a
        four-bar, or slider travels (length along the slider line from the
        foot of the perpendicular from O2) for a slider-crank.
    kind : {"fourbar", "slider-crank"}
    ground : float
        Scale: the ground link ``|O2 O4|`` of the four-bar, a positive
        length (not a bool, not text); the slider-crank is scaled by its
        travels and ignores it.
    target_at : callable, optional
        Wanted output as a function of an array of crank angles (radians)
        for the structural error over the range, e.g.
        :meth:`FunctionTargets.target_at`; default: straight lines between the
        targets in order of input angle (four-bar: each rocker angle taken
        within half a turn of the one before).
    input_range : pair of float, optional
        Crank angles (radians) of the ends of the design range: the
        structural error, the dead-point check and the transmission angle
        then cover it (with the span of the targets), e.g.
        :attr:`FunctionTargets.input_range`, whose Chebyshev-spaced targets
        lie inside it.  Default: the span of the targets.
    dense_points : int
        Samples of the input range for the structural error, 2 to
        :data:`MAX_DENSE_POINTS`.
    name : str
        Model name.

    Returns
    -------
    FunctionSynthesis

    Warns
    -----
    GearleverWarning
        When the longest link is more than :data:`PRACTICAL_LINK_RATIO`
        times the shortest (:meth:`FunctionSynthesis.proportions`): the
        ratios follow from the targets, not from ``ground``.

    Notes
    -----
    Four-bar: with ground ``d``, crank ``a``, coupler ``b``, rocker ``c``,
    crank angle ``phi`` and rocker angle ``psi``, the loop closure gives
    Freudenstein's equation (F. Freudenstein, "Approximate synthesis of
    four-bar linkages", Trans. ASME 77, 1955, pp. 853-861; also Norton,
    *Design of Machinery*, chapter on analytical linkage synthesis)::

        K1 cos(psi) - K2 cos(phi) + K3 = cos(phi - psi),
        K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c),

    linear in ``K``: three targets give it exactly, more by least squares
    (the equation error; the structural error is then measured).  A negative
    ``a`` (``c``) is the crank (rocker) pointing the other way: the model
    has the positive length ``|a|`` (``|c|``) and its link angle is
    ``phi + pi`` (``psi + pi``), recorded in
    :attr:`FunctionSynthesis.input_offset` (``output_offset``).
    Slider-crank (offset ``e``, crank ``a``, rod ``b``): ``(s - a cos phi)^2
    + (e - a sin phi)^2 = b^2`` is linear in ``(2a, 2ae, b^2 - a^2 - e^2)``:
    ``K1 s cos(phi) + K2 sin(phi) + K3 = s^2``; a negative ``a`` is again the
    crank reversed.

    The linkage is assembled at the first target on the branch nearest to
    its output, and the model is written to text and read back
    (:func:`~gearlever.mechanism.modelfile.model_toml`) so that what is checked
    is what a file holds.  The mechanism engine then solves that model over
    the targets and the whole range in one batched call, continuing from
    the sketch along its branch (:func:`gearlever.mechanism.solve.solve`):
    a row it cannot reach (a dead point or a branch change between the
    targets) is a :attr:`FunctionSynthesis.defect`, and the achieved
    outputs and the structural error are the engine's.  A four-bar that
    misses a target by more than a quarter turn is refused (GearleverError
    naming ``output``): its rocker is then nearer the reverse of the wanted
    angle, the half turn between rocker link and output is no longer told
    by the motion, and no error it could report would be the design's.

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    >>> bool(np.abs(r.error).max() < 1e-9), r.grashof, r.defect
    (True, 'triple-rocker', '')
    >>> round(float(np.degrees(r.structural_error_max)), 3)
    0.127
    >>> r = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
    >>> round(float(np.degrees(r.structural_error_max)), 3)  # the ends of the range 45..105 deg too
    0.169
    """
    if not isinstance(kind, str) or kind not in KINDS:
        raise GearleverError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    phi, out = _targets(input_angle, output, kind)
    d = _length("ground", ground)
    if isinstance(dense_points, bool) or not isinstance(dense_points, (int, np.integer)):
        raise GearleverError(f"dense_points must be an integer from 2 to {MAX_DENSE_POINTS}, got {dense_points!r}")
    if not 2 <= dense_points <= MAX_DENSE_POINTS:
        raise GearleverError(f"dense_points must be an integer from 2 to {MAX_DENSE_POINTS}, got {dense_points!r}")
    if not isinstance(name, str):
        raise GearleverError(f"name must be text, got {type(name).__name__}")
    lo, hi = float(phi.min()), float(phi.max())
    if input_range is not None:
        ra, rb = _range("input_range", input_range)
        lo, hi = min(lo, ra, rb), max(hi, ra, rb)
    if hi - lo >= 2 * math.pi:
        raise GearleverError(
            f"input_angle: the targets{' and input_range' if input_range is not None else ''} span "
            f"{math.degrees(hi - lo):.6g} deg; a crank is back in the same pose after a full turn, "
            "so the span must be less than 360 deg"
        )
    dense = np.linspace(lo, hi, int(dense_points))
    if target_at is None:
        order = np.argsort(phi)
        # rocker angles are poses: a target given a turn away from its neighbour is the same pose
        seq = np.unwrap(out[order]) if kind == "fourbar" else out[order]
        want = np.interp(dense, phi[order], seq)
    else:
        want = _target_values(target_at, dense)
    solve, default_name = _SOLVERS[kind]
    r = solve(phi, out, d, dense, want, name or default_name)
    note = "" if r.defect else r.proportions()
    if note:
        warnings.warn(
            f"{note}; the ratios follow from the targets (input and output ranges), not from the scale",
            GearleverWarning,
            stacklevel=2,
        )
    return r


def _written(model: dict) -> dict:
    """The model as its file holds it: written to TOML text and read back (15 significant digits)."""
    return tomllib.loads(model_toml(model))


def _engine(model, phi, dense, out0, output):
    """Solve the written model over the targets and the range in one batched call, continuing from the sketch.

    ``output(res)`` gives the raw output per row (rocker angle in the design's
    frame, or slider travel).  The rows run from target 1 (the sketch) down
    to the low end of the range, then from target 1 up to the high end, so
    that the continuation meets a dead point next to the last row it
    reached; the engine's crank input of a row is the sketch's angle plus
    the input's change from target 1.  Returns ``(achieved at the targets,
    over the range, defect, input_offset, rows solved)``.
    """
    from gearlever.mechanism import Mechanism

    try:
        mech = Mechanism.from_dict(model)
    except GearleverError as exc:
        raise GearleverError(f"the synthesized linkage is not a model the engine can solve: {exc}") from None
    q_sketch = float(mech.sketch_inputs[0])
    rows = np.concatenate([phi, dense])
    idx = np.arange(rows.size)
    down = idx[rows <= phi[0]]
    down = down[np.lexsort((down != 0, -rows[down]))]  # target 1 first, then descending
    up = idx[rows > phi[0]]
    up = up[np.argsort(rows[up], kind="stable")]
    order = np.concatenate([down, up])
    res = mech.solve((q_sketch + (rows[order] - phi[0]))[:, None])
    raw = np.where(res.closed, output(res), np.nan)
    defect = ""
    if not res.closed.all():
        k = int(np.flatnonzero(~res.closed)[0])
        prev = 0 if k == down.size else k - 1  # the up leg starts again from target 1
        frm, to = sorted((math.degrees(rows[order[prev]]), math.degrees(rows[order[k]])))
        defect = (
            f"the linkage meets a dead point between the input angles {frm:.6g} and {to:.6g} deg: driven from "
            "target 1, the written model cannot pass it on one branch (circuit/branch defect)"
        )
    elif out0 is not None:
        # a continuous angle along each leg from target 1, equal there to the wanted output within half a turn
        raw[0] = out0 + _wrap(raw[0] - out0)
        raw[: down.size] = np.unwrap(raw[: down.size])
        raw[down.size :] = np.unwrap(np.concatenate([[raw[0]], raw[down.size :]]))[1:]
    gen = np.empty_like(raw)
    gen[order] = raw
    n = phi.size
    return gen[:n], gen[n:], defect, q_sketch - float(phi[0]), int(rows.size)


def _fourbar(phi, psi, d, dense, want, name):
    M = np.column_stack([np.cos(psi), -np.cos(phi), np.ones_like(phi)])
    K = _solve_linear(M, np.cos(phi - psi), "input_angle/output")
    K1, K2, K3 = (float(k) for k in K)
    if abs(K1) < 1e-12 or abs(K2) < 1e-12:
        raise GearleverError("the targets need an infinitely long crank or rocker (K1 or K2 is 0); change the ranges")
    a, c = d / K1, d / K2  # signed: Freudenstein's a < 0 (c < 0) is the crank (rocker) reversed
    b2 = a * a + c * c + d * d - 2 * a * c * K3
    if not (math.isfinite(b2) and b2 > 0):
        raise GearleverError(f"no real four-bar meets these targets (coupler length squared {b2:.6g} <= 0)")
    b = math.sqrt(b2)
    A_, C_ = abs(a), abs(c)
    longest = max(d, A_, b, C_)
    if longest > MAX_LINK_RATIO * min(d, A_, b, C_):
        raise GearleverError(
            f"the targets need a linkage whose longest link is more than {MAX_LINK_RATIO:g} times its shortest "
            f"(ground {d:.6g}, crank {A_:.6g}, coupler {b:.6g}, rocker {C_:.6g}); change the ranges"
        )
    if longest >= (d + A_ + b + C_ - longest) * (1 - 1e-12):
        raise GearleverError("the synthesized four-bar cannot assemble (one link as long as the other three)")
    off_a = 0.0 if a > 0 else math.pi
    off_c = 0.0 if c > 0 else math.pi
    # branch: the one that puts the rocker nearest the first target's output (closed form)
    best = None
    for branch in ("open", "crossed"):
        r = fourbar(d, A_, b, C_, phi + off_a, branch=branch)
        miss = np.abs(_wrap(r.theta4 - off_c - psi))
        miss = np.where(np.isfinite(miss), miss, np.inf)
        key = (miss[0], float(np.max(miss)))
        if best is None or key < best[0]:
            best = (key, branch, r, miss)
    _, branch, r, miss = best
    th4 = float(r.theta4[0])
    if not math.isfinite(th4):
        raise GearleverError(
            f"the synthesized four-bar cannot be assembled at target 1 (input {math.degrees(phi[0]):.6g} deg): "
            "the least-squares linkage does not reach every crank angle of the range; change the ranges or the points"
        )
    # sketch at the first target on that branch, positive lengths, the reversed links by pi
    A = (A_ * math.cos(phi[0] + off_a), A_ * math.sin(phi[0] + off_a))
    B = (d + C_ * math.cos(th4), C_ * math.sin(th4))
    model = _written(fourbar_model((0.0, 0.0), (d, 0.0), A, B, name=name))

    def rocker(res):
        P, O = res.point["B"], res.point["O4"]
        return np.arctan2(P[:, 1] - O[:, 1], P[:, 0] - O[:, 0]) - off_c

    gen_t, gen_d, defect, q_off, evals = _engine(model, phi, dense, float(psi[0]), rocker)
    n = phi.size
    if not defect and n == 3:
        # exact: every target on the sketch's branch; one met only on the other branch is a branch defect
        other = fourbar(d, A_, b, C_, phi + off_a, branch="crossed" if branch == "open" else "open")
        miss_other = np.abs(_wrap(other.theta4 - off_c - psi))
        miss_t = np.abs(_wrap(gen_t - psi))
        worse = (miss_t > _EXACT_TOL) & (miss_other < miss_t)
        if np.any(worse):
            j = int(np.flatnonzero(worse)[0])
            defect = f"target {j + 1} is reached only on the other assembly branch (branch defect)"
    miss_t = np.abs(_wrap(gen_t - psi))
    if not defect and np.nanmax(miss_t) > _MAX_TARGET_MISS:
        j = int(np.nanargmax(miss_t))
        raise GearleverError(
            f"output: the synthesized four-bar misses target {j + 1} by {math.degrees(miss_t[j]):.4g} deg "
            f"(more than a quarter turn: its rocker points nearer the reverse of the wanted angle), so it does not "
            f"follow the wanted output over the range; change the output range, the input range or the points"
        )
    mu = transmission_angle(d, A_, b, C_, dense + off_a)
    return FunctionSynthesis(
        "fourbar",
        phi,
        psi,
        gen_t,
        _wrap(gen_t - psi),
        np.array([K1, K2, K3]),
        {"ground": d, "crank": A_, "coupler": b, "rocker": C_},
        branch,
        model,
        dense,
        want,
        gen_d,
        *_error_and_angle_stats(gen_d - want, mu),
        grashof(d, A_, b, C_).kind,
        defect,
        n == 3,
        longest,
        evals,
        q_off,
        off_c,
        longest / min(d, A_, b, C_),
    )


def _slider(phi, s, dense, want, name):
    M = np.column_stack([s * np.cos(phi), np.sin(phi), np.ones_like(phi)])
    K = _solve_linear(M, s * s, "input_angle/output")
    K1, K2, K3 = (float(k) for k in K)
    if abs(K1) < 1e-12 * max(1.0, float(np.abs(s).max())):
        raise GearleverError("the targets need a crank of zero length (K1 = 0); change the ranges")
    a = K1 / 2  # signed: a < 0 is the crank reversed
    e = K2 / K1
    b2 = K3 + a * a + e * e
    if not (math.isfinite(b2) and b2 > 0):
        raise GearleverError(f"no real slider-crank meets these targets (rod length squared {b2:.6g} <= 0)")
    b = math.sqrt(b2)
    A_ = abs(a)
    scale = max(A_, b, abs(e), float(np.abs(s).max()))
    if max(A_, b, abs(e)) > MAX_LINK_RATIO * min(A_, b):
        raise GearleverError(
            f"the targets need a slider-crank whose longest length is more than {MAX_LINK_RATIO:g} times its "
            f"shortest link (crank {A_:.6g}, rod {b:.6g}, offset {e:.6g}); change the ranges"
        )
    allphi = np.concatenate([phi, dense])
    h = e - a * np.sin(allphi)
    with np.errstate(invalid="ignore"):
        root = np.sqrt(b2 - h * h)
    base = a * np.cos(allphi)
    n = phi.size
    cands = {"+": base + root, "-": base - root}
    miss = {k: np.abs(v[:n] - s) for k, v in cands.items()}
    branch = min(cands, key=lambda k: (np.nan_to_num(miss[k][0], nan=np.inf), np.nanmax(miss[k])))
    other = "-" if branch == "+" else "+"
    s0 = float(cands[branch][0])
    if not math.isfinite(s0):
        raise GearleverError(
            f"the synthesized slider-crank cannot be assembled at target 1 (input {math.degrees(phi[0]):.6g} deg): "
            "the rod does not reach the slider line there; change the ranges or the points"
        )
    off_a = 0.0 if a > 0 else math.pi
    A = (A_ * math.cos(phi[0] + off_a), A_ * math.sin(phi[0] + off_a))
    model = _written(slider_crank_model((0.0, 0.0), A, (s0, e), name=name))
    gen_t, gen_d, defect, q_off, evals = _engine(model, phi, dense, None, lambda res: res.point["B"][:, 0])
    if not defect and n == 3:
        err = np.abs(gen_t - s)
        worse = (err > 1e-9 * scale) & (miss[other] < err)
        if np.any(worse):
            defect = f"target {int(np.flatnonzero(worse)[0]) + 1} is reached only on the other branch (branch defect)"
    rod = np.arctan2(h[n:], root[n:] if branch == "+" else -root[n:])  # rod angle from B to A seen along the line
    mu = np.arccos(np.clip(np.abs(np.sin(rod)), 0.0, 1.0))
    return FunctionSynthesis(
        "slider-crank",
        phi,
        s,
        gen_t,
        gen_t - s,
        np.array([K1, K2, K3]),
        {"crank": A_, "rod": b, "offset": e},
        branch,
        model,
        dense,
        want,
        gen_d,
        *_error_and_angle_stats(gen_d - want, mu),
        "crank turns fully" if b > A_ + abs(e) else "crank rocks",
        defect,
        n == 3,
        scale,
        evals,
        q_off,
        0.0,
        max(A_, b, abs(e)) / min(A_, b),
    )


def _slider_scaled(phi, s, d, dense, want, name):
    """:func:`_slider` with the four-bar's arguments (the slider-crank is scaled by its travels, not ``d``)."""
    return _slider(phi, s, dense, want, name)


#: kind -> (solver, default model name).
_SOLVERS = {
    "fourbar": (_fourbar, "synthesized four-bar function generator"),
    "slider-crank": (_slider_scaled, "synthesized slider-crank function generator"),
}


def _example_fourbar() -> tuple:
    """Three Chebyshev precision points of ``log10`` on 1..2 (crank 45..105 deg, rocker 135..225 deg)."""
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    return (t.input_angle, t.target), {"target_at": t.target_at}


def _example_slider() -> tuple:
    """Six travels of a known offset slider-crank (crank 2, rod 5, offset 1) for crank angles 10..150 deg."""
    phi = np.radians(np.linspace(10, 150, 6))
    return (phi, 2 * np.cos(phi) + np.sqrt(25 - (1 - 2 * np.sin(phi)) ** 2)), {}


for _order, (_name, _what, _example) in enumerate(
    [
        ("fourbar", "four-bar function generator by Freudenstein's equation", _example_fourbar),
        ("slider-crank", "offset slider-crank function generator (slider travel)", _example_slider),
    ]
):
    register(
        Kind(
            "function",
            _name,
            f"{_what}: exact through three precision points, least squares through more",
            "gearlever.synthesis.function:synthesize_function",
            searched=False,
            order=_order,
            example=_example,
        )
    )
