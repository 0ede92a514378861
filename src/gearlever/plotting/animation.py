"""The four-bar of ``gearlever animate --fourbar``, animated by the one mechanism animation.

:func:`fourbar_mechanism` builds the four-bar from its link lengths as a
mechanism model (the names of :func:`gearlever.synthesis.model.fourbar_model`:
``O2``, ``A``, ``B``, ``O4``; links ``crank``, ``coupler``, ``rocker``) in the
first crank position where it closes on the branch asked for;
:func:`animate_fourbar` sweeps the crank over one turn from there and writes
the GIF with :func:`gearlever.plotting.mechanism.animate_mechanism`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearlever._validate import positive_int
from gearlever.errors import GearleverError
from gearlever.plotting._limits import ANIMATION_DPI, ANIMATION_SIZE

__all__ = ["fourbar_mechanism", "animate_fourbar"]

#: Crank angles of the dotted point paths (one a degree).
_PATH_POINTS = 360
#: Crank angles tried for the starting pose (one a degree).
_START_ANGLES = 360


def fourbar_mechanism(ground, crank, coupler, rocker, branch="open", units: str = ""):
    """The four-bar as a :class:`~gearlever.mechanism.Mechanism`, ground along x, crank as input.

    The sketch is the first crank angle (0, 1, 2, ... degrees) where the
    linkage closes on ``branch``.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths.
    branch : {"open", "crossed"}
        Assembly branch of the sketch (the sweep follows it).
    units : str
        Length unit label of the model.

    Returns
    -------
    gearlever.mechanism.Mechanism

    Notes
    -----
    The rocker pin is ``B = A + coupler e^{i theta3}`` with the coupler angle
    of the triangle A-B-O4 on the diagonal O4 - A (R. L. Norton, *Design of
    Machinery*, McGraw-Hill, sec. 4.5, the position analysis of the four-bar),
    computed by :func:`gearlever.loops.fourbar`.

    Examples
    --------
    >>> m = fourbar_mechanism(9, 5, 8, 8)
    >>> m.model.moving, m.model.points["O4"]
    (('crank', 'coupler', 'rocker'), (9.0, 0.0))
    """
    from gearlever.loops import fourbar, grashof
    from gearlever.mechanism import Mechanism
    from gearlever.synthesis.model import fourbar_model

    kind = grashof(ground, crank, coupler, rocker).kind
    th = np.linspace(0.0, 2 * np.pi, _START_ANGLES, endpoint=False)
    r = fourbar(ground, crank, coupler, rocker, th, branch=branch)
    ok = np.flatnonzero(r.valid)
    if ok.size == 0:
        raise GearleverError(
            f"the four-bar {ground:g}/{crank:g}/{coupler:g}/{rocker:g} does not close at any crank angle"
        )
    i = int(ok[0])
    a = crank * np.exp(1j * th[i])
    b = a + coupler * np.exp(1j * r.theta3[i])
    name = f"four-bar {ground:g}/{crank:g}/{coupler:g}/{rocker:g} ({kind}, {branch})"
    d = fourbar_model((0.0, 0.0), (ground, 0.0), (a.real, a.imag), (b.real, b.imag), name=name, units=units)
    return Mechanism.from_dict(d)


def animate_fourbar(
    ground,
    crank,
    coupler,
    rocker,
    path,
    frames=36,
    branch="open",
    fps=12,
    dpi=ANIMATION_DPI,
    figsize=ANIMATION_SIZE,
) -> Path:
    """Write a GIF of the four-bar over one crank turn to ``path`` (atomically); return the path.

    The four-bar of :func:`fourbar_mechanism`, swept over ``frames`` crank
    angles of one turn, drawn by
    :func:`~gearlever.plotting.mechanism.animate_mechanism` (the one animation
    of every mechanism model).  Frames where the linkage cannot close show the
    ground only.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = animate_fourbar(9, 5, 8, 8, Path(d) / "fb.gif", frames=2, figsize=(4, 3), dpi=40)
    ...     p.name
    'fb.gif'
    """
    from gearlever.plotting.mechanism import animate_mechanism

    frames = positive_int("frames", frames)
    mech = fourbar_mechanism(ground, crank, coupler, rocker, branch)
    q0 = mech.sketch_inputs[0]
    result = mech.solve(q0 + np.linspace(0.0, 2 * np.pi, frames, endpoint=False)[:, None])
    paths = mech.solve(q0 + np.linspace(0.0, 2 * np.pi, _PATH_POINTS, endpoint=False)[:, None])
    return animate_mechanism(mech, result, path, fps=fps, dpi=dpi, figsize=figsize, paths=paths)
