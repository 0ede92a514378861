"""CAM.toml, both ways: :func:`cam_toml` writes a design's dimensions, law and report; :func:`load_cam` reads it.

Reading designs the cam again from its dimensions and law.  Imports the
standard library, gearlever._io, gearlever._format, gearlever.laws,
gearlever.errors and gearlever.cams.design.
"""

from __future__ import annotations

from gearlever.cams.design import MAX_POINTS, CamDesign, design_cam
from gearlever.errors import GearleverError, a

__all__ = ["CAM_DIGITS", "cam_centre", "cam_toml", "load_cam"]

#: Keys of the ``[cam]`` table.
CAM_KEYS = (
    "follower",
    "units",
    "base_radius",
    "roller_radius",
    "offset",
    "arm",
    "pivot_distance",
    "points",
    "centre",
)
#: Significant digits of the numbers of a CAM.toml (and of ``gearlever cam design``'s report).
CAM_DIGITS = 12


def _table(name: str, d: dict) -> list[str]:
    from gearlever._format import toml_value

    return [f"[{name}]"] + [f"{k} = {toml_value(v, CAM_DIGITS)}" for k, v in d.items() if v is not None]


def cam_toml(design: CamDesign, law_table: dict, report: dict, comment: str = "", centre=None) -> str:
    """Text of a CAM.toml: ``[cam]`` dimensions, the ``[law]`` (so the file reads as a LAW.toml too), ``[report]``.

    Parameters
    ----------
    design : CamDesign
        The cam (its follower, units, dimensions and number of cam angles).
    law_table : dict
        The law as a TOML table (:meth:`gearlever.laws.MotionLaw.to_dict`),
        ``segment`` written as ``[[law.segment]]``.
    report : dict
        Values of ``[report]``: the numbers, bools and strings of it (finite
        numbers only, at :data:`CAM_DIGITS` digits); lists are left to the
        JSON report.
    comment : str
        Lines written first as ``#`` comments.
    centre : (float, float), optional
        Where the cam's pivot sits in a drawing (``centre = [x, y]``, read
        back by :func:`cam_centre`): the workbench places the cam there.  The
        profile's own coordinates are about the pivot either way.

    Returns
    -------
    str
        TOML text that :func:`load_cam` reads back.

    Examples
    --------
    >>> import tomllib
    >>> from gearlever.cams import design_cam
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...     {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> cam = design_cam(law, "translating-flat", base_radius=30.0, points=720)
    >>> text = cam_toml(cam, law.to_dict(), {"undercut": False}, "a cam")
    >>> d = tomllib.loads(text)
    >>> d["cam"]["base_radius"], d["cam"]["points"], d["report"]["undercut"]
    (30.0, 720, False)
    """
    import math

    from gearlever._format import rounded, toml_value

    if centre is not None:
        _centre({"centre": list(centre)}, "centre")
    cam = {
        "follower": design.follower,
        "units": design.units,
        "base_radius": design.base_radius,
        "roller_radius": design.roller_radius,
        "offset": design.offset,
        "arm": design.arm,
        "pivot_distance": design.pivot_distance,
        "points": int(design.theta.size),
        "centre": None if centre is None else [float(centre[0]), float(centre[1])],
    }
    cam = rounded(cam, CAM_DIGITS)  # NaN (a dimension the follower has not) as None: left out
    lines = [f"# {c}" for c in comment.splitlines()] + [""] + _table("cam", cam) + [""]
    segs = law_table.get("segment")
    lines += _table("law", {k: v for k, v in law_table.items() if k != "segment"})
    for seg in segs or []:
        lines += ["", "[[law.segment]]"] + [f"{k} = {toml_value(v, CAM_DIGITS)}" for k, v in seg.items()]
    rep = {k: v for k, v in report.items() if isinstance(v, bool | int | float | str) and k not in cam}
    rep = {k: v for k, v in rep.items() if not (isinstance(v, float) and not math.isfinite(v))}
    lines += ["", *_table("report", rep)]
    return "\n".join(lines) + "\n"


def load_cam(path, points: int | None = None) -> CamDesign:
    """The :class:`~gearlever.cams.CamDesign` of a CAM.toml, designed again from its ``[cam]`` and ``[law]``.

    Parameters
    ----------
    path : str or Path
        A file written by ``gearlever cam design`` (its ``[cam]`` dimensions
        and its ``[law]``, which reads as a LAW.toml).
    points : int, optional
        Cam angles of the design (default: the file's ``points``).

    Returns
    -------
    CamDesign

    Raises
    ------
    GearleverError
        The message starts with the file: no ``[cam]`` table, an unknown or
        missing key, a value of the wrong type, or any refusal of
        :func:`~gearlever.cams.design_cam` (an undercut design is shown, not
        refused: the file records it).

    Notes
    -----
    The file holds the dimensions rounded to 12 significant digits, so the
    design is that of ``gearlever cam design`` to about 1e-12 relative.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "cam.toml"
    >>> _ = p.write_text('[cam]\\nfollower = "translating-flat"\\nunits = "mm"\\nbase_radius = 30.0\\n'
    ...     'offset = 0.0\\npoints = 720\\n[law]\\noutput = "displacement"\\nunits = "mm"\\n'
    ...     '[[law.segment]]\\nto = 180\\nmotion = "cycloidal"\\nrise = 10\\n'
    ...     '[[law.segment]]\\nto = 360\\nmotion = "cycloidal"\\nrise = -10\\n')
    >>> cam = load_cam(p)
    >>> cam.follower, cam.theta.size, round(cam.stroke, 9)
    ('translating-flat', 720, 10.0)
    """
    from gearlever._io import read_toml_table
    from gearlever.laws import load_law

    source = str(path)
    cam = read_toml_table(path, "CAM", "cam", CAM_KEYS, " (write one with gearlever cam design)")
    for key in ("follower", "base_radius"):
        if key not in cam:
            raise GearleverError(f"{source}: [cam] {key} is missing")
    if not isinstance(cam["follower"], str):
        raise GearleverError(f"{source}: [cam] follower must be a string, got {cam['follower']!r}")
    from gearlever.cams.followers import FOLLOWERS

    kind = FOLLOWERS.get(cam["follower"])
    dims = {}
    for key in ("base_radius", "roller_radius", "offset", "arm", "pivot_distance"):
        if key in cam and kind is not None and key != "base_radius" and key not in kind.needs:
            raise GearleverError(
                f"{source}: [cam] {key} is not a dimension of {a(kind.name)} follower "
                f"(its dimensions: base_radius, {', '.join(kind.needs)})"
            )
        if key in cam:
            v = cam[key]
            if isinstance(v, bool) or not isinstance(v, int | float):
                raise GearleverError(f"{source}: [cam] {key} must be a number, got {v!r}")
            dims[key] = float(v)
    _centre(cam, source)
    n = cam.get("points", 3600) if points is None else points
    if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= MAX_POINTS:
        raise GearleverError(f"{source}: [cam] points must be an integer in 8 .. {MAX_POINTS:,}, got {n!r}")
    law = load_law(path)
    try:
        design = design_cam(law, cam["follower"], **dims, points=n, allow_undercut=True)
    except GearleverError as exc:
        from gearlever.cams.followers._base import Unbuildable

        text = exc.named({n: f"[cam] {n}" for n in exc.names}) if isinstance(exc, Unbuildable) else str(exc)
        raise GearleverError(text if text.startswith(source) else f"{source}: {text}") from None
    if "units" not in cam or cam["units"] == design.units:
        return design
    if kind is not None and kind.law_output == "displacement":
        raise GearleverError(
            f"{source}: [cam] units = {cam['units']!r}, but a {kind.name} follower's lengths are in the "
            f"units of its [law] ({design.units!r}); give the law's units or leave units out"
        )
    from dataclasses import replace

    from gearlever.laws.law import LENGTH_UNITS

    if cam["units"] not in LENGTH_UNITS:  # an oscillating follower: the law is an angle, the file names the lengths'
        raise GearleverError(
            f"{source}: [cam] units must be one of {', '.join(LENGTH_UNITS)} (the units of the cam's lengths), "
            f"got {cam['units']!r}"
        )
    return replace(design, units=cam["units"])


def _centre(cam: dict, source: str) -> tuple[float, float]:
    """The ``centre`` of a ``[cam]`` table (default the origin), checked: two finite numbers."""
    import math

    v = cam.get("centre", [0.0, 0.0])
    if (
        not isinstance(v, list)
        or len(v) != 2
        or not all(not isinstance(x, bool) and isinstance(x, int | float) and math.isfinite(x) for x in v)
    ):
        raise GearleverError(f"{source}: [cam] centre must be [x, y], two finite numbers, got {v!r}")
    return float(v[0]), float(v[1])


def cam_centre(path) -> tuple[float, float]:
    """Where a CAM.toml places the cam's pivot in a drawing: its ``[cam] centre = [x, y]``, default the origin.

    The profile of :func:`load_cam` is about the pivot; the centre only says
    where the workbench draws it (``gearlever cam design`` writes none).

    Raises
    ------
    GearleverError
        The message starts with the file: not TOML, no ``[cam]`` table, or a
        centre that is not two finite numbers.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "cam.toml"
    >>> _ = p.write_text('[cam]\\nfollower = "translating-flat"\\nbase_radius = 30.0\\ncentre = [100, -5.5]\\n')
    >>> cam_centre(p)
    (100.0, -5.5)
    """
    from gearlever._io import read_toml_table

    return _centre(read_toml_table(path, "CAM", "cam", CAM_KEYS, " (write one with gearlever cam design)"), str(path))
