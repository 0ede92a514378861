"""
Watt six-bar
============

``watt_sixbar.toml``: two four-bars in series sharing a ternary rocker.  It
decomposes into a driver and two RRR dyads, so it is solved in closed form
batched over all rows; the point paths show the second loop following the
first.
"""

import numpy as np

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.plotting.mechanism import draw_mechanism

mech = Mechanism.load(example_path("watt_sixbar.toml"))
q = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 361)
r = mech.solve(q)
print(f"links {', '.join(mech.model.moving)}; {int(r.closed.sum())}/{r.closed.size} rows closed")
draw_mechanism(mech, r)
