"""Flywheels: turning-moment diagrams over a machine's cycle, and the textbook problems they are checked on.

(The package was ``gearlever.dynamics``; it is named for what it holds.  The
inverse and forward dynamics of a mechanism, which the engines here use, are
:mod:`gearlever.mechanism.dynamics`.)

:mod:`gearlever.flywheels.flywheel` integrates a turning-moment (crank-effort)
diagram over one cycle and sizes the flywheel that holds the speed within a
given coefficient of fluctuation (or gives the fluctuation of a given one).
:mod:`gearlever.flywheels.published` solves published textbook problems of
epicyclic holding torques, engine crank effort and flywheel sizing with the
gear networks, the mechanism models and the flywheel, beside the printed
answers kept in the package data files.

Modules here import numpy, scipy (lazily, inside the functions that need it),
and gearlever's :mod:`~gearlever.errors`, :mod:`~gearlever._validate`,
:mod:`~gearlever._result`, :mod:`~gearlever.data` (the published problems) and
:mod:`~gearlever.mechanism` and :mod:`~gearlever.gears` (lazily, to build the
engines and trains); never pandas or
matplotlib.pyplot (tables and figures live in :mod:`gearlever.tables` and
:mod:`gearlever.plotting`).
"""

from gearlever.flywheels.flywheel import Flywheel, flywheel
from gearlever.flywheels.published import TextbookCheck, textbook_checks

__all__ = ["Flywheel", "TextbookCheck", "flywheel", "textbook_checks"]
