"""
Four-bar with a coupler point
=============================

The shipped crank-rocker ``fourbar.toml``: its structure, a full crank turn
solved batched over 361 angles, the drawing with the point paths, and the
rocker's velocity and acceleration analogues (``qdot = 1``, ``qddot = 0``).
"""

import matplotlib.pyplot as plt
import numpy as np

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.plotting.mechanism import draw_mechanism

mech = Mechanism.load(example_path("fourbar.toml"))
s = mech.structure()
print(f"n={s.n} P5={s.P5} P4={s.P4} W_formula={s.W_formula} dof={s.dof} redundant={s.redundant}")

theta2 = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 361)
r = mech.solve(theta2)
print(f"{int(r.closed.sum())} of {r.closed.size} rows closed")

# %%
# The sketch, the joints and the paths of every point over the turn.
draw_mechanism(mech, r)

# %%
# The rocker's angle and its analogues: angular velocity and acceleration per
# unit crank speed at a constant crank speed.
fig, ax = plt.subplots(figsize=(7, 3.5))
deg = np.degrees(theta2 - theta2[0])
ax.plot(deg, r.omega["rocker"], label="omega_rocker / omega_crank")
ax.plot(deg, r.alpha["rocker"], label="alpha_rocker / omega_crank^2")
ax.set_xlabel("crank turned from the sketch (deg)")
ax.legend()
ax.grid(True, alpha=0.3)
fig.tight_layout()
