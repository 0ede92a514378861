"""gearlever: kinematic analysis of gear-lever differential mechanisms.

Numeric modules (floats and numpy arrays in, arrays out; none imports
matplotlib or pandas):

- :mod:`gearlever.zrdpm`, :mod:`~gearlever.vector_loop`,
  :mod:`~gearlever.differential`, :mod:`~gearlever.structure`: the ZRDPM
  paper's mobility, Willis equations, contours, analogues and Tables I and II.
- :mod:`gearlever.loops`: the general planar vector-loop engine (four-bar,
  slider-cranks, double slider, any loop system), plans.
- :mod:`gearlever.networks`, :mod:`~gearlever.chariot`, :mod:`~gearlever.car`:
  gear networks solved exactly, the Nuttall south-pointing chariot, the car
  differential.
- :mod:`gearlever.trains`, :mod:`~gearlever.synthesis`, :mod:`~gearlever.hooke`:
  trains of wheels, tooth-number synthesis and exact search, Hooke's coupling.

:mod:`gearlever.tables` (pandas) and :mod:`gearlever.plotting` (matplotlib)
sit on top of them and are imported only when asked for.

>>> import gearlever
>>> round(float(gearlever.mobility(n=9, p5=12, p4=3, q=2)), 1)
2.0
"""

__version__ = "0.1.0"

from gearlever.chariot import NuttallTeeth, design_nuttall, simulate  # noqa: E402
from gearlever.car import car_differential  # noqa: E402
from gearlever.hooke import HookeJoint  # noqa: E402
from gearlever.loops import LoopSystem, Vector, fourbar, grashof  # noqa: E402
from gearlever.networks import Network  # noqa: E402
from gearlever.structure import mobility, redundant_constraints  # noqa: E402
from gearlever.synthesis import design_train, search_best  # noqa: E402
from gearlever.trains import train_ratio  # noqa: E402
from gearlever.zrdpm import (  # noqa: E402
    TablesConstants, ZrdpmContour, analogues, contour1, contour2,
    identify_tables_constants, published_table, tables_outputs,
)

__all__ = [
    "__version__",
    "ZrdpmContour", "TablesConstants", "analogues", "contour1", "contour2",
    "tables_outputs", "published_table", "identify_tables_constants",
    "mobility", "redundant_constraints",
    "fourbar", "grashof", "LoopSystem", "Vector",
    "Network", "NuttallTeeth", "design_nuttall", "simulate", "car_differential",
    "train_ratio", "design_train", "search_best", "HookeJoint",
]
