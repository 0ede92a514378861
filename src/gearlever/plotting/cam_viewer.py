"""An interactive page that shows a disc cam turning with its follower: one self-contained HTML file.

:func:`cam_viewer_html` takes a :class:`~gearlever.cams.CamDesign` and writes
one HTML page (inline SVG, JavaScript and JSON; no network, no other file)
with the controls of the mechanism viewer (:mod:`gearlever.plotting.viewer`):
play, frame slider, dragging the cam about its centre, and a plot of the
follower's output and the pressure angle against the cam angle.  Everything
drawn is computed here with numpy, batched over the frames; the page only
rotates the profile and places the follower.  The data block is escaped and
capped as the mechanism viewer's.  No matplotlib here.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._format import page_numbers
from gearlever.errors import GearleverError
from gearlever.plotting.viewer import MAX_PAGE_BYTES, MAX_VIEW_FRAMES, _page, _script_json

__all__ = ["cam_viewer_html", "cam_viewer_data", "MAX_PROFILE_VERTICES", "CAM_DIGITS"]

#: Most vertices of the profile polygon drawn (besides the contact point of every frame, always a vertex).
MAX_PROFILE_VERTICES = 7200
#: Significant digits of the numbers stored in a cam page (the contact is checked to 1e-6 of the stroke).
CAM_DIGITS = 10


def _rot(x: np.ndarray, ang: np.ndarray) -> np.ndarray:
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([c * x[:, 0] - s * x[:, 1], s * x[:, 0] + c * x[:, 1]], axis=-1)


def cam_viewer_data(design, frames: int = 360, name: str | None = None) -> dict:
    """The data of the cam page: the profile in the cam's frame and, per frame, the follower's pose.

    Parameters are those of :func:`cam_viewer_html`.

    Returns
    -------
    dict
        Strict-JSON-ready: ``profile`` (``x``, ``y`` of the cam surface in the
        cam's frame, the contact of every frame among its vertices),
        ``pitch`` (roller followers), ``theta`` (cam angle of each frame, rad),
        and per frame in ``F``: ``s`` (the output: length, or deg for an
        oscillating follower), ``v``, ``a`` (per rad of cam angle), ``phi``
        (pressure angle, deg), ``cx``, ``cy`` (contact, fixed frame),
        ``rx``, ``ry`` (roller centre), ``arm`` (``x0, y0, x1, y1``: the stem
        of a translating follower from its tip, or the arm from the pivot),
        ``face`` (``x0, y0, x1, y1`` of a flat face).

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> from gearlever.cams import design_cam
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> cam = design_cam(law, "translating-roller", base_radius=30, roller_radius=5, points=720)
    >>> d = cam_viewer_data(cam, frames=4)
    >>> d["F"]["s"], d["F"]["ry"]
    ([0, 5.0, 10.0, 5.0], [35.0, 40.0, 45.0, 40.0])
    """
    from gearlever.cams import FOLLOWERS

    if isinstance(frames, bool) or not isinstance(frames, int | np.integer) or not 2 <= frames <= MAX_VIEW_FRAMES:
        raise GearleverError(f"frames must be an integer from 2 to {MAX_VIEW_FRAMES}, got {frames!r}")
    frames = int(frames)
    P = int(design.theta.size)
    if P % frames:
        raise GearleverError(
            f"frames: {frames} frames do not divide the design's {P} points (design it at a multiple of {frames})"
        )
    kind = FOLLOWERS[design.follower]
    idx = np.arange(frames) * (P // frames)
    theta = design.theta[idx]
    s = design.s[idx]
    rb = design.base_radius
    angle = kind.law_output == "angle"
    scale = 180 / math.pi if angle else 1.0
    contact = design.contact[idx]
    roller = kind.contact == "roller"
    R = float(np.max(np.hypot(design.surface[:, 0], design.surface[:, 1])))
    L = R
    F = {
        "s": page_numbers(s * scale, CAM_DIGITS),
        "v": page_numbers(design.v[idx] * scale, CAM_DIGITS),
        "a": page_numbers(design.a[idx] * scale, CAM_DIGITS),
        "phi": page_numbers(np.degrees(design.pressure_angle[idx]), CAM_DIGITS),
        "cx": page_numbers(contact[:, 0], CAM_DIGITS, L),
        "cy": page_numbers(contact[:, 1], CAM_DIGITS, L),
    }
    oscillating = math.isfinite(design.pivot_distance)
    pivot = np.array([design.pivot_distance, 0.0]) if oscillating else None
    pts = [contact, np.zeros((1, 2))]
    guide = None
    if roller:
        centre = _rot(design.pitch[idx], theta)
        F["rx"], F["ry"] = page_numbers(centre[:, 0], CAM_DIGITS, L), page_numbers(centre[:, 1], CAM_DIGITS, L)
        pts += [centre - design.roller_radius, centre + design.roller_radius]
        tip = centre
    else:
        from gearlever.cams.followers import FollowerParams

        p = FollowerParams(
            0.0,
            0.0 if math.isnan(design.offset) else design.offset,
            None,
            None if not oscillating else design.pivot_distance,
        )
        beta, _, _, h, _, _ = kind.face(s, p, rb)
        beta = np.broadcast_to(beta, s.shape)
        nf = np.stack([np.cos(beta), np.sin(beta)], axis=-1)
        u = np.stack([-nf[:, 1], nf[:, 0]], axis=-1)  # along the face, as face_position measures
        margin = 0.1 * max(design.face_width, 0.1 * rb)
        if oscillating:
            foot = pivot + (h - nf @ pivot)[:, None] * nf
            t0 = min(0.0, design.face_contact_min) - margin
            t1 = max(0.0, design.face_contact_max) + margin
            tip = foot
        else:
            foot = np.stack([np.full_like(h, p.offset), h], axis=-1)
            u = np.broadcast_to(np.array([1.0, 0.0]), foot.shape)
            t0, t1 = design.face_contact_min - margin, design.face_contact_max + margin
            tip = foot
        e0, e1 = foot + t0 * u, foot + t1 * u
        F["face"] = [
            page_numbers(e0[:, 0], CAM_DIGITS, L),
            page_numbers(e0[:, 1], CAM_DIGITS, L),
            page_numbers(e1[:, 0], CAM_DIGITS, L),
            page_numbers(e1[:, 1], CAM_DIGITS, L),
        ]
        pts += [e0, e1]
    if oscillating:
        a0 = np.broadcast_to(pivot, tip.shape)
        a1 = tip
        pts.append(pivot[None, :])
    else:
        stem = float(np.ptp(s)) + 0.5 * rb
        a0 = tip
        a1 = tip + np.array([0.0, stem])
        x = float(tip[0, 0])
        w = 0.09 * rb
        y0 = float(np.max(tip[:, 1])) + 0.1 * rb
        guide = {"x": x, "w": w, "y0": y0, "y1": y0 + 0.35 * rb}
        pts.append(a1)
    F["arm"] = [
        page_numbers(a0[:, 0], CAM_DIGITS, L),
        page_numbers(a0[:, 1], CAM_DIGITS, L),
        page_numbers(a1[:, 0], CAM_DIGITS, L),
        page_numbers(a1[:, 1], CAM_DIGITS, L),
    ]
    xy = np.concatenate(pts)
    lo = np.minimum(xy.min(axis=0), -R)
    hi = np.maximum(xy.max(axis=0), R)
    pad = 0.08 * float(np.max(hi - lo))
    bbox = [float(lo[0] - pad), float(lo[1] - pad), float(hi[0] + pad), float(hi[1] + pad)]

    stride = max(1, math.ceil(P / MAX_PROFILE_VERTICES))
    keep = np.union1d(np.arange(0, P, stride), idx)
    nan = lambda v: None if isinstance(v, float) and math.isnan(v) else v  # noqa: E731
    return {
        "kind": "cam",
        "name": name if name is not None else f"{design.follower} cam",
        "units": design.units,
        "follower": design.follower,
        "contact": kind.contact,
        "motion": "oscillating" if oscillating else "translating",
        "output": kind.law_output,
        "out_units": "deg" if angle else design.units,
        "N": frames,
        "L": L,
        "bbox": bbox,
        "base_radius": rb,
        "roller_radius": nan(design.roller_radius),
        "offset": nan(design.offset),
        "arm": nan(design.arm),
        "pivot_distance": nan(design.pivot_distance),
        "stroke": design.stroke * scale,
        "pressure_angle_max": math.degrees(design.pressure_angle_max),
        "undercut": bool(design.undercut),
        "pivot": None if pivot is None else [float(pivot[0]), 0.0],
        "guide": guide,
        "theta": page_numbers(theta, CAM_DIGITS),
        "index": [int(i) for i in idx],
        "profile": {
            "x": page_numbers(design.surface[keep, 0], CAM_DIGITS, L),
            "y": page_numbers(design.surface[keep, 1], CAM_DIGITS, L),
        },
        "pitch": {
            "x": page_numbers(design.pitch[keep, 0], CAM_DIGITS, L),
            "y": page_numbers(design.pitch[keep, 1], CAM_DIGITS, L),
        }
        if roller
        else None,
        "F": F,
    }


def cam_viewer_html(design, frames: int = 360, name: str | None = None) -> str:
    """One self-contained HTML page (inline SVG, JavaScript and JSON) of ``design`` turning with its follower.

    Parameters
    ----------
    design : gearlever.cams.CamDesign
        The cam (:func:`~gearlever.cams.design_cam` or :func:`~gearlever.cams.load_cam`).
    frames : int
        Frames over one counterclockwise turn of the cam (2 to
        :data:`~gearlever.plotting.viewer.MAX_VIEW_FRAMES`); they must divide
        the design's points, frame ``k`` being its sample ``k points / frames``
        (so the contact of every frame is a vertex of the profile drawn).
    name : str, optional
        Title of the page (default: the follower kind).

    Returns
    -------
    str
        The page.

    Notes
    -----
    What a test can read in the page: the cam is the group ``data-cam``
    whose ``transform`` is ``rotate(DEG)`` (the cam angle of the frame; the
    y flip is a transform of a parent group, so positive is
    counterclockwise) holding the profile polygon ``data-profile`` in the
    cam's frame; the roller ``data-roller`` (``cx``, ``cy``, ``r``), the
    contact ``data-contact``, the stem or arm ``data-arm`` and the face
    ``data-face`` (lines ``x1 .. y2``) in the fixed frame.  ``id="readout"``
    holds ``θ = ...°``, the output and the pressure angle; controls
    ``play``, ``step``, ``step-back``, ``frame``, ``speed``, ``quantity``
    (the plot); ``?frame=k`` (and ``&play=1``) in the URL; dragging the cam
    turns it by the pointer's turn about the cam centre.  The data block is
    :func:`gearlever.plotting.viewer._script_json` (``<``, ``>``, ``&``,
    U+2028/9 escaped), the page at most
    :data:`~gearlever.plotting.viewer.MAX_PAGE_BYTES`; names enter the
    document as text.  Numbers carry :data:`CAM_DIGITS` significant digits.

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> from gearlever.cams import design_cam
    >>> law = law_from_segments("angle", "deg", [{"to": 180, "motion": "cycloidal", "rise": 20},
    ...                                           {"to": 360, "motion": "cycloidal", "rise": -20}])
    >>> cam = design_cam(law, "oscillating-roller", base_radius=30, roller_radius=5, arm=40,
    ...                  pivot_distance=50, points=720)
    >>> page = cam_viewer_html(cam, frames=72)
    >>> page.startswith("<!DOCTYPE html>"), "data-cam" in page
    (True, True)
    """
    data = cam_viewer_data(design, frames, name)
    payload = _script_json(data)
    if len(payload) > MAX_PAGE_BYTES:
        raise GearleverError(
            f"frames: the page of {frames} frames would be {len(payload) / 1e6:.3g} MB, more than the cap of "
            f"{MAX_PAGE_BYTES / 1e6:g} MB"
        )
    return _page("cam", data["name"], payload)
