"""Disc cams: profile, pressure angle, curvature, undercut and sizing for a motion law.

Holds the follower kinds (:mod:`~gearlever.cams.followers`, one module per
kind behind the registry ``FOLLOWERS``: translating and oscillating, roller
and flat-faced) and the design (:mod:`~gearlever.cams.design`: the cam for a
:class:`~gearlever.laws.MotionLaw`, batched over the cam angle, and
base-circle sizing), CAM.toml written and read again (:mod:`~gearlever.cams.camfile`) and
the profile exported as CSV, SVG or DXF (:mod:`~gearlever.cams.export`, behind the registry ``EXPORTS``).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, the standard library, ezdxf
(lazily, for a DXF) and gearlever's ``_format``, ``_io``, ``_progress``,
``_result``, ``_validate``, ``data``, ``errors``, ``laws``; never pandas or
matplotlib.
"""

from gearlever.cams.camfile import cam_centre, cam_toml, load_cam
from gearlever.cams.design import CamDesign, design_cam, size_base_radius
from gearlever.cams.export import EXPORTS, export_profile
from gearlever.cams.followers import FOLLOWERS, FollowerParams

__all__ = [
    "EXPORTS",
    "FOLLOWERS",
    "CamDesign",
    "FollowerParams",
    "cam_centre",
    "cam_toml",
    "design_cam",
    "export_profile",
    "load_cam",
    "size_base_radius",
]
