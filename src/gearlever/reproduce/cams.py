"""Figures of the shipped motion laws and the disc cams that give them (SVAJ diagrams and profile)."""

from __future__ import annotations

import math
from pathlib import Path

#: The shipped laws and the cam drawn for each: follower kind and dimensions.
CASES = {
    "law_lift": ("translating-roller", {"base_radius": 40.0, "roller_radius": 8.0, "offset": 0.0}),
    "law_dwell_rocker": (
        "oscillating-roller",
        {"base_radius": 40.0, "roller_radius": 8.0, "arm": 60.0, "pivot_distance": 90.0},
    ),
}


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.cams import design_cam
    from gearlever.data import example_path
    from gearlever.errors import a
    from gearlever.laws import load_law
    from gearlever.plotting._common import save
    from gearlever.plotting.cam import cam_design_figure

    out = []
    for name, (follower, dims) in CASES.items():
        law = load_law(example_path(f"{name}.toml"))
        cam = design_cam(law, follower, **dims, points=3600)
        target = Path(figures_dir) / f"cam_{name}.png"
        save(cam_design_figure(cam, law.evaluate(cam.theta)), target, dpi=80)
        out.append(
            f"cams: {name} with {a(follower)} follower (base radius {cam.base_radius:g}): "
            f"pressure angle max {math.degrees(cam.pressure_angle_max):.2f} deg, "
            f"radius of curvature min {cam.curvature_radius_min:.3f}, undercut {cam.undercut} -> figures/{target.name}"
        )
    return out
