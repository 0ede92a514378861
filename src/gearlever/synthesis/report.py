"""Function generation's inputs checked and its result summarized: what every front end shows of it.

:func:`check_pairs` refuses target pairs (input angle, output) that no
crank can meet, naming the file, row and column; :func:`function_summary`
is the JSON-ready summary of a :class:`~gearlever.synthesis.function.FunctionSynthesis`
at the digits its computation determines (:mod:`gearlever._format`):
lengths at :data:`~gearlever._format.DIGITS_DESIGN` digits of the largest,
errors at as many of the output's range, ratios and structural errors at 6.
Angles in the summary are degrees (names ending ``_deg``).

Imports numpy, :mod:`gearlever._format`, :mod:`gearlever.errors` and
:mod:`gearlever.synthesis.function`; never pandas or matplotlib.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._format import DIGITS_DESIGN, rounded
from gearlever.errors import GearleverError
from gearlever.synthesis.function import MAX_ANGLE, MAX_LENGTH

__all__ = ["MAX_PAIR_DEG", "angle_offsets", "check_pairs", "function_summary"]

#: Largest input or output angle of a target pair, deg (57 000, within :data:`~gearlever.synthesis.function.MAX_ANGLE`).
MAX_PAIR_DEG = round(math.degrees(MAX_ANGLE), -3)


def check_pairs(input_deg, output, *, slider: bool, where: str, output_name: str | None = None, lines=None) -> None:
    """Refuse target pairs that function generation cannot take, naming ``where``, the row and the column.

    Parameters
    ----------
    input_deg : sequence of float
        Crank angles of the targets, deg.
    output : sequence of float
        Rocker angles (deg) or, for a slider-crank (``slider``), slider travels.
    where : str
        The source as the user named it (``PAIRS 'p.csv'``).
    output_name : str, optional
        The output's column (default ``output`` for a slider, ``output_deg``).
    lines : sequence of int, optional
        Each target's row in the file (default: the index + 2, after a header row).

    Raises
    ------
    GearleverError
        Fewer than 3 targets; a value beyond :data:`MAX_PAIR_DEG` (angles) or
        :data:`~gearlever.synthesis.function.MAX_LENGTH` (travels); input angles
        spanning a full turn or more; an input angle repeated.

    Examples
    --------
    >>> check_pairs([10, 20, 10], [1, 2, 3], slider=False, where="PAIRS")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: PAIRS row 4 column input_deg: repeats row 2 (10)
    """
    out_col = output_name or ("output" if slider else "output_deg")
    cols = {"input_deg": list(input_deg), out_col: list(output)}
    rows = list(lines) if lines is not None else [i + 2 for i in range(len(cols["input_deg"]))]
    n = len(cols["input_deg"])
    if n < 3:
        raise GearleverError(f"{where}: function generation needs at least 3 targets, got {n}")
    caps = (("input_deg", MAX_PAIR_DEG), (out_col, MAX_LENGTH if slider else MAX_PAIR_DEG))
    for col, cap in caps:
        big = [(i, v) for i, v in enumerate(cols[col]) if abs(v) > cap]
        if big:
            i, v = big[0]
            raise GearleverError(f"{where} row {rows[i]} column {col}: must be at most {cap:g} in size, got {v:g}")
    span = max(cols["input_deg"]) - min(cols["input_deg"])
    if span >= 360:
        raise GearleverError(
            f"{where} column input_deg: the targets span {span:g} deg; a crank is back in the same pose "
            "after a full turn, so they must span less than 360 deg"
        )
    seen: dict = {}
    for i, v in enumerate(cols["input_deg"]):
        if v in seen:
            raise GearleverError(f"{where} row {rows[i]} column input_deg: repeats row {rows[seen[v]]} ({v!r})")
        seen[v] = i


def angle_offsets(res) -> dict:
    """The model's crank input minus the design's input angle, deg (a multiple of 180: reversed, whole turns);
    for a four-bar also the model's rocker angle minus the output angle (0 or 180).

    >>> from types import SimpleNamespace
    >>> angle_offsets(SimpleNamespace(input_offset=math.pi, output_offset=0.0, kind="fourbar"))
    {'crank': 180, 'rocker': 0}
    """
    out = {"crank": round(math.degrees(res.input_offset))}
    if res.kind == "fourbar":
        out["rocker"] = round(math.degrees(res.output_offset)) % 360
    return out


def function_summary(res, *, expression: str | None = None, x=None, warnings=(), time_s: float | None = None) -> dict:
    """The JSON-ready summary of a function synthesis, every number at the digits its computation determines.

    Parameters
    ----------
    res : FunctionSynthesis
    expression : str, optional
        The formula the targets came from (``None`` for target pairs).
    x : sequence of float, optional
        The formula's argument at each target.
    warnings : sequence of str
        Notes for the reader (impractical proportions and what to do about them).
    time_s : float, optional
        Wall time, rounded to 0.01 s.

    Returns
    -------
    dict
        ``kind``, ``objective`` (in words), ``expression``, ``lengths``,
        ``link_ratio``, ``coefficients``, ``branch``, ``grashof``, ``targets``
        (per target: ``x``, ``input_deg``, ``model_input_deg``, output,
        ``generated`` (the field :attr:`~gearlever.synthesis.function.FunctionSynthesis.achieved`:
        the report's key is kept) and error, ``_deg`` for a four-bar), the largest target
        error, the structural error (max, rms, samples) over the range, the
        transmission angle range, ``defect``, ``model_angle_offsets_deg``,
        ``warnings``, ``evaluations``, ``time_s``.

    Notes
    -----
    Freudenstein's equation (four-bar) or the slider-crank loop equation,
    exact through 3 precision points and least squares through more; the
    structural error is the mechanism engine's output against the desired
    function over the range (Norton, *Design of Machinery*, ch. 5).

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.synthesis.function import synthesize_function
    >>> res = synthesize_function(np.radians([30, 60, 90]), np.radians([40, 55, 75]), kind="fourbar")
    >>> s = function_summary(res)
    >>> s["objective"], len(s["targets"])
    ("exact through 3 precision points (Freudenstein's equation)", 3)
    """
    slider = res.kind == "slider-crank"
    conv = (lambda v: v) if slider else math.degrees
    unit = "" if slider else "_deg"
    offsets = angle_offsets(res)
    out_scale = float(np.ptp([conv(float(v)) for v in res.target])) or 1.0  # errors: at digits of the output range
    size = max(abs(v) for v in res.lengths.values())  # lengths: at digits of the largest
    D = DIGITS_DESIGN
    return {
        "kind": res.kind,
        "objective": (
            "exact through 3 precision points"
            if res.exact
            else f"least squares of the design equation through {res.input_angle.size} targets"
        )
        + (" (Freudenstein's equation)" if not slider else " (slider-crank loop equation)"),
        "expression": expression,
        "lengths": {k: rounded(float(v), D, size) for k, v in res.lengths.items()},
        "link_ratio": rounded(float(res.link_ratio), 6),
        "coefficients": [rounded(float(k), D) for k in res.coefficients],
        "branch": res.branch,
        "grashof": res.grashof,
        "targets": [
            {
                "x": rounded(float(x[j]), D) if x is not None else None,
                "input_deg": rounded(math.degrees(res.input_angle[j]), D),
                "model_input_deg": rounded(math.degrees(res.input_angle[j]) + offsets["crank"], D),
                f"output{unit}": rounded(float(conv(res.target[j])), D),
                f"generated{unit}": rounded(float(conv(res.achieved[j])), D),  # the report's key, the field achieved
                f"error{unit}": rounded(float(conv(res.error[j])), D, out_scale),
            }
            for j in range(res.input_angle.size)
        ],
        f"max_target_error{unit}": rounded(float(conv(float(np.max(np.abs(res.error))))), D, out_scale),
        f"structural_error_max{unit}": rounded(float(conv(res.structural_error_max)), 6),
        f"structural_error_rms{unit}": rounded(float(conv(res.structural_error_rms)), 6),
        "structural_error_samples": int(res.dense_input.size),
        "transmission_angle_deg": [
            rounded(math.degrees(res.transmission_range[0]), 6),
            rounded(math.degrees(res.transmission_range[1]), 6),
        ],
        "defect": res.defect or None,
        "model_angle_offsets_deg": offsets,
        "warnings": list(warnings),
        "evaluations": res.evaluations,
        "time_s": None if time_s is None else round(time_s, 2),
    }
