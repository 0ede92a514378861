"""Disc cams: profile, pressure angle, curvature, undercut and sizing for a motion law.

Holds the follower kinds (:mod:`~gearlever.cams.followers`, one module per
kind behind the registry ``FOLLOWERS``: translating and oscillating, roller
and flat-faced) and the design (:mod:`~gearlever.cams.design`: the cam for a
:class:`~gearlever.laws.MotionLaw`, batched over the cam angle, and
base-circle sizing) and reading a CAM.toml again (:mod:`~gearlever.cams.camfile`).

Pure numeric core: may import numpy, the standard library, gearlever.laws,
gearlever.errors, gearlever._result and gearlever._io (to read CAM.toml); never pandas or matplotlib.
"""

from gearlever.cams.camfile import load_cam
from gearlever.cams.design import CamDesign, design_cam, size_base_radius
from gearlever.cams.followers import FOLLOWERS, FollowerParams

__all__ = ["FOLLOWERS", "CamDesign", "FollowerParams", "design_cam", "load_cam", "size_base_radius"]
