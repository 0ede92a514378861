"""Gears: the Willis relation, gear networks, the south-pointing chariot, the car differential.

- :mod:`~gearlever.gears.willis`: the Willis (inverted-motion) relation of a pair
  of gears on a carrier, the one statement of its sign rule used everywhere.
- :mod:`~gearlever.gears.networks`: gear networks as data (members, meshes,
  differentials, shafts), solved exactly in fractions.
- :mod:`~gearlever.gears.epicyclic`: the tabular method of epicyclic trains.
- :mod:`~gearlever.gears.planetary`: planetary sets, assembly conditions, tooth search.
- :mod:`~gearlever.gears.chariot`: the Nuttall south-pointing chariot.
- :mod:`~gearlever.gears.car`: the car (bevel) differential.
- :mod:`~gearlever.gears.geometry`: involute tooth geometry of spur and helical
  pairs (external, internal, rack), tooth outlines, planetary sets with shifted gears.
- :mod:`~gearlever.gears.strength`: Lewis, Hertz and AGMA tooth stresses, over a mechanism's cycle.

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, :mod:`fractions` and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``data``, ``errors``; never pandas or matplotlib.
"""

from gearlever.gears.car import car_differential
from gearlever.gears.chariot import NuttallTeeth, design_nuttall, simulate
from gearlever.gears.epicyclic import TabularMethod, tabular_method
from gearlever.gears.geometry import GearMesh, PlanetaryGeometry, ToothProfile, planetary_geometry, tooth_outline
from gearlever.gears.networks import Differential, Gear, Mesh, Network, SameShaft, parse_network
from gearlever.gears.planetary import PlanetaryDesign, PlanetarySet, design_planetary, planetary_network
from gearlever.gears.strength import MeshStress, mesh_stresses

__all__ = [
    "Differential",
    "Gear",
    "Mesh",
    "Network",
    "SameShaft",
    "parse_network",
    "TabularMethod",
    "tabular_method",
    "PlanetaryDesign",
    "PlanetarySet",
    "design_planetary",
    "planetary_network",
    "NuttallTeeth",
    "design_nuttall",
    "simulate",
    "car_differential",
    "GearMesh",
    "ToothProfile",
    "PlanetaryGeometry",
    "tooth_outline",
    "planetary_geometry",
    "MeshStress",
    "mesh_stresses",
]
