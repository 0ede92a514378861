"""
Linkage synthesis: a log10 generator and a path generator
=========================================================

Function generation: a four-bar whose rocker angle follows ``y = log10 x``
for ``1 <= x <= 2`` (crank 45 to 105 deg, rocker 135 to 225 deg), exact
through three Chebyshev precision points (Freudenstein's equation), its
structural error measured by solving the synthesized model.  Path
generation: a four-bar whose coupler point passes through the five points of
``motion_poses.csv`` in order, found by the seeded differential evolution
with a small budget (the command line's default is 200 000 evaluations).
"""

import numpy as np

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from gearlever.plotting.synthesis import function_figure
from gearlever.plotting.synthesis_path import path_synthesis_plot
from gearlever.synthesis import function_targets, synthesize_function
from gearlever.synthesis.path import synthesize_path

t = function_targets("log10(x)", (1.0, 2.0), np.radians((45.0, 105.0)), np.radians((135.0, 225.0)))
fn = synthesize_function(t.input_angle, t.target, target_at=t.target_at, input_range=t.input_range)
print("lengths:", {k: round(v, 6) for k, v in fn.lengths.items()}, fn.grashof)
print(f"structural error: max {np.degrees(fn.structural_error_max):.4f} deg over {fn.dense_input.size} crank angles")

# %%
# Targets, generated and wanted output, the structural error and the linkage.
function_figure(fn)

# %%
# Path generation through five points without timing.  The result is a model:
# it is solved here over a crank turn like any model file.
poses = np.loadtxt(example_path("motion_poses.csv"), delimiter=",", skiprows=1)
path = synthesize_path(poses[:, :2], length_range=(0.2, 5), coord_range=(-5, 5), budget=8000, seed=0, workers=1)
print(
    f"{path.kind}, {path.grashof}, objective {path.objective:.3g}, links",
    {k: round(v, 4) for k, v in path.links.items()},
)
m = Mechanism.from_dict(path.model())
turn = m.solve(m.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 361))
print(f"{int(turn.closed.sum())} of 361 crank angles assembled")
ax = path_synthesis_plot(path)
