"""Machine dynamics over a cycle: turning-moment diagrams and flywheels.

:mod:`gearlever.dynamics.flywheel` integrates a turning-moment (crank-effort)
diagram over one cycle and sizes the flywheel that holds the speed within a
given coefficient of fluctuation (or gives the fluctuation of a given one).

Modules here import numpy, scipy (lazily, inside the functions that need it),
and gearlever's :mod:`~gearlever.errors`, :mod:`~gearlever._validate` and
:mod:`~gearlever._result`; never pandas or matplotlib.pyplot (tables and
figures live in :mod:`gearlever.tables` and :mod:`gearlever.plotting`).
"""

from gearlever.dynamics.flywheel import Flywheel, flywheel

__all__ = ["Flywheel", "flywheel"]
