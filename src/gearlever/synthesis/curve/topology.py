"""Dyadic topologies of the curve synthesis: joints, edges, ground pivots, motor, traced joint, random draws.

A leaf of :mod:`gearlever.synthesis.curve`: the library (:mod:`gearlever.synthesis.curve.library`),
the targets (:mod:`gearlever.synthesis.curve.targets`) and the search
(:mod:`gearlever.synthesis.curve.search`) all build on it.

Imports numpy, :mod:`gearlever.mechanism.linkage` and :mod:`gearlever.errors`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever.mechanism.linkage import Linkage, SolvePlan, _plan

__all__ = ["Topology", "prune", "random_sketches", "random_topology"]


@dataclass(frozen=True, eq=False)
class Topology:
    """A dyadic topology: joints, edges, fixed joints, motor, traced joint and its solve plan."""

    n: int
    edges: np.ndarray
    fixed: np.ndarray
    motor: tuple
    target: int
    plan: SolvePlan

    def linkage(self, x0) -> Linkage:
        return Linkage(np.asarray(x0, dtype=float) + 0.0, self.edges, self.fixed, self.motor, self.target)

    def key(self) -> tuple:
        return (self.n, tuple(map(tuple, self.edges.tolist())), tuple(self.fixed.tolist()), self.motor, self.target)


def _topology(n, edges, fixed, motor, target) -> Topology:
    edges = np.asarray(edges, dtype=int).reshape(-1, 2)
    fixed = np.asarray(sorted(set(int(f) for f in fixed)), dtype=int)
    plan = _plan(n, edges, fixed, int(motor[0]), int(motor[1]))
    return Topology(n, edges, fixed, (int(motor[0]), int(motor[1])), int(target), plan)


def random_topology(rng, n_dyads: int, n_fixed: int) -> Topology:
    """A random dyadic topology: joint 0 the motor pivot, 1 the crank tip, then other fixed joints, then dyads."""
    fixed = list(range(2, 1 + n_fixed)) + [0]
    edges = [[0, 1]]
    n = 1 + n_fixed
    moving = [1]
    for _ in range(n_dyads):
        k = n
        while True:
            i, j = sorted(rng.choice(n, 2, replace=False).tolist())
            if (i in fixed and j in fixed) or {i, j} == {0, 1}:
                continue
            # prefer parents among the newest moving joints: deeper chains
            break
        edges += [[i, k], [j, k]]
        moving.append(k)
        n += 1
    return _topology(n, edges, fixed, (0, 1), n - 1)


def prune(topo: Topology, target: int) -> tuple[Topology, np.ndarray]:
    """The topology reduced to the joints ``target`` needs, and the kept joint indices (old numbering)."""
    parents = {int(k): (int(i), int(j)) for k, i, j, _ in topo.plan.dyads}
    need = {topo.motor[0], topo.motor[1], target}
    stack = [target]
    while stack:
        for p in parents.get(stack.pop(), ()):
            if p not in need or p in parents:
                stack.append(p)
            need.add(p)
    keep = np.array(sorted(need), dtype=int)
    new = {int(o): n for n, o in enumerate(keep)}
    edges = [[new[int(i)], new[int(j)]] for i, j in topo.edges if int(i) in new and int(j) in new]
    # fixed-fixed edges carry no motion: drop them
    fixed = [new[int(f)] for f in topo.fixed if int(f) in new]
    fs = set(fixed)
    edges = [e for e in edges if not (e[0] in fs and e[1] in fs)]
    return _topology(len(keep), edges, fixed, (new[topo.motor[0]], new[topo.motor[1]]), new[target]), keep


def random_sketches(rng, topo: Topology, count: int) -> np.ndarray:
    """Random sketches: joints uniform in the unit square around the origin, a short crank."""
    x = rng.uniform(-1.0, 1.0, (count, topo.n, 2))
    r = rng.uniform(0.05, 0.5, count)
    a = rng.uniform(0.0, 2 * math.pi, count)
    p, t = topo.motor
    x[:, t, 0] = x[:, p, 0] + r * np.cos(a)
    x[:, t, 1] = x[:, p, 1] + r * np.sin(a)
    return x
