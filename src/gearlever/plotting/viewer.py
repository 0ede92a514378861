"""An interactive page that shows any mechanism model move: one self-contained HTML file.

:func:`viewer_html` solves the model over one turn of its first input (and,
for two or more inputs, over a grid of values of the second), and writes one
HTML page with inline SVG, JavaScript and JSON: no network, no other file.
The page draws the links, joints, sliders and guides, gears and ground, and
animates them; see :func:`viewer_html` for what it shows and for the
attributes a test can read.

The page template (HTML, CSS, JavaScript) is package data in
``gearlever/plotting/viewer_page/``.  No matplotlib here.
"""

from __future__ import annotations

import json
import math
import re
from importlib import resources

import numpy as np

from gearlever._format import page_numbers
from gearlever._io import _strict
from gearlever.errors import GearleverError

__all__ = [
    "viewer_html",
    "viewer_data",
    "page_estimate",
    "MAX_VIEW_FRAMES",
    "MAX_VIEW_LINKS",
    "MAX_VIEW_WORK",
    "MAX_PAGE_BYTES",
    "MAX_CENTRE_BODIES",
    "MAX_START_TURNS",
    "GRID_STEPS",
    "SIGNIFICANT_DIGITS",
]

#: Largest number of frames of a page (about 0.7 kB per frame for a six-bar: a 2.5 MB page at the cap).
MAX_VIEW_FRAMES = 3600
#: Largest number of moving links of a model shown (the solve grows faster than the number of links).
MAX_VIEW_LINKS = 150
#: Largest work of a page: frames x values of the second input x moving links ("link-frames").
MAX_VIEW_WORK = 250_000
#: Largest page (bytes): refused before solving from an estimate of the numbers it holds, and checked after.
MAX_PAGE_BYTES = 20_000_000
#: Instant centres and Kennedy lines are drawn for models of at most this many bodies (ground included):
#: n bodies have n (n - 1) / 2 centres and n (n - 1) (n - 2) / 6 Kennedy triples.
MAX_CENTRE_BODIES = 16
#: Largest distance of the start of a rotary input from its sketch value (turns); for a slider input,
#: times the model's length scale.  The solver walks from the sketch to the start in small steps.
MAX_START_TURNS = 1000
#: Estimated bytes of one stored number in the page (6 significant digits, sign, point, comma).
_BYTES_PER_VALUE = 10
#: Values of the second input offered by the page's extra slider (models with two or more inputs).
GRID_STEPS = 24
#: Significant digits of the coordinates stored in the page.
SIGNIFICANT_DIGITS = 6


def _round(a, scale=None):
    """Values at :data:`SIGNIFICANT_DIGITS` digits (:func:`gearlever._format.page_numbers`); one if all equal.

    Values below ``1e-12 scale`` (default: the array's largest) are rounding noise: written as 0.
    """
    a = np.asarray(a, dtype=float).ravel()
    fin = np.isfinite(a)
    ref = (np.max(np.abs(a[fin])) if scale is None else scale) if fin.any() else None
    out = page_numbers(a, SIGNIFICANT_DIGITS, ref, integers=True)
    if out and all(v == out[0] for v in out):
        return out[0]
    return out


def _slices(a, M: int, scale=None) -> list:
    """``M`` slices of a flat array (grid index major), each a list of frames or one value when constant."""
    return [_round(part, scale) for part in np.split(np.asarray(a, dtype=float), M)]


def _frames_inputs(mech, frames: int, inputs) -> tuple:
    """Start values of the inputs (rad or length) and the grid of the second input."""
    m = mech.model
    labels = [s.label for s in m.inputs]
    start = mech.sketch_inputs.astype(float)
    for name, value in (inputs or {}).items():
        if name not in labels:
            raise GearleverError(f"inputs: unknown input {name!r} (inputs: {', '.join(labels)})")
        v = float(value)
        if not math.isfinite(v):
            raise GearleverError(f"inputs: {name} must be a finite number, got {value!r}")
        i = labels.index(name)
        if m.inputs[i].kind == "link":
            turns = abs(v - start[i]) / (2 * math.pi)
            if not turns <= MAX_START_TURNS:
                raise GearleverError(
                    f"inputs: {name} is {turns:.3g} turns from its sketch value, "
                    f"more than the cap of {MAX_START_TURNS} turns"
                )
        else:
            span = abs(v - start[i]) / m.length_scale
            if not span <= MAX_START_TURNS:
                raise GearleverError(
                    f"inputs: {name} is {span:.3g} times the model's size from its sketch value, "
                    f"more than the cap of {MAX_START_TURNS}"
                )
        start[i] = v
    if m.inputs[0].kind != "link":
        raise GearleverError(
            f"inputs: the viewer turns the first input a full turn; {labels[0]!r} is a slider "
            "(put a rotary input first)"
        )
    if len(m.inputs) == 1:
        return start, None, 0
    spec = m.inputs[1]
    j = np.arange(GRID_STEPS)
    if spec.kind == "link":
        values, default = start[1] + 2 * np.pi * j / GRID_STEPS, 0
    else:
        half = GRID_STEPS // 2
        values, default = start[1] + 0.5 * m.length_scale * (j - half) / half, half
    return start, values, default


def _first_input_rows(mech, start, frames: int, branch: str = "continue"):
    """Values of the first input over the frames, their directions and its limits (None when it turns fully).

    A first input that turns fully turns one turn from ``start`` (end
    excluded); one that rocks (:func:`~gearlever.mechanism.limits.input_limits`,
    the others held at ``start``) sweeps one oscillation
    (:func:`~gearlever.mechanism.sweep.oscillation`): up to its upper limit,
    down to its lower one, back to ``start``.
    """
    from gearlever.mechanism.limits import input_limits
    from gearlever.mechanism.sweep import oscillation

    lim = input_limits(mech, 0, start=start, branch=branch)
    if lim.full_turn:
        return start[0] + 2 * np.pi * np.arange(frames) / frames, np.ones(frames, dtype=int), None
    if lim.locked:
        links = ", ".join(dict.fromkeys(lim.binding_lower + lim.binding_upper))
        raise GearleverError(f"inputs: {lim.input} cannot move from its start: it is locked by the links {links}")
    v, d = oscillation(lim.start, lim.lower, lim.upper, frames)
    return v, d, lim


def page_estimate(model, frames: int) -> dict:
    """The work and the estimated size of a page, before anything is solved.

    Parameters
    ----------
    model : gearlever.mechanism.model.MechanismModel
    frames : int
        Frames over one turn of the first input.

    Returns
    -------
    dict
        ``links`` (moving links), ``grid`` (values of the second input, 1 for
        one input), ``work`` (``frames x grid x links``, link-frames, capped
        by :data:`MAX_VIEW_WORK`), ``bytes`` (estimated data block, capped by
        :data:`MAX_PAGE_BYTES`), ``bytes_per_frame`` and ``centres`` (whether
        the page holds instant centres, :data:`MAX_CENTRE_BODIES`).

    Notes
    -----
    The size counts the numbers the page stores per frame and value of the
    second input: 6 per moving point (position, velocity, acceleration), 3
    per moving link (angle, angular velocity and acceleration) and per
    slider, 2 per instant centre, 1 assembly flag; at 10 bytes each (6
    significant digits, sign, point, exponent, comma) an upper bound of the
    data block (a constant array is stored once, so real pages are smaller).

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> est = page_estimate(m, 360)
    >>> est["work"], est["bytes"], est["centres"]
    (360, 43200, True)
    """
    from gearlever.mechanism.model import GROUND

    K = len(model.moving)
    M = GRID_STEPS if len(model.inputs) > 1 else 1
    bodies = K + 1
    centres = M == 1 and bodies <= MAX_CENTRE_BODIES
    moving_points = len(set(model.points) - set(model.links[GROUND].points))
    per_frame = 6 * moving_points + 3 * K + 3 * len(model.sliders) + (bodies * (bodies - 1) if centres else 0) + 1
    return {
        "links": K,
        "grid": M,
        "work": frames * M * K,
        "bytes": _BYTES_PER_VALUE * per_frame * frames * M,
        "bytes_per_frame": _BYTES_PER_VALUE * per_frame * M,
        "centres": centres,
    }


def _check_size(m, frames: int) -> bool:
    """Refuse a page over the caps before anything is solved; True if it shows instant centres."""
    est = page_estimate(m, frames)
    K, M = est["links"], est["grid"]
    if K > MAX_VIEW_LINKS:
        raise GearleverError(f"mech: [links] has {K} moving links, more than the viewer's cap of {MAX_VIEW_LINKS}")
    grid = f" x {M} values of {m.inputs[1].label}" if M > 1 else ""
    if est["work"] > MAX_VIEW_WORK:
        raise GearleverError(
            f"frames: {frames} frames{grid} x {K} moving links is {est['work']} link-frames, more than the cap of "
            f"{MAX_VIEW_WORK}; use at most {MAX_VIEW_WORK // (M * K)} frames"
        )
    if est["bytes"] > MAX_PAGE_BYTES:
        raise GearleverError(
            f"frames: a page of {frames} frames{grid} would be about {est['bytes'] / 1e6:.3g} MB, more than the "
            f"cap of {MAX_PAGE_BYTES / 1e6:g} MB; use at most {MAX_PAGE_BYTES // est['bytes_per_frame']} frames"
        )
    return est["centres"]


def _rates(mech, rpm) -> tuple:
    """Input rates (rad/s or length/s) and the period of one turn (s), or analogues (per rad) and None."""
    m = mech.model
    W = len(m.inputs)
    labels = [s.label for s in m.inputs]
    if rpm is None:
        rates = np.zeros(W)
        rates[0] = 1.0
        return rates, None
    if not isinstance(rpm, dict):
        if W != 1:
            raise GearleverError(f"rpm: give one value per input as a dict {{name: rpm}} ({', '.join(labels)})")
        rpm = {labels[0]: rpm}
    rates = np.zeros(W)
    for name, value in rpm.items():
        if name not in labels:
            raise GearleverError(f"rpm: unknown input {name!r} (inputs: {', '.join(labels)})")
        v = float(value)
        if not math.isfinite(v):
            raise GearleverError(f"rpm: {name} must be a finite number, got {value!r}")
        i = labels.index(name)
        rates[i] = v * math.pi / 30.0 if m.inputs[i].kind == "link" else v / 60.0
    if labels[0] not in rpm or rates[0] == 0:
        raise GearleverError(f"rpm: the first input {labels[0]!r} needs a non-zero speed (it sets the time)")
    return rates, 2 * math.pi / abs(rates[0])


def viewer_data(mech, frames: int = 360, rpm=None, inputs=None, branch: str = "continue") -> dict:
    """The data of the page: model geometry and, per frame, every position, rate and instant centre.

    Parameters are those of :func:`viewer_html`.  Arrays are flat lists over
    ``grid index * frames + frame`` with :data:`SIGNIFICANT_DIGITS` digits,
    ``None`` where the model does not assemble (a constant array is stored
    as one value).

    Returns
    -------
    dict
        Strict-JSON-ready (see :func:`viewer_html`).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> d = viewer_data(m, frames=4)
    >>> d["S"]["x"]["A"], d["S"]["y"]["A"]
    ([[1, 0, -1, 0]], [[0, 1, 0, -1]])
    """
    from gearlever.mechanism.model import GROUND

    if isinstance(frames, bool) or not isinstance(frames, (int, np.integer)) or not 2 <= frames <= MAX_VIEW_FRAMES:
        raise GearleverError(f"frames must be an integer from 2 to {MAX_VIEW_FRAMES}, got {frames!r}")
    frames = int(frames)
    m = mech.model
    W = len(m.inputs)
    with_centres = _check_size(m, frames)
    start, grid, grid_default = _frames_inputs(mech, frames, inputs)
    rates, period = _rates(mech, rpm)
    turn, direction, lim = _first_input_rows(mech, start, frames, branch)
    frame_rates = np.tile(rates, (frames, 1))
    if lim is not None:  # one oscillation: the speed signed by the motion, the period that of the oscillation
        frame_rates[:, 0] = abs(rates[0]) * direction
        if period is not None:
            period = 2.0 * (lim.upper - lim.lower) / abs(rates[0])
    slices = [start.copy()] if grid is None else []
    if grid is not None:
        for v in grid:
            s = start.copy()
            s[1] = v
            slices.append(s)
    results = []
    for s in slices:
        q = np.tile(s, (frames, 1))
        q[:, 0] = turn
        results.append(mech.solve(q, frame_rates, branch=branch))

    points = [p for p in results[0].point]
    L = m.length_scale
    closed = np.concatenate([r.closed for r in results])
    bbox, gears = _extent(m, results, points)
    vmax, amax = _longest(results, points, "velocity"), _longest(results, points, "acceleration")
    ground_pts = set(m.links[GROUND].points)
    joints = sorted({p for p, _, _ in m.joints}, key=list(m.points).index)
    units = m.units or "len"
    spec0 = m.inputs
    data = {
        "name": m.name,
        "units": units,
        "N": frames,
        "M": len(slices),
        "L": L,
        "bbox": bbox,
        "inputs": [
            {
                "label": s.label,
                "kind": s.kind,
                "link": s.name if s.kind == "link" else None,
                "relative_to": s.relative_to,
                "start": float(start[i]),
                "rate": float(rates[i]),
            }
            for i, s in enumerate(spec0)
        ],
        "grid": None
        if grid is None
        else {"input": 1, "values": [float(v) for v in grid], "default": int(grid_default)},
        "period": period,
        "rated": rpm is not None,
        "points": points,
        "ground_points": [p for p in points if p in ground_pts],
        "joints": joints,
        "links": [{"name": k, "points": list(m.links[k].points), "angle0": m.links[k].angle0} for k in m.moving],
        "sliders": _slider_tracks(m, results),
        "gears": gears,
        "closed": "".join("1" if c else "0" for c in closed),
        "S": _series(mech, results, points),
        "vscale": 0.5 * L / vmax if vmax > 0 else 0.0,
        "ascale": 0.5 * L / amax if amax > 0 else 0.0,
        "ic": None,
    }
    if lim is not None:  # only then: the pages of inputs that turn fully stay as they were
        data["osc"] = {
            "q": [float(v) for v in turn],
            "dir": [int(v) for v in direction],
            "lower": lim.lower,
            "upper": lim.upper,
        }
    data["centres_capped"] = W == 1 and not with_centres
    data["centres_max"] = MAX_CENTRE_BODIES
    if W == 1 and with_centres:
        data["ic"] = _centres(results[0], L)
    return data


def _cat(results, attr: str, key=None) -> np.ndarray:
    """``result.attr[key]`` (or ``result.attr``) of every grid slice, concatenated."""
    parts = [getattr(r, attr) if key is None else getattr(r, attr)[key] for r in results]
    return np.concatenate([np.asarray(a, dtype=float) for a in parts])


def _series(mech, results, points) -> dict:
    """The page's per-frame arrays: point positions, velocities, accelerations; link and slider motions."""
    m = mech.model
    M, L = len(results), m.length_scale
    series = {k: {} for k in ("x", "y", "vx", "vy", "ax", "ay", "phi", "w", "al", "s", "sv", "sa")}
    for p in points:
        P, V, A = _cat(results, "point", p), _cat(results, "velocity", p), _cat(results, "acceleration", p)
        for key, arr, c in (("x", P, 0), ("y", P, 1), ("vx", V, 0), ("vy", V, 1), ("ax", A, 0), ("ay", A, 1)):
            series[key][p] = _slices(arr[:, c], M, L if key in ("x", "y") else None)
    for k in m.moving:
        i = mech.system.idx[k]
        series["phi"][k] = _slices(_cat(results, "x")[:, i], M)
        series["w"][k] = _slices(_cat(results, "omega", k), M)
        series["al"][k] = _slices(_cat(results, "alpha", k), M)
    for sl in m.sliders:
        series["s"][sl.name] = _slices(_cat(results, "displacement", sl.name), M)
        series["sv"][sl.name] = _slices(_cat(results, "slider_velocity", sl.name), M)
        series["sa"][sl.name] = _slices(_cat(results, "slider_acceleration", sl.name), M)
    return series


def _extent(m, results, points) -> tuple:
    """``(bbox, gears)``: the drawing's box over every frame (points and gear rims, padded) and the gears drawn."""
    xy = np.concatenate([_cat(results, "point", p) for p in points])
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    if xy.size == 0:
        xy = np.array(list(m.points.values()), dtype=float)
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    gears = []
    for g in m.gears.values():
        r = m.pitch_radius(g.name)
        gears.append(
            {"name": g.name, "link": g.link, "centre": g.centre, "teeth": g.teeth, "internal": g.internal, "r": r}
        )
        if r is not None:
            c = _cat(results, "point", g.centre)
            c = c[np.all(np.isfinite(c), axis=1)]
            if c.size:
                lo = np.minimum(lo, c.min(axis=0) - r)
                hi = np.maximum(hi, c.max(axis=0) + r)
    pad = 0.12 * m.length_scale
    return [float(lo[0] - pad), float(lo[1] - pad), float(hi[0] + pad), float(hi[1] + pad)], gears


def _slider_tracks(m, results) -> list:
    """Each slider's guide as drawn: its line and the travel it covers over the frames (padded)."""
    L = m.length_scale
    sliders = []
    for sl in m.sliders:
        s = _cat(results, "displacement", sl.name)
        s = s[np.isfinite(s)]
        smin, smax = (float(s.min()), float(s.max())) if s.size else (0.0, 0.0)
        sliders.append(
            {
                "name": sl.name,
                "link": sl.link,
                "on": sl.on,
                "point": sl.point,
                "dir": list(sl.direction),
                "smin": smin - 0.08 * L,
                "smax": smax + 0.08 * L,
            }
        )
    return sliders


def _longest(results, points, attr: str) -> float:
    """The longest ``attr`` vector (velocity or acceleration) of any point in any frame: one arrow scale for all."""
    best = 0.0
    for p in points:
        v = _cat(results, attr, p)
        a = np.hypot(v[:, 0], v[:, 1])
        a = a[np.isfinite(a)]
        if a.size:
            best = max(best, float(a.max()))
    return best


def _centres(result, L: float) -> dict:
    """The instant centres of every frame (one input): positions, and directions of those at infinity."""
    from gearlever.mechanism.centres import instant_centres

    ic = instant_centres(result)
    return {
        "links": list(ic.links),
        "pairs": list(ic.pairs),
        "x": {k: _slices(ic.xy[:, p, 0], 1, L) for p, k in enumerate(ic.pairs)},
        "y": {k: _slices(ic.xy[:, p, 1], 1, L) for p, k in enumerate(ic.pairs)},
        "inf": {
            k: [
                [int(i), round(float(ic.direction[i, p, 0]), 6), round(float(ic.direction[i, p, 1]), 6)]
                for i in np.flatnonzero(np.all(np.isfinite(ic.direction[:, p]), axis=1))
            ]
            for p, k in enumerate(ic.pairs)
            if np.isfinite(ic.direction[:, p]).any()
        },
    }


def _template(name: str) -> str:
    return resources.files("gearlever.plotting").joinpath("viewer_page", name).read_text(encoding="utf-8")


#: The parts of ``viewer_page/`` that every page holds (top: title, readout and the transport controls that
#: ``common.js`` drives; speed: speed and fit; bottom: the data block and the script), at ``<!--__PART__-->``.
_PARTS = ("top", "speed", "bottom")


def _page(page: str, title: str, payload: str) -> str:
    """The page ``viewer_page/<page>.html`` filled in: its parts, then in one pass title, data, CSS, scripts.

    The scripts are ``common.js`` (what every page shares) and ``<page>.js``;
    ``payload`` is the data block (:func:`_script_json`), ``title`` plain text.
    """
    html = _template(f"{page}.html")
    for part in _PARTS:
        html = html.replace(f"<!--__{part.upper()}__-->\n", _template(f"{part}.html"))
    fill = {
        "__DATA__": payload,
        "__TITLE__": _escape(title),
        "/*__CSS__*/": _template("viewer.css"),
        "/*__JS__*/": _template("common.js") + _template(f"{page}.js"),
    }
    # one pass: a name holding a marker is not expanded
    return re.sub("|".join(re.escape(k) for k in fill), lambda mt: fill[mt.group(0)], html)


def viewer_html(mech, frames: int = 360, rpm=None, inputs=None, branch: str = "continue") -> str:
    """One self-contained HTML page (inline SVG, JavaScript and JSON) that animates ``mech``.

    Parameters
    ----------
    mech : gearlever.mechanism.Mechanism
    frames : int
        Frames over one turn of the first input (2 to :data:`MAX_VIEW_FRAMES`).
        Frame ``k`` is at input angle ``start + 2 pi k / frames`` (the end
        excluded), ``start`` the sketch angle unless ``inputs`` gives it.
    rpm : float or dict, optional
        Speed of the inputs (rev/min; length/min for a slider), one value for
        a one-input model or ``{input: rpm}``; the first input must move.
        With it the page shows time, velocities in length/s and
        accelerations in length/s^2 at constant speed; without it the
        velocity and acceleration analogues per radian of the first input
        (the others held).
    inputs : dict, optional
        ``{input: value}`` (rad, or length for a slider): the start of the
        first input and the held value of the others (default: the sketch).
    branch : {"continue", "keep", "stop"}
        The policy at branch points of the motion (:meth:`Mechanism.solve`).

    Returns
    -------
    str
        The page.  For two or more inputs, the page sweeps the first and
        offers :data:`GRID_STEPS` values of the second (a full turn, or
        +-L/2 for a slider, ``L`` the model's length scale); further inputs
        stay at their held values.

    Notes
    -----
    What a test can read in the page: every model point is an SVG circle
    ``data-point="NAME"`` whose ``cx``, ``cy`` are the model coordinates at
    the frame shown (:data:`SIGNIFICANT_DIGITS` digits; the y flip is a
    transform of a parent group), hidden where the model does not assemble;
    every moving link is an element ``data-link="NAME"``; velocity arrows
    ``data-vel``, acceleration arrows ``data-acc``, point paths ``data-path``;
    instant centres (one-input models) circles ``data-ic="A/B"`` (ground
    first, then links in model order) hidden (``display: none``) where the
    two angular velocities are equal (centre at infinity).  ``id="readout"``
    holds ``θ = ...°``; controls ``play``, ``frame``, ``speed``,
    ``show-velocity``, ``show-paths``; ``?frame=k`` (and ``&play=1``) in
    the URL; gears ``data-gear="NAME"`` (ground gears included);
    ``window.gearlever.fmt`` the number formatter and
    ``window.gearlever.cycleCsv()`` the CSV of the whole cycle (empty cells
    where there is no value).  The instant centres are
    :func:`gearlever.mechanism.centres.instant_centres` (models of at most
    :data:`MAX_CENTRE_BODIES` bodies).

    The data block is compact strict JSON with ``<``, ``>``, ``&``, U+2028
    and U+2029 written as ``\\uXXXX`` escapes, so no text of the model can
    end or bend the ``<script>`` element; the page puts names into the
    document as text.  Refused before anything is solved
    (:class:`~gearlever.errors.GearleverError`, naming ``frames``,
    ``inputs`` or ``mech``): more than :data:`MAX_VIEW_LINKS` moving links,
    more than :data:`MAX_VIEW_WORK` link-frames, a page estimated over
    :data:`MAX_PAGE_BYTES` (:func:`page_estimate`; checked again on the
    page built), a start more than :data:`MAX_START_TURNS` turns from the
    sketch.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> page = viewer_html(m, frames=8)
    >>> page.startswith("<!DOCTYPE html>"), 'data-point' in page
    (True, True)
    """
    data = viewer_data(mech, frames, rpm, inputs, branch)
    payload = _script_json(data)
    if len(payload) > MAX_PAGE_BYTES:  # the estimate of _check_size missed: refuse all the same
        most = max(2, int(frames * MAX_PAGE_BYTES / len(payload)))
        raise GearleverError(
            f"frames: the page of {frames} frames would be {len(payload) / 1e6:.3g} MB, more than the cap of "
            f"{MAX_PAGE_BYTES / 1e6:g} MB; use at most {most} frames"
        )
    return _page("viewer", mech.model.name, payload)


#: Characters that may not appear raw in JSON inside a <script> element: "<" would let "</script>" or
#: "<!--" end or bend the element, ">" and "&" are escaped alike, U+2028/U+2029 end a line in older JavaScript.
_SCRIPT_ESCAPES = {"<": "\\u003c", ">": "\\u003e", "&": "\\u0026", "\u2028": "\\u2028", "\u2029": "\\u2029"}


def _script_json(data) -> str:
    """Compact strict JSON, safe between ``<script>`` tags: ``<``, ``>``, ``&``, U+2028/9 as ``\\uXXXX``.

    The characters can only occur inside JSON strings, where the escape
    is the same string.

    >>> _script_json({"name": "</script><!--&"})
    '{"name":"\\\\u003c/script\\\\u003e\\\\u003c!--\\\\u0026"}'
    """
    text = json.dumps(_strict(data), separators=(",", ":"), allow_nan=False)
    return re.sub("[<>&\u2028\u2029]", lambda mt: _SCRIPT_ESCAPES[mt.group(0)], text)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
