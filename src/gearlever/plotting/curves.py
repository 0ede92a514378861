"""Figure of a curve synthesis: the distance-material front, the best curves over the target, the best linkage."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def curve_synthesis_plot(result, target, fig=None, best: int = 3):
    """Three panels: front (distance vs material, feasible box), best curves over the target, best linkage.

    The designs of :func:`gearlever.synthesis.curve.search.synthesize_curve` are in the
    target's frame: the curves and the linkage are drawn where they run, over
    the target (closed in the relative scoring).  Returns the Figure.
    """
    from gearlever.mechanism.linkage import solve_plan
    from gearlever.synthesis.curve.score import REFERENCE, closed
    from gearlever.synthesis.curve.simulate import simulate

    fig = fig or plt.figure(figsize=(13.0, 4.3))
    a1, a2, a3 = fig.subplots(1, 3)
    d, m = np.asarray(result.error), np.asarray(result.material)
    a1.step(d, m, where="post", color="C0")
    a1.plot(d, m, "o", ms=3, color="C0")
    a1.axvline(REFERENCE[0], color="0.6", ls="--")
    a1.axhline(REFERENCE[1], color="0.6", ls="--")
    a1.set(xlabel="distance", ylabel="material", title=f"{len(d)} designs, hypervolume {result.hypervolume:.3f}")
    scored = closed(target) if getattr(result, "scoring", "challenge") == "relative" else np.asarray(target, float)
    a2.plot(*scored.T, color="k", lw=3, alpha=0.4, label="target")
    for n, lk in enumerate(result.designs[:best]):
        x = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint]
        a2.plot(*x.T, lw=1.2, label=f"{n + 1:04d}: distance {d[n]:.3g}, material {m[n]:.3g}")
    a2.set_aspect("equal", adjustable="datalim")
    a2.set(title="best traced curves on the target (as written)")
    # below the axes: the legend never covers a curve
    a2.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=7, ncol=1, frameon=False)
    if result.designs:
        lk = result.designs[0]
        x = simulate(lk.x0[None], solve_plan(lk))[0]
        a3.plot(*scored.T, color="k", lw=3, alpha=0.25)
        for i, j in lk.edges:
            a3.plot(*lk.x0[[i, j]].T, color="C0", lw=2)
        a3.plot(*lk.x0[lk.fixed_joints].T, "^", color="k", ms=8)
        a3.plot(*lk.x0.T, "o", color="w", mec="C0", ms=5)
        a3.plot(*x[lk.target_joint].T, color="C3", lw=1)
        a3.plot(*lk.x0[list(lk.motor)].T, color="C1", lw=3)
        a3.set_aspect("equal")
        a3.set(title=f"0001: {lk.n_joints} joints, {len(lk.edges)} links")
    else:
        a3.plot(*scored.T, color="k", lw=3, alpha=0.25)
        a3.set_aspect("equal")
        a3.set(title="no design on the front")
        a3.text(0.5, 0.5, "no feasible design", transform=a3.transAxes, ha="center", va="center")
    fig.tight_layout()
    return fig
