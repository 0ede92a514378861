"""gearlever: analysis and synthesis of gear-lever differential mechanisms.

Subpackages by concept; the numeric core (numpy arrays in, arrays out) never
imports matplotlib or pandas:

- :mod:`gearlever.zrdpm`: the ZRDPM paper (Alimukhamedov et al., 2020):
  contours, analogues, Tables I and II and the constants they were computed with.
- :mod:`gearlever.gears`: the Willis relation (:mod:`~gearlever.gears.willis`),
  gear networks with meshes on carriers, the tabular method, planetary design,
  the Nuttall south-pointing chariot, the car differential.
- :mod:`gearlever.trains`: ratio and sense of trains of wheels, tooth-number
  design by the classical rules, an exact best search, Hooke's coupling.
- :mod:`gearlever.loops`: the planar vector-loop engine, closed forms (four-bar,
  slider-cranks, the double slider), velocity and acceleration plans.
- :mod:`gearlever.mechanism`: planar mechanisms of links, pins, sliders and
  gears read from model files: structure, positions, velocities, accelerations,
  instant centres, assembly from lengths, inverse and forward dynamics for any
  number of inputs.
- :mod:`gearlever.flywheels`: flywheels and the published textbook problems.
- :mod:`gearlever.synthesis`: dimensional synthesis (function, motion and path
  generation) written as model files, scaled out on dask.

:mod:`gearlever.tables` (pandas) and :mod:`gearlever.plotting` (matplotlib)
sit on top of them and are imported only when asked for; :mod:`gearlever.cli`
is the command line.  ``gearlever.simulate_chariot`` is the chariot's
simulation (:func:`gearlever.gears.chariot.simulate`); a mechanism's motion
is :meth:`Mechanism.simulate`.  Radians everywhere in the API; bad input raises
:class:`GearleverError` (a :class:`ValueError`).

>>> import gearlever
>>> round(float(gearlever.mobility(n=9, p5=12, p4=3, q=2)), 1)
2.0
"""

__version__ = "0.1.0"

from gearlever._result import Result  # noqa: E402
from gearlever.errors import ClosureError, GearleverError  # noqa: E402
from gearlever.flywheels.flywheel import flywheel  # noqa: E402
from gearlever.gears.car import car_differential  # noqa: E402
from gearlever.gears.chariot import NuttallTeeth, design_nuttall  # noqa: E402
from gearlever.gears.chariot import simulate as simulate_chariot  # noqa: E402
from gearlever.gears.networks import Network  # noqa: E402
from gearlever.loops import LoopSystem, Vector, fourbar, grashof  # noqa: E402
from gearlever.mechanism.core import Mechanism  # noqa: E402
from gearlever.mechanism.mobility import mobility, redundant_constraints  # noqa: E402
from gearlever.trains import design_train, search_best, train_ratio  # noqa: E402
from gearlever.trains.hooke import HookeJoint  # noqa: E402
from gearlever.zrdpm import (  # noqa: E402
    TablesConstants,
    ZrdpmContour,
    analogues,
    contour1,
    contour2,
    identify_tables_constants,
    published_table,
    tables_outputs,
)

__all__ = [
    "__version__",
    "GearleverError",
    "ClosureError",
    "ZrdpmContour",
    "TablesConstants",
    "analogues",
    "contour1",
    "contour2",
    "tables_outputs",
    "published_table",
    "identify_tables_constants",
    "mobility",
    "redundant_constraints",
    "Mechanism",
    "fourbar",
    "grashof",
    "LoopSystem",
    "Vector",
    "Network",
    "NuttallTeeth",
    "design_nuttall",
    "simulate_chariot",
    "car_differential",
    "train_ratio",
    "design_train",
    "search_best",
    "HookeJoint",
    "flywheel",
    "Result",
]
