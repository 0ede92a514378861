"""Function generation: a four-bar (crank angle -> rocker angle) or a slider-crank (crank angle -> slider travel).

Angles are measured counter-clockwise from the ground line: for the
four-bar the line from the crank pivot ``O2`` (origin) to the rocker pivot
``O4`` (on +x); for the slider-crank the slider's line of travel (+x).  The
slider's travel ``s`` is measured along that line from the foot of the
perpendicular from ``O2``.  Three targets are met exactly, more by least
squares on the linear design equation.  Every result is checked by solving
the synthesized model with the mechanism engine over the whole input range.

Numeric core: numpy, :mod:`gearlever.loops`, :mod:`gearlever.mechanism`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.loops.fourbar import fourbar, grashof, transmission_angle
from gearlever.synthesis._model import fourbar_model, slider_crank_model
from gearlever.synthesis.expr import parse_expression

__all__ = [
    "FunctionTargets",
    "FunctionSynthesis",
    "precision_points",
    "function_targets",
    "synthesize_function",
    "MAX_TARGETS",
    "DENSE_POINTS",
]

#: Most targets accepted (pairs or precision points).
MAX_TARGETS = 10_000
#: Input angles at which the synthesized linkage is solved to measure the structural error.
DENSE_POINTS = 721
#: An exact (three-target) synthesis must meet its targets to this fraction of the output range
#: (or of a radian); more is a branch defect.
_EXACT_TOL = 1e-9
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
    a, b = float(a), float(b)
    if not (math.isfinite(a) and math.isfinite(b)) or not b != a:
        raise GearleverError(f"range must be two different finite numbers, got [{a!r}, {b!r}]")
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
    output : ndarray
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
    output: np.ndarray
    x_range: tuple
    input_range: tuple
    output_range: tuple

    def desired(self, input_angle) -> np.ndarray:
        """The wanted output at crank angles (radians) by the formula and the two linear maps."""
        f = parse_expression(self.expression)
        (xa, xb), (pa, pb), (oa, ob) = self.x_range, self.input_range, self.output_range
        x = xa + (np.asarray(input_angle, dtype=float) - pa) / (pb - pa) * (xb - xa)
        ya, yb = f(np.array([xa, xb]))
        return oa + (f(x) - ya) / (yb - ya) * (ob - oa)


def _range(name: str, r) -> tuple:
    try:
        a, b = (float(v) for v in r)
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be two numbers (from, to), got {r!r}") from None
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
    >>> np.round(np.degrees(t.input_angle), 3).tolist(), np.round(np.degrees(t.output), 3).tolist()
    ([49.019, 75.0, 100.981], [143.419, 187.647, 220.577])
    """
    f = parse_expression(expression)
    xr, ir, orng = _range("x_range", x_range), _range("input_range", input_range), _range("output_range", output_range)
    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not 3 <= points <= MAX_TARGETS:
        raise GearleverError(f"points must be an integer from 3 to {MAX_TARGETS}, got {points!r}")
    x = precision_points(xr[0], xr[1], int(points), spacing)
    ends = f(np.array(xr))
    if not np.all(np.isfinite(ends)):
        raise GearleverError(f"expression {expression!r} is not finite at the ends of x_range {xr}")
    if ends[0] == ends[1]:
        raise GearleverError(f"expression {expression!r} has the same value at both ends of x_range {xr}")
    dense = f(np.linspace(xr[0], xr[1], DENSE_POINTS))
    if not np.all(np.isfinite(dense)):
        raise GearleverError(f"expression {expression!r} is not finite everywhere in x_range {xr}")
    t = FunctionTargets(expression, x, np.empty(0), np.empty(0), xr, ir, orng)
    phi = ir[0] + (x - xr[0]) / (xr[1] - xr[0]) * (ir[1] - ir[0])
    return FunctionTargets(expression, x, phi, t.desired(phi), xr, ir, orng)


@dataclass(frozen=True)
class FunctionSynthesis(Result):
    """A synthesized function generator, checked by the mechanism engine.

    Attributes
    ----------
    kind : {"fourbar", "slider-crank"}
    input_angle : ndarray
        Crank angles of the targets, radians.
    output : ndarray
        Wanted outputs: rocker angle (radians) or slider travel (length).
    generated : ndarray
        The engine's output at the targets.
    error : ndarray
        ``generated - output``.
    coefficients : ndarray
        ``(K1, K2, K3)`` of the design equation (see :func:`synthesize_function`).
    lengths : dict
        ``ground, crank, coupler, rocker`` (four-bar) or ``crank, rod, offset``.
    branch : str
        ``"open"``/``"crossed"`` (four-bar, :mod:`gearlever.loops.fourbar`) or
        ``"+"``/``"-"`` (slider ahead of or behind the crank pin).
    model : dict
        Model dict assembled at the first target (:mod:`gearlever.synthesis._model`).
    dense_input, dense_desired, dense_generated : ndarray
        The input range sampled, wanted output and engine output there.
    structural_error_max, structural_error_rms : float
        Over the dense samples (output units).
    transmission_angle_min, transmission_angle_max : float
        Radians, over the dense samples.
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

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> r = synthesize_function(t.input_angle, t.output, desired=t.desired)
    >>> r.kind, r.exact, r.grashof
    ('fourbar', True, 'triple-rocker')
    """

    kind: str
    input_angle: np.ndarray
    output: np.ndarray
    generated: np.ndarray
    error: np.ndarray
    coefficients: np.ndarray
    lengths: dict
    branch: str
    model: dict
    dense_input: np.ndarray
    dense_desired: np.ndarray
    dense_generated: np.ndarray
    structural_error_max: float
    structural_error_rms: float
    transmission_angle_min: float
    transmission_angle_max: float
    grashof: str
    defect: str
    exact: bool
    size: float
    evaluations: int

    def _frame_columns(self) -> dict:
        unit = "rad" if self.kind == "fourbar" else "length"
        return {
            "input_angle_rad": self.input_angle,
            f"output_{unit}": self.output,
            f"generated_{unit}": self.generated,
            f"error_{unit}": self.error,
        }


def _wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def _targets(input_angle, output):
    try:
        phi = np.asarray(input_angle, dtype=float).reshape(-1)
        out = np.asarray(output, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise GearleverError("input_angle and output must be arrays of numbers") from None
    if phi.shape != out.shape:
        raise GearleverError(f"input_angle and output must have the same length, got {phi.size} and {out.size}")
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(out))):
        raise GearleverError("input_angle and output must be finite (found NaN or inf)")
    if phi.size < 3:
        raise GearleverError(f"function generation needs at least 3 targets, got {phi.size}")
    if phi.size > MAX_TARGETS:
        raise GearleverError(f"at most {MAX_TARGETS} targets, got {phi.size}")
    order = np.argsort(phi, kind="stable")
    if np.any(np.diff(phi[order]) == 0):
        j = int(order[int(np.flatnonzero(np.diff(phi[order]) == 0)[0]) + 1])
        raise GearleverError(f"input_angle: target {j + 1} repeats the input angle {phi[j]!r} of another target")
    return phi, out


def _error_and_angle_stats(derr, mu) -> tuple:
    """Max and RMS of the structural error, min and max transmission angle (NaN rows ignored; NaN if none)."""
    e, m = np.isfinite(derr).any(), np.isfinite(mu).any()
    return (
        float(np.nanmax(np.abs(derr))) if e else math.nan,
        float(np.sqrt(np.nanmean(derr**2))) if e else math.nan,
        float(np.nanmin(mu)) if m else math.nan,
        float(np.nanmax(mu)) if m else math.nan,
    )


def _solve_linear(M, rhs, what):
    if np.linalg.matrix_rank(M, tol=1e-12 * max(1.0, np.abs(M).max())) < 3:
        raise GearleverError(f"{what}: the targets do not determine the three design coefficients (degenerate)")
    K, *_ = np.linalg.lstsq(M, rhs, rcond=None)
    return K


def synthesize_function(
    input_angle,
    output,
    *,
    kind: str = "fourbar",
    ground: float = 1.0,
    desired: Callable | None = None,
    input_range=None,
    dense_points: int = DENSE_POINTS,
    name: str = "",
) -> FunctionSynthesis:
    """Synthesize a function generator through targets (exact for three, least squares for more).

    Parameters
    ----------
    input_angle : array_like
        Crank angles of the targets, radians from the ground line.
    output : array_like
        Wanted rocker angles (radians from the ground line O2->O4) for a
        four-bar, or slider travels (length along the slider line from the
        foot of the perpendicular from O2) for a slider-crank.
    kind : {"fourbar", "slider-crank"}
    ground : float
        Scale: the ground link ``|O2 O4|`` of the four-bar (the slider-crank
        is scaled by its travels).
    desired : callable, optional
        Wanted output as a function of crank angle (radians) for the
        structural error over the range; default: straight lines between
        the targets in order of input angle.
    input_range : pair of float, optional
        Crank angles (radians) of the ends of the design range: the
        structural error, the dead-point check and the transmission angle
        then cover it (with the span of the targets), e.g.
        :attr:`FunctionTargets.input_range`, whose Chebyshev-spaced targets
        lie inside it.  Default: the span of the targets.
    dense_points : int
        Samples of the input range for the structural error.
    name : str
        Model name.

    Returns
    -------
    FunctionSynthesis

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
    ``a`` (``c``) is the crank (rocker) pointing the other way: its link
    angle is ``phi + pi`` (``psi + pi``).
    Slider-crank (offset ``e``, crank ``a``, rod ``b``): ``(s - a cos phi)^2
    + (e - a sin phi)^2 = b^2`` is linear in ``(2a, 2ae, b^2 - a^2 - e^2)``:
    ``K1 s cos(phi) + K2 sin(phi) + K3 = s^2``.
    The linkage is assembled at the first target on the branch nearest to
    its output, solved in closed form (:func:`gearlever.loops.fourbar.fourbar`)
    over the range to find dead points and branch changes, and by the
    mechanism engine for the reported outputs.

    Examples
    --------
    >>> t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    >>> r = synthesize_function(t.input_angle, t.output, desired=t.desired)
    >>> bool(np.abs(r.error).max() < 1e-9), r.grashof, r.defect
    (True, 'triple-rocker', '')
    >>> round(float(np.degrees(r.structural_error_max)), 3)
    0.127
    >>> r = synthesize_function(t.input_angle, t.output, desired=t.desired, input_range=t.input_range)
    >>> round(float(np.degrees(r.structural_error_max)), 3)  # the ends of the range 45..105 deg too
    0.169
    """
    phi, out = _targets(input_angle, output)
    if kind not in KINDS:
        raise GearleverError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    if isinstance(dense_points, bool) or not isinstance(dense_points, (int, np.integer)) or not 2 <= dense_points:
        raise GearleverError(f"dense_points must be an integer >= 2, got {dense_points!r}")
    dense_points = min(int(dense_points), 100_000)
    lo, hi = float(phi.min()), float(phi.max())
    if input_range is not None:
        ra, rb = _range("input_range", input_range)
        lo, hi = min(lo, ra, rb), max(hi, ra, rb)
    dense = np.linspace(lo, hi, dense_points)
    if desired is None:
        order = np.argsort(phi)
        want = np.interp(dense, phi[order], out[order])
    else:
        want = np.asarray(desired(dense), dtype=float)
        if want.shape != dense.shape or not np.all(np.isfinite(want)):
            raise GearleverError("desired must give a finite output at every crank angle of the range")
    if kind == "fourbar":
        return _fourbar(phi, out, float(ground), dense, want, name or "synthesized four-bar function generator")
    return _slider(phi, out, dense, want, name or "synthesized slider-crank function generator")


def _fourbar(phi, psi, d, dense, want, name):
    if not (math.isfinite(d) and d > 0):
        raise GearleverError(f"ground must be a positive length, got {d!r}")
    M = np.column_stack([np.cos(psi), -np.cos(phi), np.ones_like(phi)])
    K = _solve_linear(M, np.cos(phi - psi), "input_angle/output")
    K1, K2, K3 = (float(k) for k in K)
    if abs(K1) < 1e-12 or abs(K2) < 1e-12:
        raise GearleverError("the targets need an infinitely long crank or rocker (K1 or K2 is 0); change the ranges")
    a, c = d / K1, d / K2
    b2 = a * a + c * c + d * d - 2 * a * c * K3
    if not b2 > 0:
        raise GearleverError(f"no real four-bar meets these targets (coupler length squared {b2:.6g} <= 0)")
    b = math.sqrt(b2)
    A_, C_ = abs(a), abs(c)
    longest = max(d, A_, b, C_)
    if longest >= (d + A_ + b + C_ - longest) * (1 - 1e-12):
        raise GearleverError("the synthesized four-bar cannot assemble (one link as long as the other three)")
    off_a = 0.0 if a > 0 else math.pi
    off_c = 0.0 if c > 0 else math.pi
    # branch: the one that puts the rocker nearest the first target's output
    best = None
    for branch in ("open", "crossed"):
        r = fourbar(d, A_, b, C_, np.concatenate([phi, dense]) + off_a, branch=branch)
        gen = r.theta4 - off_c
        miss = np.abs(_wrap(gen[: phi.size] - psi))
        miss = np.where(np.isfinite(miss), miss, np.inf)
        key = (miss[0], float(np.max(miss)))
        if best is None or key < best[0]:
            best = (key, branch, r, miss)
    _, branch, r, miss = best
    other = fourbar(d, A_, b, C_, phi + off_a, branch="crossed" if branch == "open" else "open")
    miss_other = np.abs(_wrap(other.theta4 - off_c - psi))
    defect = ""
    n = phi.size
    dense_r_valid = r.valid[n:]
    if not dense_r_valid.all():
        bad = dense[int(np.flatnonzero(~dense_r_valid)[0])]
        defect = (
            f"the linkage meets a dead point or cannot close at crank angle {math.degrees(bad):.6g} deg "
            "between the targets (circuit/branch defect)"
        )
    else:
        tol = max(_EXACT_TOL, 1e-9) if n == 3 else np.inf
        worse = (miss > tol) & (miss_other < miss)
        if np.any(worse):
            j = int(np.flatnonzero(worse)[0])
            defect = f"target {j + 1} is reached only on the other assembly branch (branch defect)"
    # sketch at the first target on that branch
    th4 = float(r.theta4[0])
    A = (a * math.cos(phi[0]), a * math.sin(phi[0]))
    B = (d + C_ * math.cos(th4), C_ * math.sin(th4))
    if not np.isfinite(th4):
        raise GearleverError("the synthesized four-bar cannot assemble at the first target")
    model = fourbar_model((0.0, 0.0), (d, 0.0), A, B, name=name)
    gen_t, gen_d, evals = _engine_outputs(model, phi + off_a, dense + off_a, "O4", "B", off_c, psi[0])
    err = gen_t - psi
    derr = gen_d - want
    mu = transmission_angle(d, A_, b, C_, dense + off_a)
    g = grashof(d, A_, b, C_).kind
    return FunctionSynthesis(
        "fourbar",
        phi,
        psi,
        gen_t,
        err,
        np.array([K1, K2, K3]),
        {"ground": d, "crank": A_, "coupler": b, "rocker": C_},
        branch,
        model,
        dense,
        want,
        gen_d,
        *_error_and_angle_stats(derr, mu),
        g,
        defect,
        n == 3,
        longest,
        evals,
    )


def _engine_outputs(model, q_targets, q_dense, pivot, pin, offset, ref, slider=False):
    """Outputs at the targets and over the range from the mechanism engine (continuation from the sketch)."""
    from gearlever.mechanism import Mechanism

    mech = Mechanism.from_dict(model)
    q = np.concatenate([q_targets, q_dense])
    res = mech.solve(q[:, None])
    P = res.point[pin]
    if slider:
        gen = np.where(res.closed, P[:, 0], np.nan)
    else:
        O = res.point[pivot]
        raw = np.arctan2(P[:, 1] - O[:, 1], P[:, 0] - O[:, 0]) - offset
        # the output as a continuous angle near the first target's
        gen = np.where(res.closed, ref + _wrap(raw - ref), np.nan)
        gen = np.where(res.closed, gen, np.nan)
    n = q_targets.size
    return gen[:n], gen[n:], int(q.size)


def _slider(phi, s, dense, want, name):
    M = np.column_stack([s * np.cos(phi), np.sin(phi), np.ones_like(phi)])
    K = _solve_linear(M, s * s, "input_angle/output")
    K1, K2, K3 = (float(k) for k in K)
    if abs(K1) < 1e-12 * max(1.0, float(np.abs(s).max())):
        raise GearleverError("the targets need a crank of zero length (K1 = 0); change the ranges")
    a = K1 / 2
    e = K2 / K1
    b2 = K3 + a * a + e * e
    if not b2 > 0:
        raise GearleverError(f"no real slider-crank meets these targets (rod length squared {b2:.6g} <= 0)")
    b = math.sqrt(b2)
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
    scale = max(abs(a), b, abs(e), float(np.abs(s).max()))
    defect = ""
    dense_ok = np.isfinite(root[n:]) & (root[n:] > 1e-9 * scale)
    if not dense_ok.all():
        bad = dense[int(np.flatnonzero(~dense_ok)[0])]
        defect = (
            f"the rod cannot reach the slider line or is at a dead point at crank angle {math.degrees(bad):.6g} deg "
            "between the targets (branch defect)"
        )
    elif n == 3:
        worse = (miss[branch] > 1e-9 * scale) & (miss[other] < miss[branch])
        if np.any(worse):
            defect = f"target {int(np.flatnonzero(worse)[0]) + 1} is reached only on the other branch (branch defect)"
    s0 = float(cands[branch][0])
    if not math.isfinite(s0):
        raise GearleverError("the synthesized slider-crank cannot assemble at the first target")
    model = slider_crank_model((0.0, 0.0), (a * math.cos(phi[0]), a * math.sin(phi[0])), (s0, e), name=name)
    # the engine's crank angle is that of O2->A: a < 0 puts the pin at phi + pi
    off_a = 0.0 if a > 0 else math.pi
    gen_t, gen_d, evals = _engine_outputs(model, phi + off_a, dense + off_a, "O2", "B", 0.0, 0.0, slider=True)
    err = gen_t - s
    derr = gen_d - want
    rod = np.arctan2(h[n:], root[n:] if branch == "+" else -root[n:])  # rod angle from B to A seen along the line
    mu = np.arccos(np.clip(np.abs(np.sin(rod)), 0.0, 1.0))
    return FunctionSynthesis(
        "slider-crank",
        phi,
        s,
        gen_t,
        err,
        np.array([K1, K2, K3]),
        {"crank": abs(a), "rod": b, "offset": e},
        branch,
        model,
        dense,
        want,
        gen_d,
        *_error_and_angle_stats(derr, mu),
        "crank turns fully" if b > abs(a) + abs(e) else "crank rocks",
        defect,
        n == 3,
        scale,
        evals,
    )
