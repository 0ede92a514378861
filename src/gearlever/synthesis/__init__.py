"""Dimensional synthesis of linkages: from the motion a designer wants to a model file.

- :mod:`~gearlever.synthesis.model`: the one home for writing model files:
  the synthesized linkages as model dicts in the schema of
  :mod:`gearlever.mechanism.model` (four-bar, slider-crank, geared five-bar,
  Stephenson six-bar) and their TOML text, used by every package that writes
  a model.
- :mod:`~gearlever.synthesis.expr`: a safe formula ``y = f(x)`` (parsed by
  :mod:`ast`, never evaluated by Python).
- :mod:`~gearlever.synthesis.function`: function generation, four-bar
  (Freudenstein's equation) and slider-crank, exact for three precision
  points and least squares for more, checked by the mechanism engine.
- :mod:`~gearlever.synthesis.motion`: motion generation (rigid-body
  guidance) of a four-bar through 3, 4 or 5 poses: pivots, Burmester curves
  and Burmester points, ranked four-bars free of branch, order and circuit
  defects.
- :mod:`~gearlever.synthesis.path`: path generation, the driver (seeded
  starts on dask, polish) over the registry of linkage kinds
  :mod:`~gearlever.synthesis.path_kinds`, one module per kind:
  :mod:`~gearlever.synthesis.path_fourbar` (four-bar),
  :mod:`~gearlever.synthesis.fivebar` (geared five-bar),
  :mod:`~gearlever.synthesis.sixbar` (Stephenson six-bar).
- :mod:`~gearlever.synthesis.law`: law synthesis.
- :mod:`~gearlever.synthesis.driver`: the one multistart driver of the
  searched families (path, law, curve): the problem protocol, a named
  record per start, ``workers=`` an int, a map-like or a dask scheduler
  address, the one budget rule.
- :mod:`~gearlever.synthesis.registry`: the one registry of every kind of
  every family (function, motion, path, law, curve); :func:`kinds` lists
  them.

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy, (for scale-out) dask and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``cams``, ``data``, ``errors``, ``gears``, ``laws``, ``loops``, ``mechanism``;
never pandas or matplotlib.
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
from gearlever.synthesis.registry import Kind, kinds, register

__all__ = [
    "BurmesterCurves",
    "Dyad",
    "FunctionSynthesis",
    "FunctionTargets",
    "Kind",
    "MotionSolution",
    "MotionSynthesis",
    "burmester_curves",
    "burmester_points",
    "fixed_pivot",
    "function_targets",
    "kinds",
    "moving_pivot",
    "precision_points",
    "register",
    "synthesize_function",
    "synthesize_motion",
]
