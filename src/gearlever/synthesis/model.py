"""The synthesized linkages as model dicts.

The builders of the synthesized linkages: :func:`fourbar_model`,
:func:`slider_crank_model`, :func:`geared_fivebar_model`,
:func:`stephenson_sixbar_model`.  The model file's writer is
:mod:`gearlever.mechanism.modelfile` (:func:`~gearlever.mechanism.modelfile.model_toml`,
:func:`~gearlever.mechanism.modelfile.mechanism_table`,
:func:`~gearlever.mechanism.modelfile.xy_pair`).

The point and link names follow one convention for every synthesized
four-bar: ``O2`` input (crank) pivot, ``O4`` output (rocker) ground pivot,
``A`` crank pin, ``B`` rocker pin, ``P`` traced point; links ``ground``,
``crank``, ``coupler``, ``rocker``; the crank is the input.  The schema is
that of :mod:`gearlever.mechanism.model`.

Imports only :mod:`gearlever.errors` and :mod:`gearlever.mechanism.modelfile`.
"""

from __future__ import annotations

import math

from gearlever.errors import GearleverError
from gearlever.mechanism.modelfile import mechanism_table, xy_pair

__all__ = [
    "fourbar_model",
    "geared_fivebar_model",
    "slider_crank_model",
    "stephenson_sixbar_model",
]


def fourbar_model(O2, O4, A, B, P=None, *, name: str = "synthesized four-bar", units: str = "") -> dict:
    """Model dict of a four-bar with the crank as input, in the pose given.

    Parameters
    ----------
    O2, O4, A, B : pair of float
        Crank pivot, rocker pivot, crank pin, rocker pin (sketch positions).
    P : pair of float, optional
        Coupler point (traced point).
    name, units : str
        ``[mechanism]`` name and length unit label.

    Returns
    -------
    dict
        Accepted by :func:`gearlever.mechanism.model_from_dict`.

    Examples
    --------
    >>> from gearlever.mechanism import model_from_dict
    >>> m = model_from_dict(fourbar_model((0, 0), (4, 0), (1, 0), (4.5, 2.8), (3, 4.5)))
    >>> m.moving
    ('crank', 'coupler', 'rocker')
    """
    pts = {"O2": xy_pair("O2", O2), "O4": xy_pair("O4", O4), "A": xy_pair("A", A), "B": xy_pair("B", B)}
    coupler = ["A", "B"]
    if P is not None:
        pts["P"] = xy_pair("P", P)
        coupler.append("P")
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": coupler, "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }


def slider_crank_model(
    O2, A, B, direction=(1.0, 0.0), *, name: str = "synthesized slider-crank", units: str = ""
) -> dict:
    """Model dict of a slider-crank with the crank as input, in the pose given.

    Point names: ``O2`` crank pivot, ``A`` crank pin, ``B`` slider pin (wrist
    pin); links ``ground``, ``crank``, ``rod``, ``slider``; the slider moves
    on the ground along ``direction`` through B.

    Parameters
    ----------
    O2, A, B : pair of float
        Sketch positions.
    direction : pair of float
        Direction of the slider line (not zero).
    name, units : str
        ``[mechanism]`` name and length unit label.

    Returns
    -------
    dict
        Accepted by :func:`gearlever.mechanism.model_from_dict`.

    Examples
    --------
    >>> from gearlever.mechanism import model_from_dict
    >>> m = model_from_dict(slider_crank_model((0, 0), (10, 0), (44.641016151378, 5.0)))
    >>> m.moving
    ('crank', 'rod', 'slider')
    """
    u = xy_pair("direction", direction)
    if math.hypot(*u) == 0.0:
        raise GearleverError("direction must not be zero")
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": {"O2": xy_pair("O2", O2), "A": xy_pair("A", A), "B": xy_pair("B", B)},
        "links": {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "slider": ["B"]},
        "sliders": [{"link": "slider", "on": "ground", "point": "B", "direction": u}],
        "inputs": [{"link": "crank"}],
    }


def geared_fivebar_model(
    O2, O4, A, B, C, P, teeth, *, name: str = "synthesized geared five-bar", units: str = ""
) -> dict:
    """Model dict of a geared five-bar: two cranks on O2 and O4 coupled by an external gear pair.

    Points ``O2`` input pivot, ``O4`` second crank pivot, ``A`` crank pin,
    ``B`` second crank pin, ``C`` joint of the two couplers, ``P`` traced
    point on the coupler A-C; links ``ground``, ``crank``, ``crank2``,
    ``coupler`` (A, C, P), ``link5`` (B, C); gears ``g1`` on the crank and
    ``g2`` on crank2 with ``teeth = (z1, z2)``, one mesh (the ground carries
    both centres; no module, so the pitch radii follow from the centre
    distance); the crank is the input.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> d = geared_fivebar_model((0, 0), (5, 0), (1, 0), (5, 1.5), (3, 4), (2, 3), (20, 40))
    >>> Mechanism.from_dict(d).structure().dof
    1
    """
    z = [int(t) for t in teeth]
    if len(z) != 2 or min(z) < 1 or any(int(t) != t for t in teeth):
        raise GearleverError(f"teeth must be two positive integers (z1, z2), got {teeth!r}")
    pts = {
        "O2": xy_pair("O2", O2),
        "O4": xy_pair("O4", O4),
        "A": xy_pair("A", A),
        "B": xy_pair("B", B),
        "C": xy_pair("C", C),
        "P": xy_pair("P", P),
    }
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "crank2": ["O4", "B"],
            "coupler": ["A", "C", "P"],
            "link5": ["B", "C"],
        },
        "gears": {
            "g1": {"link": "crank", "centre": "O2", "teeth": z[0]},
            "g2": {"link": "crank2", "centre": "O4", "teeth": z[1]},
        },
        "meshes": [{"gears": ["g1", "g2"]}],
        "inputs": [{"link": "crank"}],
    }


def stephenson_sixbar_model(
    O2, O4, O6, A, B, C, D, P, *, name: str = "synthesized Stephenson six-bar", units: str = ""
) -> dict:
    """Model dict of a Stephenson III six-bar: a four-bar whose coupler point C drives a dyad C-D-O6.

    Points ``O2, O4, O6`` ground pivots, ``A`` crank pin, ``B`` rocker pin,
    ``C`` on the coupler, ``D`` the dyad's joint, ``P`` traced point on
    ``C-D``; links ``ground`` (O2, O4, O6), ``crank``, ``coupler`` (A, B, C),
    ``rocker``, ``link5`` (C, D, P), ``output`` (O6, D); the crank is the input.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> d = stephenson_sixbar_model((0, 0), (4, 0), (6, 3), (1, 0), (4.5, 2.8), (2, 3), (5, 5), (3, 5))
    >>> Mechanism.from_dict(d).structure().dof
    1
    """
    names = ("O2", "O4", "O6", "A", "B", "C", "D", "P")
    pts = {n: xy_pair(n, v) for n, v in zip(names, (O2, O4, O6, A, B, C, D, P))}
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {
            "ground": ["O2", "O4", "O6"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "C"],
            "rocker": ["O4", "B"],
            "link5": ["C", "D", "P"],
            "output": ["O6", "D"],
        },
        "inputs": [{"link": "crank"}],
    }
