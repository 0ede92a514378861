"""
Planetaries, Ferguson's paradox and the geared five-bar
=======================================================

The shipped models with gear meshes: the simple planetary (three planets, two
redundant constraints), the compound planetary, Ferguson's paradox and the
geared five-bar.  Each is solved over a turn of its input and drawn with its
pitch circles; the structure line shows the counts and the redundant
constraints found from the Jacobian's rank.
"""

import matplotlib.pyplot as plt
import numpy as np

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.mechanism.sweep import sweep
from gearlever.plotting.mechanism import draw_mechanism

names = ["planetary", "compound_planetary", "ferguson", "geared_fivebar"]
fig, axes = plt.subplots(2, 2, figsize=(10, 10))
for ax, name in zip(axes.flat, names):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    q, qdot = sweep(mech, 181)
    r = mech.solve(q, qdot)
    s = mech.structure()
    print(f"{name}: n={s.n} P5={s.P5} P4={s.P4} W_formula={s.W_formula} dof={s.dof} redundant={s.redundant}")
    draw_mechanism(mech, r, ax=ax)
    ax.set_title(mech.name, fontsize=10)

# %%
# Ferguson's paradox: per turn of the arm the three coaxial gears (99, 100 and
# 101 teeth) turn -1/99, 0 and +1/101 of a turn.
mech = Mechanism.load(example_path("ferguson.toml"))
r = mech.solve(mech.sketch_inputs[0] + np.array([0.0, 2 * np.pi]))
for link in mech.model.moving:
    turns = round(float(r.angle[link][1] - r.angle[link][0]) / (2 * np.pi), 9) + 0.0
    print(f"{link}: {turns:+.6f} turn per arm turn")
