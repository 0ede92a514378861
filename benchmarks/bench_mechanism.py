"""Benchmark: the four-bar model file through gearlever.Mechanism against three references.

All timings in this process, best of 15 repeats, interleaved; the comparison with pylinkage
is printed in wall time and in CPU time of the process (``time.process_time``: both sides run
on one thread; on a shared machine the CPU time leaves out the time the process waits for a
core, so it varies less from run to run):

1. the `mechanism` package (scipy fsolve per position, velocity and
   acceleration) per point, target: Mechanism at least 2000 times faster;
2. the closed form ``gearlever.fourbar`` on 10**5 crank angles, target:
   Mechanism (solve plus position, velocity and acceleration of the
   coupler-rocker joint B) within 3 times its time;
3. pylinkage 1.3 with numba, ``Linkage.step_fast_with_kinematics`` computing
   the same (positions, velocities, accelerations of B over 10**5 crank
   angles), target: Mechanism at least 3 times faster.  Skipped with a note
   when pylinkage is not installed (``pip install '.[bench]'``).
"""

from __future__ import annotations

import math
import time
import warnings
from pathlib import Path

import numpy as np
from _machine import machine_line

import gearlever
from gearlever import fourbar

N = 10**5
REPEATS = 15
MODEL = Path(__file__).resolve().parents[1] / "examples" / "fourbar.toml"
A, B = (10.0, 0.0), (45.1, 28.3)
GROUND, CRANK = 40.0, 10.0
COUPLER, ROCKER = math.dist(A, B), math.dist((40.0, 0.0), B)


def best(fn, repeats=REPEATS, clock=time.perf_counter) -> float:
    t = float("inf")
    for _ in range(repeats):
        t0 = clock()
        fn()
        t = min(t, clock() - t0)
    return t


def ours(mech, th):
    r = mech.solve(th)
    return r.point["B"], r.velocity["B"], r.acceleration["B"]


def mechanism_package_runner(points=40):
    """A callable running the `mechanism` package over ``points`` crank angles, or None if not installed."""
    try:
        import mechanism
    except ImportError:
        return None
    th = np.linspace(0.0, 2 * np.pi, points, endpoint=False)
    O, Aj, Bj, C = mechanism.get_joints("O A B C")
    a = mechanism.Vector((O, Aj), r=CRANK)
    b = mechanism.Vector((Aj, Bj), r=COUPLER)
    c = mechanism.Vector((O, C), r=GROUND, theta=0, style="ground")
    d = mechanism.Vector((C, Bj), r=ROCKER)

    def loops(x, inp):
        return a(inp) + b(x[0]) - c() - d(x[1])

    f = fourbar(GROUND, CRANK, COUPLER, ROCKER, th[:1])
    guess = (np.array([f.theta3[0], f.theta4[0]]), np.array([1.0, 1.0]), np.array([1.0, 1.0]))

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = mechanism.Mechanism(
                vectors=(a, b, c, d),
                origin=O,
                loops=loops,
                pos=th,
                vel=np.ones(points),
                acc=np.zeros(points),
                guess=guess,
            )
            m.iterate()

    return run, points


def pylinkage_runner():
    try:
        import pylinkage as pl
    except ImportError:
        return None, None
    O2, O4 = pl.Ground(0.0, 0.0, name="O2"), pl.Ground(GROUND, 0.0, name="O4")
    crank = pl.Crank(O2, radius=CRANK, angular_velocity=2 * np.pi / N, initial_angle=0.0, name="crank")
    joint = pl.RRRDyad(crank.output, O4, distance1=COUPLER, distance2=ROCKER, x=B[0], y=B[1], name="B")
    linkage = pl.Linkage([O2, O4, crank, joint])
    linkage.set_input_velocity(crank, omega=1.0, alpha=0.0)

    def run():
        return linkage.step_fast_with_kinematics(iterations=N)

    return run, pl.__version__


def main() -> None:
    print(machine_line())
    mech = gearlever.Mechanism.load(MODEL)
    th = np.linspace(0.0, 2 * np.pi, N, endpoint=False)
    ours(mech, th)  # compile the model once
    P, V, Acc = ours(mech, th)
    f = fourbar(GROUND, CRANK, COUPLER, ROCKER, th)
    Bx = GROUND + ROCKER * np.cos(f.theta4)
    assert np.abs(P[:, 0] - Bx).max() < 1e-9
    plk, plk_version = pylinkage_runner()
    if plk is not None:
        pos, vel, acc = plk()  # numba compilation
    pkg = mechanism_package_runner()
    if pkg is not None:
        pkg[0]()
    # interleaved: one run of each side per round, best of REPEATS rounds
    t_ours = t_fb = t_pl = t_pkg = float("inf")
    c_ours = c_pl = float("inf")  # CPU time of this process (both sides run on one thread)
    for _ in range(REPEATS):
        t_ours = min(t_ours, best(lambda: ours(mech, th), 1))
        c_ours = min(c_ours, best(lambda: ours(mech, th), 1, time.process_time))
        t_fb = min(t_fb, best(lambda: fourbar(GROUND, CRANK, COUPLER, ROCKER, th), 1))
        if plk is not None:
            t_pl = min(t_pl, best(plk, 1))
            c_pl = min(c_pl, best(plk, 1, time.process_time))
        if pkg is not None:
            t_pkg = min(t_pkg, best(pkg[0], 1))
    per_point = t_ours / N
    print(
        f"Mechanism (four-bar model file): {N} crank angles in {t_ours * 1e3:.2f} ms = {per_point * 1e9:.0f} ns/point"
    )
    print(
        f"closed-form gearlever.fourbar: {t_fb * 1e3:.2f} ms; ratio Mechanism/fourbar = {t_ours / t_fb:.2f} "
        f"(target <= 3): {'ok' if t_ours / t_fb <= 3 else 'ABOVE TARGET'}"
    )
    if pkg is None:
        print("mechanism package not installed: comparison skipped (pip install '.[test]')")
    else:
        t_pkg /= pkg[1]
        ratio = t_pkg / per_point
        print(
            f"mechanism package: {t_pkg * 1e3:.2f} ms/point; speed-up = {ratio:.0f}x "
            f"(target >= 2000): {'ok' if ratio >= 2000 else 'BELOW TARGET'}"
        )
    if plk is None:
        print("pylinkage not installed: comparison skipped (pip install '.[bench]')")
    else:
        # pylinkage turns the crank before it records a row: row i is at crank angle (i + 1) * 2 pi / N
        r = mech.solve(th + 2 * np.pi / N)
        err = [
            np.abs(a[:, -1, :] - d["B"]).max() for a, d in ((pos, r.point), (vel, r.velocity), (acc, r.acceleration))
        ]
        ratio = t_pl / t_ours
        print(
            f"pylinkage {plk_version} step_fast_with_kinematics (numba): {t_pl * 1e3:.2f} ms = "
            f"{t_pl / N * 1e9:.0f} ns/point; speed-up = {ratio:.2f}x "
            f"(target >= 3): {'ok' if ratio >= 3 else 'BELOW TARGET'}"
        )
        cratio = c_pl / c_ours
        print(
            f"  in CPU time of this process: ours {c_ours / N * 1e9:.0f} ns/point, pylinkage "
            f"{c_pl / N * 1e9:.0f} ns/point; speed-up = {cratio:.2f}x "
            f"(target >= 3): {'ok' if cratio >= 3 else 'BELOW TARGET'}"
        )
        print(
            f"  agreement with pylinkage (its rows at crank angles (i + 1) 2 pi / N): max |B difference| "
            f"position {err[0]:.1e}, velocity {err[1]:.1e}, acceleration {err[2]:.1e}"
        )


if __name__ == "__main__":
    main()
