"""Reading a CAM.toml written by ``gearlever cam design``: the design again from its dimensions and law.

Imports the standard library, gearlever._io, gearlever.laws, gearlever.errors and gearlever.cams.design.
"""

from __future__ import annotations

from gearlever.cams.design import MAX_POINTS, CamDesign, design_cam
from gearlever.errors import GearleverError

__all__ = ["load_cam"]

#: Keys of the ``[cam]`` table.
CAM_KEYS = ("follower", "units", "base_radius", "roller_radius", "offset", "arm", "pivot_distance", "points")


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
    dims = {}
    for key in ("base_radius", "roller_radius", "offset", "arm", "pivot_distance"):
        if key in cam:
            v = cam[key]
            if isinstance(v, bool) or not isinstance(v, int | float):
                raise GearleverError(f"{source}: [cam] {key} must be a number, got {v!r}")
            dims[key] = float(v)
    n = cam.get("points", 3600) if points is None else points
    if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= MAX_POINTS:
        raise GearleverError(f"{source}: [cam] points must be an integer in 8 .. {MAX_POINTS:,}, got {n!r}")
    law = load_law(path)
    try:
        return design_cam(law, cam["follower"], **dims, points=n, allow_undercut=True)
    except GearleverError as exc:
        text = str(exc)
        raise GearleverError(text if text.startswith(source) else f"{source}: {text}") from None
