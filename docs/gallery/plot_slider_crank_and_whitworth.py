"""
Slider-crank and Whitworth quick return
=======================================

Two shipped models with sliders: the offset slider-crank (``slider_crank.toml``)
and the Whitworth quick-return (``whitworth.toml``, a block sliding in a slotted
lever that turns fully).  The ram's stroke over a crank turn shows the quick
return: the cutting stroke takes more of the turn than the return.
"""

import matplotlib.pyplot as plt
import numpy as np

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.plotting.mechanism import draw_mechanism

fig, axes = plt.subplots(1, 2, figsize=(10, 4))
results = {}
for ax, name in zip(axes, ["slider_crank", "whitworth"]):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    q = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 361)
    results[name] = (mech, mech.solve(q))
    draw_mechanism(mech, results[name][1], ax=ax)
    ax.set_title(mech.name)

# %%
# The slider positions over the turn (x of the last point of each model).
fig, ax = plt.subplots(figsize=(7, 3.5))
for name, (mech, r) in results.items():
    point = list(mech.model.points)[-1]
    ax.plot(np.linspace(0, 360, 361), r.point[point][:, 0], label=f"{name}: x of {point}")
ax.set_xlabel("crank turned from the sketch (deg)")
ax.set_ylabel("x (mm)")
ax.legend()
ax.grid(True, alpha=0.3)
fig.tight_layout()
