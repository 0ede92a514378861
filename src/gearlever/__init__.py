"""gearlever: kinematic analysis of gear-lever differential mechanisms.

Numeric modules (floats and numpy arrays in, arrays out; none imports
matplotlib or pandas):

- :mod:`gearlever.zrdpm`, :mod:`~gearlever.loops.vector_loop`,
  :mod:`~gearlever.gears.willis`, :mod:`~gearlever.mechanism.structure`: the ZRDPM
  paper's mobility, Willis equations, contours, analogues and Tables I and II.
- :mod:`gearlever.loops`: the general planar vector-loop engine (four-bar,
  slider-cranks, double slider, any loop system), plans.
- :mod:`gearlever.gears.networks`, :mod:`~gearlever.gears.chariot`, :mod:`~gearlever.gears.car`:
  gear networks solved exactly, the Nuttall south-pointing chariot, the car
  differential.
- :mod:`gearlever.trains`, :mod:`~gearlever.trains.synthesis`, :mod:`~gearlever.trains.hooke`:
  trains of wheels, tooth-number synthesis and exact search, Hooke's coupling.

:mod:`gearlever.tables` (pandas) and :mod:`gearlever.plotting` (matplotlib)
sit on top of them and are imported only when asked for.

>>> import gearlever
>>> round(float(gearlever.mobility(n=9, p5=12, p4=3, q=2)), 1)
2.0
"""

__version__ = "0.1.0"

from gearlever import _aliases  # noqa: E402
from gearlever.dynamics.flywheel import flywheel  # noqa: E402
from gearlever.errors import ClosureError, GearleverError  # noqa: E402
from gearlever.gears.car import car_differential  # noqa: E402
from gearlever.gears.chariot import NuttallTeeth, design_nuttall, simulate  # noqa: E402
from gearlever.gears.networks import Network  # noqa: E402
from gearlever.loops import LoopSystem, Vector, fourbar, grashof  # noqa: E402
from gearlever.mechanism.core import Mechanism  # noqa: E402
from gearlever.mechanism.structure import mobility, redundant_constraints  # noqa: E402
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
    "simulate",
    "car_differential",
    "train_ratio",
    "design_train",
    "search_best",
    "HookeJoint",
    "flywheel",
]

_aliases.install()
