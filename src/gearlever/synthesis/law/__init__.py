"""Law synthesis: a linkage or geared linkage whose output follows a motion law over the whole cycle.

- :mod:`~gearlever.synthesis.law._core`: the sampled target
  (:class:`LawTarget`, :func:`law_target`), the kind interface
  (:class:`LawKind`) and registry (:data:`KINDS`), the objective and the
  minimax polish (:class:`LawProblem`).
- one module per kind, each registering itself:
  :mod:`~gearlever.synthesis.law.fourbar` (crank-rocker, rocker output),
  :mod:`~gearlever.synthesis.law.slider_crank` (offset slider output),
  :mod:`~gearlever.synthesis.law.geared_fourbar` (coupler gear driving an
  output gear), :mod:`~gearlever.synthesis.law.sixbar_dwell` (a dyad on a
  circular arc of a coupler curve), :mod:`~gearlever.synthesis.law.gear_lever`
  (the ZRDPM gear-lever differential, its carrier swung by a linkage).
- :mod:`~gearlever.synthesis.law.driver`: seeded starts
  (:func:`gearlever.synthesis.driver.multistart`) for each kind,
  :class:`LawSynthesis`.
- :mod:`~gearlever.synthesis.law.measure`: the law a mechanism model
  produces, segments fitted (the inverse use), and the report of a synthesis.

The kinds are also records of family ``law`` in the one registry of
synthesis kinds (:func:`gearlever.synthesis.kinds`), added here.

Numeric core: may import numpy, scipy, :mod:`gearlever.synthesis`,
:mod:`gearlever.mechanism`, :mod:`gearlever.laws`, :mod:`gearlever.errors`;
never pandas or matplotlib.
"""

from gearlever.synthesis.law import (  # noqa: F401 (the kinds)
    fourbar,
    gear_lever,
    geared_fourbar,
    sixbar_dwell,
    slider_crank,
)
from gearlever.synthesis.law._core import KINDS, LawKind, LawProblem, LawTarget, law_target
from gearlever.synthesis.law.driver import MIN_BUDGET, LawSynthesis, example, synthesize_law
from gearlever.synthesis.registry import Kind, register

__all__ = ["KINDS", "LawKind", "LawProblem", "LawSynthesis", "LawTarget", "law_target", "synthesize_law"]

# the law kinds in the one registry of synthesis kinds (family "law", in the order of KINDS: that of "auto")
for _order, (_name, _cls) in enumerate(KINDS.items()):
    register(
        Kind(
            "law",
            _name,
            ((_cls.__doc__ or "").strip().splitlines() or [_name])[0].replace(" (see the module docstring)", ""),
            "gearlever.synthesis.law.driver:synthesize_law",
            polish_counted=True,
            min_budget=MIN_BUDGET,
            order=_order,
            example=example(_name),
            spec=_cls,
        )
    )
