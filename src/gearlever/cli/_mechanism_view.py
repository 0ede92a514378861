"""``gearlever mechanism view``: one self-contained HTML page that animates a model file.

Sub-command (added to ``gearlever mechanism`` by :func:`register_view`)::

    gearlever mechanism view MODEL --out PAGE.html [--frames N] [--rpm NAME=R ...] [--input NAME=VALUE ...]
        [--branch continue|keep|stop]

The first input turns one full turn from its sketch angle (or from
``--input`` for it) over ``--frames`` frames (end excluded), or, when it
cannot turn fully, sweeps one oscillation between its limits (dead points)
and says so on stderr; the other inputs
stay at their sketch values (or ``--input``; degrees for a link, length for a
slider); for two or more inputs the page offers
:data:`gearlever.plotting.viewer.GRID_STEPS` values of the second.  With
``--rpm`` (one per input, ``NAME=VALUE``; a bare value for a one-input model)
the page shows time and velocities per second.  Given a CAM.toml (written by
``gearlever cam design``) it writes the cam page of ``gearlever cam view``.  Caps (refused before anything is
solved, exit 2): ``--frames`` at most :data:`gearlever.plotting.viewer.MAX_VIEW_FRAMES`,
frames x grid values x moving links at most :data:`~gearlever.plotting.viewer.MAX_VIEW_WORK`,
a page of at most :data:`~gearlever.plotting.viewer.MAX_PAGE_BYTES` bytes, at most
:data:`~gearlever.plotting.viewer.MAX_VIEW_LINKS` moving links, an ``--input`` at most
:data:`~gearlever.plotting.viewer.MAX_START_TURNS` turns from the sketch.
"""

from __future__ import annotations

import math

from gearlever.cli._common import emit, named_values
from gearlever.cli._shared import add_branch_argument, add_page_arguments, cam_page, check_page_out, load_model
from gearlever.errors import GearleverError


def register_view(ms) -> None:
    v = ms.add_parser("view", help="interactive HTML page (one self-contained file) that animates the model")
    v.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    add_page_arguments(v, "the first input")
    v.add_argument(
        "--rpm", action="append", metavar="NAME=VALUE", help="speed of an input (rev/min), once per input that moves"
    )
    v.add_argument(
        "--input",
        action="append",
        metavar="NAME=VALUE",
        help="start of the first input / held value of another (deg, or length for a slider)",
    )
    add_branch_argument(v)
    v.set_defaults(func=_view)


def _view(args) -> int:
    check_page_out(args.out)
    if _is_cam_file(args.model):
        if args.rpm or args.input:
            raise GearleverError(f"{'--rpm' if args.rpm else '--input'} does not apply to a cam file ({args.model})")
        emit(cam_page(args.model, args.frames), args.out)
        return 0
    from gearlever.plotting.viewer import viewer_html

    mech = load_model(args.model)
    specs = mech.model.inputs
    labels = [s.label for s in specs]
    rpm = named_values(args.rpm, "--rpm", labels) if args.rpm else None
    given = named_values(args.input, "--input", labels)
    inputs = {
        name: value * (math.pi / 180.0 if specs[labels.index(name)].kind == "link" else 1.0)
        for name, value in given.items()
    }
    if rpm is not None and labels[0] not in rpm:
        raise GearleverError(f"--rpm must give the first input {labels[0]!r} (it sets the time)")
    try:
        page = viewer_html(mech, frames=args.frames, rpm=rpm, inputs=inputs or None, branch=args.branch)
    except GearleverError as exc:
        text = str(exc)
        for lib, flag in (
            ("rpm:", "--rpm:"),
            ("inputs:", "--input:"),
            ("frames:", "--frames:"),
            ("mech:", f"{args.model}:"),
        ):
            if text.startswith(lib):
                text = flag + text[len(lib) :]
        raise GearleverError(text) from None
    _say_oscillation(mech, inputs, args.branch)
    _say_branch_points(mech, inputs, args.frames, args.branch)
    emit(page, args.out)
    return 0


def _say_branch_points(mech, inputs, frames: int, branch: str) -> None:
    """The stderr line of a page whose first input passes branch points (the rows of its first grid value)."""
    import numpy as np

    from gearlever.cli._shared import say_branch_points
    from gearlever.plotting.viewer import _first_input_rows, _frames_inputs

    start = _frames_inputs(mech, frames, inputs or None)[0]
    turn = _first_input_rows(mech, start, frames, branch)[0]
    q = np.tile(start, (turn.size, 1))
    q[:, 0] = turn
    say_branch_points(mech, mech.solve(q, branch=branch))


def _say_oscillation(mech, inputs, branch: str = "continue") -> None:
    """The stderr line of a page that sweeps one oscillation of a rocking first input."""
    import sys

    import numpy as np

    from gearlever.mechanism.limits import input_limits

    if mech.model.inputs[0].kind != "link":
        return
    labels = [s.label for s in mech.model.inputs]
    start = np.array(mech.sketch_inputs, dtype=float)
    for name, value in (inputs or {}).items():
        start[labels.index(name)] = value
    lim = input_limits(mech, 0, start=start, branch=branch)
    if lim.rocks:
        print(f"{lim.input} rocks between {lim.text()}: sweeping one oscillation", file=sys.stderr)


def _is_cam_file(path: str) -> bool:
    """True for a CAM.toml of ``gearlever cam design`` (a ``[cam]`` table and no ``[points]``)."""
    import tomllib

    from gearlever._io import read_text_capped

    try:
        data = tomllib.loads(read_text_capped(path, "MODEL"))
    except (GearleverError, tomllib.TOMLDecodeError):
        return False  # the model loader names the problem
    return isinstance(data.get("cam"), dict) and "points" not in data
