"""
The ZRDPM gear contour and parallel levers
==========================================

The two models of the ZRDPM paper's mechanism: the gear contour (leading gear
9 on the lever's pivot, driven gear 8 on lever 1; two inputs, W = 2) and the
lever part of four equal parallel levers joined by one bar, whose formula
mobility is -1 while it moves with one degree of freedom: two redundant
constraints, as the paper's eq. 1 says.
"""

import matplotlib.pyplot as plt

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.mechanism.sweep import sweep
from gearlever.plotting.mechanism import draw_mechanism

ranges = {"zrdpm_gear_contour": [(0.0, 360.0), (0.0, 60.0)], "parallel_levers": [(20.0, 160.0)]}
fig, axes = plt.subplots(1, 2, figsize=(10, 4.5))
for ax, (name, rng) in zip(axes, ranges.items()):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    q, qdot = sweep(mech, 181, rng)
    r = mech.solve(q, qdot)
    s = mech.structure()
    print(f"{name}: n={s.n} P5={s.P5} P4={s.P4} W_formula={s.W_formula} dof={s.dof} redundant={s.redundant}")
    draw_mechanism(mech, r, ax=ax)
    ax.set_title(mech.name, fontsize=10)
