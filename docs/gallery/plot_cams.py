"""
Motion laws and the disc cams that give them
============================================

``law_lift.toml`` is a dwell, a 20 mm cycloidal lift, a dwell and a 3-4-5
return over one cam turn.  Its SVAJ diagrams show s, v and a continuous (the
fundamental law of cam design); the cam for a translating roller follower is
sized for a 30 deg maximum pressure angle, and the same law drives a
flat-faced follower sized for a 10 mm minimum radius of curvature.
"""

import math

from gearlever.cams import design_cam, size_base_radius
from gearlever.data import example_path
from gearlever.laws import load_law
from gearlever.plotting.cam import cam_design_figure

law = load_law(example_path("law_lift.toml"))
print("continuous (s, v, a):", law.continuity().ok)
rb = size_base_radius(law, "translating-roller", roller_radius=8.0, max_pressure_angle=math.radians(30))
roller = design_cam(law, "translating-roller", base_radius=rb, roller_radius=8.0)
print(f"roller: base radius {rb:.3f} mm, max pressure angle {math.degrees(roller.pressure_angle_max):.2f} deg")
cam_design_figure(roller, law.evaluate(roller.theta))

# %%
# The flat-faced follower: no pressure angle, but the face must be wide
# enough for the contact's travel along it.
rb = size_base_radius(law, "translating-flat", min_curvature_radius=10.0)
flat = design_cam(law, "translating-flat", base_radius=rb)
print(f"flat: base radius {rb:.3f} mm, face width {flat.face_width:.2f} mm")
cam_design_figure(flat, law.evaluate(flat.theta))
