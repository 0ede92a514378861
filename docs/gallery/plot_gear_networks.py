"""
Gear networks: epicyclic trains solved exactly
==============================================

The shipped gear networks (CSV records of members and constraints) solved as
constraint equations: every member's rotation as an exact fraction of the
input, the redundant constraints and the members forced still.  The bars show
the rotation of each member per turn of the input.
"""

import matplotlib.pyplot as plt

from gearlever.data import example_path
from gearlever.gears.networks import parse_network

inputs = {
    "ferguson_paradox": ["arm"],
    "simple_planetary": ["sun"],
    "compound_planetary": ["sun"],
    "reverted_train": ["A"],
}
fig, axes = plt.subplots(1, len(inputs), figsize=(12, 3.8))
for ax, (name, given) in zip(axes, inputs.items()):
    net = parse_network(example_path(f"{name}.csv").read_text(encoding="utf-8"))
    a = net.analyse()
    sol = net.solve(given)
    print(f"{name}: unknowns {a.unknowns}, rank {a.rank}, dof {a.dof}")
    for member in net.names:
        print("   ", sol.relation(member))
    names = list(net.names)
    values = [float(sol.coefficients[m][0]) for m in names]
    ax.bar(names, values, color=["C0" if v >= 0 else "C3" for v in values])
    ax.set_title(name.replace("_", " "), fontsize=10)
    ax.set_ylabel(f"turns per turn of {given[0]}")
    ax.tick_params(axis="x", labelrotation=60, labelsize=8)
    ax.grid(True, axis="y", alpha=0.3)
fig.tight_layout()

# %%
# The car differential has two inputs: the pinion and the left wheel.  The
# right wheel turns at half the pinion's rate (through the 10:40 ring) minus
# the left wheel.
net = parse_network(example_path("car_differential.csv").read_text(encoding="utf-8"))
sol = net.solve(["pinion", "left"])
for member in net.names:
    print(sol.relation(member))
