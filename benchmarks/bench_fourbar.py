"""Four-bar speed: the `mechanism` package (fsolve per step) vs gearlever, one process.

Four-bar ground 9, crank 5, coupler 8, rocker 8 (a crank-rocker); positions,
angular velocities and angular accelerations over a full crank turn at 3600
points, constant crank speed OMEGA.  Prints both times, their ratio (target
>= 3000), the agreement, gearlever's general Newton engine on the same loop,
and gearlever's closed form at 10^6 points.

Run: .venv/bin/python benchmarks/bench_fourbar.py   (needs `pip install mechanism`)
"""

from __future__ import annotations

import statistics
import time
import warnings

import numpy as np

from gearlever import fourbar
from gearlever.loops import fourbar_system

N = 3600
OMEGA = 1.7
LINKS = (9.0, 5.0, 8.0, 8.0)  # ground, crank, coupler, rocker


def wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def timed(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def run_mechanism(theta2):
    import mechanism

    O, A, B, C = mechanism.get_joints("O A B C")
    a = mechanism.Vector((O, A), r=LINKS[1])
    b = mechanism.Vector((A, B), r=LINKS[2])
    c = mechanism.Vector((O, C), r=LINKS[0], theta=0, style="ground")
    d = mechanism.Vector((C, B), r=LINKS[3])

    def loops(x, inp):
        return a(inp) + b(x[0]) - c() - d(x[1])

    r0 = fourbar(*LINKS, theta2[:1])
    guess = (np.array([r0.theta3[0], r0.theta4[0]]), np.array([1.0, 1.0]), np.array([1.0, 1.0]))
    m = mechanism.Mechanism(
        vectors=(a, b, c, d),
        origin=O,
        loops=loops,
        pos=theta2,
        vel=np.full(theta2.size, OMEGA),
        acc=np.zeros(theta2.size),
        guess=guess,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # fsolve's "not making good progress"
        m.iterate()
    return b, d


def main() -> None:
    theta2 = np.linspace(0.0, 2 * np.pi, N, endpoint=False)
    t0 = time.perf_counter()
    coupler, rocker = run_mechanism(theta2)
    t_mech = time.perf_counter() - t0

    t_gl, r = timed(lambda: fourbar(*LINKS, theta2), 200)
    system = fourbar_system(*LINKS)
    seed = {"theta3": float(r.theta3[0]), "theta4": float(r.theta4[0])}
    t_newton, sol = timed(lambda: system.solve(theta2, seed), 3)

    dev = {
        "theta3 (rad)": np.abs(wrap(coupler.pos.thetas - r.theta3)).max(),
        "theta4 (rad)": np.abs(wrap(rocker.pos.thetas - r.theta4)).max(),
        "omega3 (rad/s)": np.abs(coupler.vel.omegas - OMEGA * r.dtheta3_dphi).max(),
        "omega4 (rad/s)": np.abs(rocker.vel.omegas - OMEGA * r.dtheta4_dphi).max(),
        "alpha3 (rad/s^2)": np.abs(coupler.acc.alphas - OMEGA**2 * r.d2theta3_dphi2).max(),
        "alpha4 (rad/s^2)": np.abs(rocker.acc.alphas - OMEGA**2 * r.d2theta4_dphi2).max(),
    }
    newton_dev = max(np.abs(wrap(sol["theta4"] - r.theta4)).max(), np.abs(sol.d2("theta4") - r.d2theta4_dphi2).max())

    big = np.linspace(0.0, 2 * np.pi, 1_000_000, endpoint=False)
    t_big, _ = timed(lambda: fourbar(*LINKS, big), 5)

    print(
        f"four-bar {'/'.join(f'{v:g}' for v in LINKS)} (ground/crank/coupler/rocker), "
        f"{N} points, position + velocity + acceleration"
    )
    from importlib.metadata import version

    print(f"  mechanism {version('mechanism')} (fsolve per step, 1 run): {t_mech:10.4f} s")
    print(f"  gearlever.fourbar (closed form, median of 200): {t_gl * 1e3:10.4f} ms")
    print(f"  ratio mechanism / gearlever.fourbar: {t_mech / t_gl:10.0f} x   (target >= 3000)")
    print(
        f"  gearlever LoopSystem.solve (general batched Newton, median of 3): {t_newton * 1e3:8.2f} ms "
        f"(ratio {t_mech / t_newton:.0f} x; max deviation from closed form {newton_dev:.1e})"
    )
    print("  agreement with mechanism (max |difference| over the turn):")
    for k, v in dev.items():
        print(f"    {k:18s} {v:.2e}")
    print(f"  gearlever.fourbar at 10^6 points (median of 5): {t_big:.4f} s ({t_big / 1e6 * 1e9:.0f} ns per point)")


if __name__ == "__main__":
    main()
