"""The cams of the cam page tests: one design per follower kind (and an offset translating roller)."""

from __future__ import annotations

from pathlib import Path

from gearlever.cams import design_cam
from gearlever.laws import law_from_segments, load_law

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ROCK20 = [
    {"to": 120, "motion": "dwell"},
    {"to": 240, "motion": "cycloidal", "rise": 20},
    {"to": 360, "motion": "345", "rise": -20},
]


def designs():
    """One design per follower kind (and an offset translating roller), 3600 points."""
    lift = load_law(EXAMPLES / "law_lift.toml")
    rocker = load_law(EXAMPLES / "law_dwell_rocker.toml")
    rock20 = law_from_segments("angle", "deg", ROCK20)
    return {
        "translating-roller": design_cam(lift, "translating-roller", base_radius=40.0, roller_radius=8.0),
        "offset-roller": design_cam(lift, "translating-roller", base_radius=40.0, roller_radius=8.0, offset=6.0),
        "translating-flat": design_cam(lift, "translating-flat", base_radius=45.0),
        "oscillating-roller": design_cam(
            rocker, "oscillating-roller", base_radius=30.0, roller_radius=6.0, arm=50.0, pivot_distance=70.0
        ),
        "oscillating-flat": design_cam(rock20, "oscillating-flat", base_radius=55.0, pivot_distance=100.0, offset=5.0),
    }
