"""Planar vector loops: a general engine plus closed forms for the classic linkages.

- :mod:`~gearlever.loops.engine`: :class:`LoopSystem` of vectors (fixed /
  input / unknown lengths and angles), batched Newton positions and
  analogues by batched linear solves, with NaN + masks where it cannot close.
- :mod:`~gearlever.loops.fourbar`: :func:`fourbar` (closed form), Grashof,
  limit positions, transmission angle.
- :mod:`~gearlever.loops.closed`: slider-crank, inverted slider-crank,
  the ZRDPM double slider.
- :mod:`~gearlever.loops.plan`: velocity and acceleration plans (numbers).
- :mod:`~gearlever.loops.trig`, :mod:`~gearlever.loops.compiled`: sine and
  cosine of arrays (one half-angle tangent; a numba kernel, imported on first
  use by the ZRDPM fast path only).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy and gearlever's ``_format``,
``_io``, ``_progress``, ``_result``, ``_validate``, ``errors``, ``gears`` (no
scipy, matplotlib or pandas at import; numba in ``compiled`` alone).
"""

from gearlever.loops.closed import (
    double_slider,
    double_slider_system,
    inverted_slider_crank,
    inverted_slider_crank_system,
    slider_crank,
    slider_crank_system,
    zrdpm_contour,
    zrdpm_contour_system,
)
from gearlever.loops.engine import INPUT, Input, LoopSolution, LoopSystem, Unknown, Vector
from gearlever.loops.fourbar import (
    FourBar,
    FourBarResult,
    GrashofClass,
    LimitPositions,
    change_points,
    fourbar,
    fourbar_system,
    grashof,
    limit_positions,
    transmission_angle,
)
from gearlever.loops.plan import PlanTerm, acceleration_plan, velocity_plan

__all__ = [
    "INPUT",
    "Input",
    "Unknown",
    "Vector",
    "LoopSystem",
    "LoopSolution",
    "fourbar",
    "fourbar_system",
    "FourBar",
    "FourBarResult",
    "grashof",
    "GrashofClass",
    "limit_positions",
    "LimitPositions",
    "transmission_angle",
    "change_points",
    "slider_crank",
    "slider_crank_system",
    "inverted_slider_crank",
    "inverted_slider_crank_system",
    "double_slider",
    "double_slider_system",
    "zrdpm_contour",
    "zrdpm_contour_system",
    "PlanTerm",
    "velocity_plan",
    "acceleration_plan",
]
