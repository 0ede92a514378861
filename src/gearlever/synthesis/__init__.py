"""Dimensional synthesis of linkages: from the motion a designer wants to a model file.

- :mod:`~gearlever.synthesis._model`: the synthesized linkage as a model
  dict in the schema of :mod:`gearlever.mechanism.model` and its TOML text
  (four-bar and slider-crank).
- :mod:`~gearlever.synthesis.expr`: a safe formula ``y = f(x)`` (parsed by
  :mod:`ast`, never evaluated by Python).
- :mod:`~gearlever.synthesis.function`: function generation, four-bar
  (Freudenstein's equation) and slider-crank, exact for three precision
  points and least squares for more, checked by the mechanism engine.
- :mod:`~gearlever.synthesis.motion`: motion generation (rigid-body
  guidance) of a four-bar through 3, 4 or 5 poses: pivots, Burmester curves
  and Burmester points, ranked four-bars free of branch, order and circuit
  defects.

Numeric core: may import numpy, scipy, :mod:`gearlever.loops`,
:mod:`gearlever.mechanism`, :mod:`gearlever.errors`, :mod:`gearlever._io`
and (for scale-out) dask; never pandas or matplotlib.
"""

from gearlever.synthesis.function import (
    FunctionSynthesis,
    FunctionTargets,
    function_targets,
    precision_points,
    synthesize_function,
)
from gearlever.synthesis.motion import (
    BurmesterCurves,
    Dyad,
    MotionSolution,
    MotionSynthesis,
    burmester_curves,
    burmester_points,
    fixed_pivot,
    moving_pivot,
    synthesize_motion,
)

__all__ = [
    "BurmesterCurves",
    "Dyad",
    "FunctionSynthesis",
    "FunctionTargets",
    "MotionSolution",
    "MotionSynthesis",
    "burmester_curves",
    "burmester_points",
    "fixed_pivot",
    "function_targets",
    "moving_pivot",
    "precision_points",
    "synthesize_function",
    "synthesize_motion",
]
