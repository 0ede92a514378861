"""Gear networks at scale: exact (sparse fractions) and float (sparse LU) paths against scipy's splu.

Builds networks of 10^2 .. 10^4 members: a spine of equal 30-tooth gears
(the drive), from each spine gear a branch of meshes, and the ends of each
pair of branches joined by a differential on a free carrier; one input (s0).
For each size it prints the parse time of the CSV text, the exact path
(``Network.solve``: analysis + solution in fractions), the float path
(``Network.solve_float``) and ``scipy.sparse.linalg.splu`` alone on the same
square constraint matrix (input column removed), with the ratios of both
paths to splu.  Goals at 10^4 members: float <= 30x splu, exact <= 300x.

Run: ``.venv/bin/python benchmarks/bench_networks.py``
"""

from __future__ import annotations

import sys
import time

import numpy as np

from gearlever.gears.networks import Differential, Gear, Mesh, Network, parse_network

BRANCH = 10


def branch_network(members: int, branch: int = BRANCH) -> Network:
    """About ``members`` members: spine s_k (30 teeth), branches g_k_j, differential carriers c_k."""
    per = branch + 1.5  # spine gear + branch (+ half a carrier)
    count = max(2, int(members / per))
    count -= count % 2
    gears, cons = [Gear("s0", 30)], []
    for k in range(count):
        if k:
            gears.append(Gear(f"s{k}", 30))
            cons.append(Mesh(f"sp{k}", f"s{k - 1}", f"s{k}"))
        length = branch + (k % 2)  # odd branches one gear longer: the differentials do not cancel
        for j in range(length):
            gears.append(Gear(f"g{k}_{j}", 12 + (7 * k + 5 * j) % 40))
            cons.append(Mesh(f"m{k}_{j}", f"s{k}" if j == 0 else f"g{k}_{j - 1}", f"g{k}_{j}"))
        if k % 2:
            gears.append(Gear(f"c{k}"))
            cons.append(Differential(f"d{k}", f"g{k - 1}_{branch - 1}", f"g{k}_{length - 1}", f"c{k}"))
    return Network(gears, cons)


def to_csv(net: Network) -> str:
    lines = [f"member,{g.name},gear,{'' if g.teeth is None else g.teeth}" for g in net.gears]
    for c in net.constraints:
        if isinstance(c, Mesh):
            lines.append(f"constraint,{c.label},mesh,{c.p},{c.q},,{c.sign}")
        else:
            lines.append(f"constraint,{c.label},differential,{c.a},{c.b},{c.carrier}")
    return "\n".join(lines) + "\n"


def best_of(fn, repeat, *args):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn(*args)
        best = min(best, time.perf_counter() - t)
    return best


def main(sizes=(100, 1000, 10000)) -> int:
    import scipy.sparse.linalg as spla

    heads = ("members", "parse s", "exact s", "float s", "splu s", "exact/splu", "float/splu")
    print(" ".join(f"{h:>11}" for h in heads))
    for size in sizes:
        net = branch_network(size)
        text = to_csv(net)
        repeat = 3 if size <= 1000 else 2
        t_parse = best_of(parse_network, repeat, text)
        t_exact = best_of(net.solve, repeat, ["s0"])
        t_float = best_of(net.solve_float, 5, ["s0"])
        A = net.matrix_sparse().tocsc()
        A_o = A[:, 1:].tocsc()  # s0 is column 0
        t_splu = best_of(spla.splu, 7, A_o)
        X = net.solve_float(["s0"])
        exact = net.solve(["s0"]).matrix(net.names)
        assert np.allclose(X, exact, rtol=1e-9, atol=1e-12)
        print(
            f"{len(net.gears):>11} {t_parse:>11.4f} {t_exact:>11.4f} {t_float:>11.4f} {t_splu:>11.5f} "
            f"{t_exact / t_splu:>11.0f} {t_float / t_splu:>11.1f}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
