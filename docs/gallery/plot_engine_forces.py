"""
Engine: input torque, bearing loads and a flywheel
==================================================

``engine.toml`` is a single-cylinder engine as an in-line slider-crank with
masses, gravity and a gas load (SI units).  Its inverse dynamics at 3000 rpm
give the torque the crank must receive and every pin force; the torque over a
turn is the turning-moment diagram a flywheel is sized from.
"""

import math

import numpy as np

from gearlever.data import example_path
from gearlever.flywheels.flywheel import flywheel
from gearlever.mechanism import Mechanism
from gearlever.plotting.dynamics import forces_figure, turning_moment_figure

mech = Mechanism.load(example_path("engine.toml"))
rpm = 3000.0
w = rpm * math.pi / 30.0
q = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
d = mech.inverse_dynamics(q, np.full_like(q, w), np.zeros_like(q))
tau = d.input_force[:, 0]
print(f"input torque {tau.min():.1f} .. {tau.max():.1f} N m, mean {tau.mean():.2f} N m")
print("pins:", ", ".join(d.reaction))

# %%
# Input torque and the polar diagram of the crank-pin load.
bearing = "A" if "A" in d.reaction else next(iter(d.reaction))
forces_figure(d, bearing, label=f"input torque at {rpm:g} rpm")

# %%
# A motor giving the mean torque drives this machine: the energy between the
# two curves fixes the flywheel for a coefficient of fluctuation of 2 %.
fw = flywheel(q, np.full_like(tau, float(tau.mean())), rpm, fluctuation=0.02, load=tau, period=2 * np.pi)
print(f"dE = {fw.energy_fluctuation:.2f} J, I = {fw.inertia:.4f} kg m^2")
turning_moment_figure(fw)
