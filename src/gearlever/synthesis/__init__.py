"""Dimensional synthesis of linkages: from the motion a designer wants to a model file.

- :mod:`~gearlever.synthesis._model`: the synthesized linkage as a model
  dict in the schema of :mod:`gearlever.mechanism.model` and its TOML text.

Numeric core: may import numpy, scipy, :mod:`gearlever.loops`,
:mod:`gearlever.mechanism`, :mod:`gearlever.errors`, :mod:`gearlever._io`
and (for scale-out) dask; never pandas or matplotlib.
"""
