"""Path synthesis: benchmark cases of the literature, DE against CMA-ES, and objective evaluations/s
against pylinkage, one process.

1. Every case of ``gearlever/data/path_benchmarks.toml`` with the default
   settings (budget, seed 0, 2 local dask threads): objective, objective of
   the best published design (recomputed from the design, see the data
   file) and its paper, wall time on this machine.
2. Global search: the package's batched differential evolution against its
   CMA-ES at the same budget (default), seeds 0..2, same polish: median
   final objective per case.
3. Evaluations of the path objective per second, counted as candidates x
   targets / s on one core, on the eighteen-point case (timing: 20 deg
   crank steps): gearlever's batched evaluator (a population of 4096
   candidates per call) against pylinkage 1.3 evaluating the same
   candidates the way its synthesis verifies one (``solution_to_linkage``,
   then ``Linkage.step`` over the crank turn, numba absent so its Python
   path), trajectories checked to agree.  Prints the ratio.
4. Motion generation through five poses (``examples/motion_poses.csv``,
   made from a known four-bar with pivots (0, 0), (4, 0)): gearlever's
   Burmester points (:func:`gearlever.synthesis.burmester_points`) against
   pylinkage 1.3 ``motion_generation`` on the same poses, median time of
   repeated runs, and how exact each tool's dyads are: the spread of the
   moving pivot's distance to its ground pivot over the five poses
   (0 for a dyad that reaches them), relative to the poses' size.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_synthesis.py [--quick]
(needs ``pip install pylinkage==1.3.0`` for part 3).
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time
import tomllib

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from gearlever.data import read_text  # noqa: E402
from gearlever.synthesis.path import DEFAULT_BUDGET, FourBarPathProblem, synthesize_path  # noqa: E402
from gearlever.synthesis.path_fourbar import _coupler  # noqa: E402

CASES = tomllib.loads(read_text("path_benchmarks.toml"))["cases"]


def case_args(c):
    T = np.column_stack([c["x"], c["y"]])
    ang = np.radians(c["input_deg"]) if "input_deg" in c else None
    kw = dict(timing=c["timing"], length_range=c["length_range"], coord_range=c["coord_range"])
    if "pivot" in c:
        kw["pivot"] = c["pivot"]
    if "ground_angle_deg" in c:
        kw["ground_angle"] = math.radians(c["ground_angle_deg"])
    return T, ang, kw


def best_published(c):
    """The case's best published design entry (objective recomputed from the design, see the data file)."""
    return next(d for d in c["published"] if d["label"] == c["best_published"])


def part_cases():
    print(f"1. cases, default settings (seed 0, budget {DEFAULT_BUDGET}, 2 threads)")
    print(f"{'case':24s} {'objective':>12s} {'published':>10s} {'time s':>7s}  best published design (paper)")
    for name, c in CASES.items():
        T, ang, kw = case_args(c)
        t0 = time.perf_counter()
        r = synthesize_path(T, ang, **kw, seed=0, workers=2)
        dt = time.perf_counter() - t0
        pub = best_published(c)
        print(f"{name:24s} {r.objective:12.6g} {pub['objective']:10.4g} {dt:7.1f}  {pub['paper']}")


def part_methods(seeds=(0, 1, 2)):
    print(f"\n2. global search at equal budget ({DEFAULT_BUDGET} evaluations), median objective, seeds {list(seeds)}")
    print(f"{'case':24s} {'DE':>12s} {'CMA-ES':>12s} {'DE s':>7s} {'CMA s':>7s}")
    for name, c in CASES.items():
        T, ang, kw = case_args(c)
        res = {}
        for method in ("de", "cma"):
            vals, times = [], []
            for s in seeds:
                t0 = time.perf_counter()
                vals.append(synthesize_path(T, ang, **kw, seed=s, workers=2, method=method).objective)
                times.append(time.perf_counter() - t0)
            res[method] = (statistics.median(vals), statistics.median(times))
        print(f"{name:24s} {res['de'][0]:12.6g} {res['cma'][0]:12.6g} {res['de'][1]:7.1f} {res['cma'][1]:7.1f}")


def fourbar_solution(p, phi0):
    """pylinkage FourBarSolution of parameters ``p`` with the crank one step before ``phi0``."""
    from pylinkage.synthesis._types import FourBarSolution

    x0, y0, th0, r1, r2, r3, r4, cx, cy, sig = (
        p[k] for k in ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy", "sigma")
    )
    al = th0 + phi0
    A = (x0, y0)
    D = (x0 + r1 * math.cos(th0), y0 + r1 * math.sin(th0))
    B = (x0 + r2 * math.cos(al), y0 + r2 * math.sin(al))
    Dx, Dy = D[0] - B[0], D[1] - B[1]
    f = math.hypot(Dx, Dy)
    cg = (r3 * r3 + f * f - r4 * r4) / (2 * r3 * f)
    sg = sig * math.sqrt(max(0.0, 1 - cg * cg))
    c3, s3 = (Dx * cg - Dy * sg) / f, (Dy * cg + Dx * sg) / f
    C = (B[0] + r3 * c3, B[1] + r3 * s3)
    P = (B[0] + cx * c3 - cy * s3, B[1] + cx * s3 + cy * c3)
    return FourBarSolution(A, D, B, C, r2, r3, r4, r1, P)


def pylinkage_fourbar(sol, iterations):
    """pylinkage linkage of ``sol`` built as its ``solution_to_linkage`` does, plus the rocker pin's
    position as the dyad's start (without it the dyad may start on the other branch)."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRRDyad
    from pylinkage.simulation import Linkage
    from pylinkage.synthesis.conversion import _compute_coupler_point_params

    A, D, B, C = sol.ground_pivot_a, sol.ground_pivot_d, sol.crank_pivot_b, sol.coupler_pivot_c
    ga, gd = Ground(A[0], A[1], name="A"), Ground(D[0], D[1], name="D")
    crank = Crank(
        anchor=ga,
        radius=sol.crank_length,
        angular_velocity=2 * math.pi / iterations,
        initial_angle=math.atan2(B[1] - A[1], B[0] - A[0]),
        name="B",
    )
    jc = RRRDyad(
        anchor1=crank.output, anchor2=gd, distance1=sol.coupler_length, distance2=sol.rocker_length, x=C[0], y=C[1]
    )
    dist, angle = _compute_coupler_point_params(B, C, sol.coupler_point)
    jp = FixedDyad(anchor1=crank.output, anchor2=jc, distance=dist, angle=angle, name="P")
    return Linkage([ga, gd, crank, jc, jp], name="fourbar")


def part_speed(n_ours=4096, n_pl=200):
    print("\n3. path objective evaluations (candidates x targets / s, one core), eighteen-point case")
    c = CASES["kunjur_closed18_timed"]
    T, ang, kw = case_args(c)
    pb = FourBarPathProblem(T, kw["timing"], ang, length_range=kw["length_range"], coord_range=kw["coord_range"])
    rng = np.random.default_rng(0)
    Z = pb.sample(rng, 4 * n_ours)
    Z = Z[np.isfinite(pb.objective(Z))][:n_ours]
    N = pb.N
    reps = []
    for _ in range(5):
        t0 = time.perf_counter()
        F = pb.objective(Z)
        reps.append(time.perf_counter() - t0)
    ours = Z.shape[0] * N / statistics.median(reps)
    print(f"gearlever batched objective: {ours:12.4g} candidate-targets/s ({Z.shape[0]} candidates per call)")
    try:
        import pylinkage
    except ImportError:
        print("pylinkage not installed: pip install pylinkage==1.3.0")
        return
    # pylinkage's dyads take the circle intersection nearest the previous position, so the crank
    # must advance in small steps to stay on one branch: SUB steps per 20 deg target step (1 deg)
    SUB = 20
    step = 2 * math.pi / (N * SUB)
    sub = Z[:n_pl]
    params, _ = pb.params(sub)
    phis = pb.phis(sub)
    t0 = time.perf_counter()
    Fpl = np.empty(len(sub))
    trajs = []
    for i in range(len(sub)):
        p = {k: float(v[i]) for k, v in params.items()}
        lk = pylinkage_fourbar(fourbar_solution(p, phis[i, 0] - step), N * SUB)
        tr = np.array([pos[-1] for pos in lk.step(iterations=N * SUB)], dtype=float)[::SUB]
        Fpl[i] = float(np.sum((tr - T) ** 2))
        trajs.append(tr)
    dt = time.perf_counter() - t0
    theirs = len(sub) * N / dt
    # agreement of the trajectories and objectives
    args = [params[k][:, None] for k in ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy")]
    P = _coupler(*args, phis, params["sigma"][:, None])
    dev = max(float(np.abs(P[i] - trajs[i]).max()) for i in range(len(sub)))
    rel = float(np.max(np.abs(Fpl - F[:n_pl]) / np.maximum(F[:n_pl], 1e-300)))
    print(
        f"pylinkage {pylinkage.__version__} (build linkage + step): {theirs:12.4g} candidate-targets/s "
        f"({len(sub)} candidates, {SUB} steps per target step to hold the branch)"
    )
    print(f"trajectories agree to {dev:.2g} (length), objectives to {rel:.2g} (relative)")
    print(f"ratio gearlever / pylinkage: {ours / theirs:.0f}")
    print(
        f"(per simulated crank position, pylinkage {theirs * SUB:.4g}/s: ratio {ours / (theirs * SUB):.0f}; "
        "pylinkage's numba solver is not installed)"
    )


def _circle_spread(pts, ang, ground, moving):
    """Spread of |M_j - G| over the poses, for a dyad given at the first pose (M_j carried by the coupler)."""
    z = pts[:, 0] + 1j * pts[:, 1]
    Mj = z + np.exp(1j * (ang - ang[0])) * (complex(*moving) - z[0])
    r = np.abs(Mj - complex(*ground))
    return float(np.ptp(r))


def part_motion(repeats=50):
    from gearlever.data import example_path
    from gearlever.synthesis import burmester_points

    print("\n4. motion generation through five poses of a known four-bar (pivots (0, 0) and (4, 0))")
    P = np.loadtxt(example_path("motion_poses.csv"), delimiter=",", skiprows=1)
    pts, ang = P[:, :2], np.radians(P[:, 2])
    size = float(np.ptp(pts, axis=0).max())

    def timed(fn):
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            out = fn()
            times.append(time.perf_counter() - t0)
        return out, statistics.median(times)

    ours, t_ours = timed(lambda: burmester_points(pts, ang))
    spread = max(_circle_spread(pts, ang, d.ground_pivot, d.moving_pivot) for d in ours) / size
    known = (
        min(math.hypot(*d.ground_pivot) for d in ours),
        min(math.hypot(d.ground_pivot[0] - 4, d.ground_pivot[1]) for d in ours),
    )
    print(
        f"gearlever burmester_points   {t_ours * 1e3:8.3f} ms  {len(ours)} dyads, circle spread <= {spread:.1e} "
        f"of the size; known pivots found to {max(known):.1e}"
    )
    try:
        from pylinkage.synthesis import Pose, motion_generation
    except ImportError:
        print("pylinkage not installed: pip install pylinkage==1.3.0")
        return
    poses = [Pose(float(x), float(y), float(a)) for (x, y), a in zip(pts, ang)]
    res, t_pl = timed(lambda: motion_generation(poses, max_solutions=None, require_grashof=False))
    dyads = set()
    for sol in res.solutions:
        c = {d.name: (d.x, d.y) for d in sol.dyads}
        dyads.add((c["A"], c["B"]))
        dyads.add((c["D"], c["C"]))
    spreads = [_circle_spread(pts, ang, g, m) / size for g, m in dyads]
    grounds = {g for g, _ in dyads}
    known = min(math.hypot(*g) for g in grounds), min(math.hypot(g[0] - 4, g[1]) for g in grounds)
    print(
        f"pylinkage motion_generation  {t_pl * 1e3:8.3f} ms  {len(res.solutions)} four-bars, {len(dyads)} dyads, circle"
        f" spread {min(spreads):.1e} .. {max(spreads):.1e} of the size; nearest to the known pivots"
        f" {known[0]:.3g}, {known[1]:.3g}"
    )
    print(f"ratio: gearlever {t_pl / t_ours:.1f}x faster, and its dyads reach the five poses")


def main():
    quick = "--quick" in sys.argv
    if "--motion" in sys.argv:
        part_motion()
        return
    part_speed()
    part_motion()
    if "--speed" in sys.argv:
        return
    part_cases()
    if not quick:
        part_methods()


if __name__ == "__main__":
    main()
