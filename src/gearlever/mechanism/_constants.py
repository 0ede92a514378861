"""Step sizes shared by the solver's modules; imports nothing.

:mod:`~gearlever.mechanism.solve` (the continuation) and
:mod:`~gearlever.mechanism.assur` (the closed-form dyads, which must unwrap
their rotations as the continuation would) both read them here, so neither
imports the other for a number.

>>> from gearlever.mechanism._constants import COARSE_STEP
>>> COARSE_STEP
0.25
"""

#: Largest step (rad, or length / model length scale) of the sequential continuation.
COARSE_STEP = 0.25

#: Hadamard-ratio threshold below which the reduced Jacobian counts as singular (a dead point).
SINGULAR_TOL = 1e-9
