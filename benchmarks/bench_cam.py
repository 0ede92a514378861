"""Benchmark: a disc cam of 3600 profile points, against pylinkage's and `mechanism`'s cam functions.

The same law (cycloidal rise of 20 over 120 deg, dwell 60, cycloidal return
over 120, dwell 60) in the three packages, in this process:

- gearlever ``design_cam`` (translating roller, base radius 40, roller 8):
  pitch curve, cam surface, pressure angle, radius of curvature at 3600
  angles (target: under 1 s), timed beside pylinkage's ``FunctionProfile``
  evaluating the pitch radius and pressure angle at the same 3600 angles
  (a Python loop over its scalar functions): values compared point by point,
  and the ratio pylinkage_time / gearlever_time printed.
- base-circle sizing for a 30 deg maximum pressure angle (roller 8) and for a
  minimum radius of curvature 10 (flat face), against ``mechanism``'s
  ``Cam.get_base_circle`` (its grid of 3600 angles), with the flat follower's
  face width.  mechanism's roller sizing uses sqrt((Rb + Rf)**2 + e**2), so
  only zero offset is compared.
"""

from __future__ import annotations

import math
import time

import numpy as np

from gearlever.cams import design_cam, size_base_radius
from gearlever.laws import law_from_segments

H, RB, RR = 20.0, 40.0, 8.0
POINTS = 3600
REPEATS = 5


def best(fn, repeats=REPEATS):
    out, t = None, float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        t = min(t, time.perf_counter() - t0)
    return out, t


def main() -> None:
    law = law_from_segments(
        "displacement",
        "mm",
        [
            {"to": 120, "motion": "cycloidal", "rise": H},
            {"to": 180, "motion": "dwell"},
            {"to": 300, "motion": "cycloidal", "rise": -H},
            {"to": 360, "motion": "dwell"},
        ],
    )
    cam, t_gl = best(lambda: design_cam(law, "translating-roller", base_radius=RB, roller_radius=RR, points=POINTS))
    print(
        f"gearlever design_cam: {POINTS} points in {t_gl * 1e3:.1f} ms (target < 1000 ms): "
        f"{'ok' if t_gl < 1.0 else 'ABOVE TARGET'}"
    )

    from pylinkage.cam import CycloidalMotionLaw, FunctionProfile

    prof = FunctionProfile(
        motion_law=CycloidalMotionLaw(),
        base_radius=RB + RR,
        total_lift=H,
        rise_start=0.0,
        rise_end=2 * math.pi / 3,
        dwell_high_end=math.pi,
        fall_end=5 * math.pi / 3,
    )
    prof.evaluate(0.1), prof.pressure_angle(0.1)  # compile its numba kernels before timing

    def pyl():
        r = np.array([prof.evaluate(x) for x in cam.theta])
        phi = np.array([prof.pressure_angle(x) for x in cam.theta])
        return r, phi

    (r_pl, phi_pl), t_pl = best(pyl, 3)
    dr = np.max(np.abs(r_pl - np.hypot(*cam.pitch.T)))
    dphi = np.degrees(np.max(np.abs(phi_pl - cam.pressure_angle)))
    print(
        f"pylinkage FunctionProfile: pitch radius + pressure angle at {POINTS} angles in {t_pl * 1e3:.1f} ms; "
        f"max |pitch radius diff| {dr:.2e} mm, max |pressure angle diff| {dphi:.2e} deg"
    )
    print(f"ratio pylinkage/gearlever = {t_pl / t_gl:.2f} (gearlever also gives the surface and curvature)")

    from mechanism.cams import Cam

    def mech():
        c = Cam(
            motion=[("Rise", H, 120), ("Dwell", 60), ("Fall", H, 120), ("Dwell", 60)],
            degrees=True,
            omega=1.0,
            h=2 * math.pi / POINTS,
        )
        return (
            c.get_base_circle(kind="cycloidal", follower="roller", roller_radius=RR, max_pressure_angle=30),
            c.get_base_circle(kind="cycloidal", follower="flat", desired_min_rho=10.0),
        )

    (m_roll, m_flat), t_m = best(mech, 3)

    def ours():
        rb_r = size_base_radius(law, "translating-roller", roller_radius=RR, max_pressure_angle=math.radians(30))
        rb_f = size_base_radius(law, "translating-flat", min_curvature_radius=10.0)
        return rb_r, rb_f, design_cam(law, "translating-flat", base_radius=rb_f, points=POINTS).face_width

    (rb_r, rb_f, fw), t_o = best(ours, 3)
    print(
        f"base radius for 30 deg (roller {RR:g}): gearlever {rb_r:.6f}, mechanism {m_roll['Rb']:.6f} "
        f"(diff {abs(rb_r - m_roll['Rb']):.1e})"
    )
    print(
        f"base radius for rho_min 10 (flat): gearlever {rb_f:.6f}, mechanism {m_flat['Rb']:.6f} "
        f"(diff {abs(rb_f - m_flat['Rb']):.1e}); face width {fw:.6f} vs {m_flat['Min Face Width']:.6f}"
    )
    print(
        f"sizing time: gearlever {t_o * 1e3:.1f} ms (bisection with a fold/undercut check per step), "
        f"mechanism {t_m * 1e3:.1f} ms (fsolve / closed form); ratio mechanism/gearlever = {t_m / t_o:.3f}"
    )


if __name__ == "__main__":
    main()
