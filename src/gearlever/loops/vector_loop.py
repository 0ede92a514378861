"""Closed-form vector contours of the ZRDPM (kept importable; they live in :mod:`gearlever.loops.closed`).

``double_slider`` here is the tuple form,
:func:`gearlever.loops.closed.double_slider_projections`;
:func:`gearlever.loops.closed.double_slider` returns the same numbers as a
:class:`~gearlever.loops.engine.LoopSolution`.

>>> from gearlever.loops import vector_loop
>>> float(vector_loop.slider_lever(2.0, 1.0, 1.0, [0.0])[1][0])
1.0
"""

from __future__ import annotations

from gearlever.loops.closed import double_slider_projections as double_slider
from gearlever.loops.closed import point_acceleration, recover_analogues, slider_lever

__all__ = ["double_slider", "point_acceleration", "recover_analogues", "slider_lever"]
