"""Figure of a curve synthesis: the distance-material front, the best curves over the target, the best linkage."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def _aligned(curve, target):
    """The traced curve in the target's frame: centred, best rotation, target's centre (for drawing)."""
    from gearlever.curves.score import _alignment_indices, normalise

    cz, tz = normalise(curve[None], target)
    n = tz.shape[0]
    C = cz[0][_alignment_indices(n)]
    z = (tz * np.conj(C)).sum(-1)
    rot = np.exp(1j * np.angle(z))
    a = int(np.argmin(np.abs(tz - rot[:, None] * C).mean(-1)))
    return rot[a], C[a]


def curve_synthesis_plot(result, target, fig=None, best: int = 3):
    """Three panels: front (distance vs material, feasible box), best curves over the target, best linkage.

    Returns the Figure.
    """
    from gearlever.curves.links import solve_plan
    from gearlever.curves.score import REFERENCE, resample
    from gearlever.curves.simulate import simulate

    fig = fig or plt.figure(figsize=(13.0, 4.3))
    a1, a2, a3 = fig.subplots(1, 3)
    d, m = np.asarray(result.distance), np.asarray(result.material)
    a1.step(d, m, where="post", color="C0")
    a1.plot(d, m, "o", ms=3, color="C0", label=f"front ({len(d)} designs)")
    a1.axvline(REFERENCE[0], color="0.6", ls="--")
    a1.axhline(REFERENCE[1], color="0.6", ls="--")
    a1.set(xlabel="distance", ylabel="material", title=f"hypervolume {result.hypervolume:.3f}")
    a1.legend(loc="upper right")
    t = resample(np.asarray(target, dtype=float)[None])[0]
    tc = t - t.mean(0)
    s = np.sqrt((tc**2).sum(-1).mean())
    a2.plot(tc[:, 0] / s, tc[:, 1] / s, color="k", lw=3, alpha=0.4, label="target")
    for n, lk in enumerate(result.designs[:best]):
        x = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint]
        rot, cz = _aligned(x, target)
        z = rot * cz
        a2.plot(z.real, z.imag, lw=1.2, label=f"{n + 1:04d}: distance {d[n]:.3g}, material {m[n]:.3g}")
    a2.set_aspect("equal")
    a2.set(title="best curves (target's frame, scaled by its RMS radius)")
    a2.legend(loc="lower center", fontsize=7)
    if result.designs:
        lk = result.designs[0]
        x = simulate(lk.x0[None], solve_plan(lk))[0]
        for i, j in lk.edges:
            a3.plot(*lk.x0[[i, j]].T, color="C0", lw=2)
        a3.plot(*lk.x0[lk.fixed_joints].T, "^", color="k", ms=8)
        a3.plot(*lk.x0.T, "o", color="w", mec="C0", ms=5)
        a3.plot(*x[lk.target_joint].T, color="C3", lw=1)
        a3.plot(*lk.x0[list(lk.motor)].T, color="C1", lw=3)
        a3.set_aspect("equal")
        a3.set(title=f"0001: {lk.n_joints} joints, {len(lk.edges)} links")
    fig.tight_layout()
    return fig
