"""Law synthesis: a linkage or geared linkage whose output follows a motion law over the whole cycle.

- :mod:`~gearlever.synthesis.law._core`: the sampled target
  (:class:`LawTarget`, :func:`law_target`), the kind interface
  (:class:`LawKind`) and its registration in the one registry (:data:`KINDS`
  is a read-only view of it), the objective and the
  minimax polish (:class:`LawProblem`).
- one module per kind, each registering itself:
  :mod:`~gearlever.synthesis.law.fourbar` (crank-rocker, rocker output),
  :mod:`~gearlever.synthesis.law.slider_crank` (offset slider output),
  :mod:`~gearlever.synthesis.law.geared_fourbar` (coupler gear driving an
  output gear), :mod:`~gearlever.synthesis.law.sixbar_dwell` (a dyad on a
  circular arc of a coupler curve), :mod:`~gearlever.synthesis.law.gear_lever`
  (the ZRDPM gear-lever differential, its carrier swung by a linkage),
  :mod:`~gearlever.synthesis.law.slotted_lever` (crank and slotted lever:
  quick return of the lever, or of a ram on its arm),
  :mod:`~gearlever.synthesis.law.sixbar_slider` (the shaper: slotted lever,
  rod and ram).
- :mod:`~gearlever.synthesis.law.driver`: seeded starts
  (:func:`gearlever.synthesis.driver.multistart`) for each kind,
  :class:`LawSynthesis`.
- :mod:`~gearlever.synthesis.law.measure`: the law a mechanism model
  produces, segments fitted (the inverse use), and the report of a synthesis.

The kinds are records of family ``law`` in the one registry of synthesis
kinds (:func:`gearlever.synthesis.kinds`), each added by its module.

Numeric core: may import numpy, scipy, :mod:`gearlever.synthesis`,
:mod:`gearlever.mechanism`, :mod:`gearlever.laws`, :mod:`gearlever.errors`;
never pandas or matplotlib.
"""

from gearlever.synthesis.law import (  # noqa: F401 (the kinds: each registers itself in the one registry)
    fourbar,
    gear_lever,
    geared_fourbar,
    sixbar_dwell,
    sixbar_slider,
    slider_crank,
    slotted_lever,
)
from gearlever.synthesis.law._core import KINDS, LawKind, LawProblem, LawTarget, kind_class, law_target
from gearlever.synthesis.law.driver import LawSynthesis, synthesize_law

__all__ = ["KINDS", "LawKind", "LawProblem", "LawSynthesis", "LawTarget", "kind_class", "law_target", "synthesize_law"]
