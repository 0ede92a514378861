"""Motion laws: the output a machine needs as a function of the input angle over one turn.

Holds the normalised segment motions (:mod:`~gearlever.laws.motions`:
dwell, linear, harmonic, cycloidal, 3-4-5, 4-5-6-7, modified trapezoid,
modified sine) and the law itself (:mod:`~gearlever.laws.law`: segments or a
periodic spline through samples, read from LAW.toml; displacement, velocity,
acceleration and jerk per radian or per second; continuity check).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy, the standard library and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``data``, ``errors``; never pandas or matplotlib.
"""

from gearlever.laws.law import (
    ContinuityReport,
    LawValues,
    MotionLaw,
    law_from_samples,
    law_from_segments,
    load_law,
)
from gearlever.laws.motions import MOTIONS, Motion

__all__ = [
    "MOTIONS",
    "ContinuityReport",
    "LawValues",
    "Motion",
    "MotionLaw",
    "law_from_samples",
    "law_from_segments",
    "load_law",
]
