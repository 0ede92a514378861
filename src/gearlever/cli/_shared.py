"""Pieces shared by the ``mechanism`` and ``cam`` commands: the model loader, the page arguments, the cam page.

``gearlever mechanism`` (with its ``forces``/``simulate`` and ``view``
sub-commands, :mod:`~gearlever.cli._mechanism_dynamics` and
:mod:`~gearlever.cli._mechanism_view`) and ``gearlever cam`` all import these
from here, so that no command module imports another: the command modules
sit above this one, which imports only :mod:`gearlever.cli._common`, the
error family and (lazily, when called) the library.
"""

from __future__ import annotations

from pathlib import Path

from gearlever.cli._common import capped_int
from gearlever.errors import GearleverError

#: Largest ``--frames`` (same as :data:`gearlever.plotting.viewer.MAX_VIEW_FRAMES`, kept here so ``--help`` stays fast).
MAX_VIEW_FRAMES = 3600


def load_model(path):
    """The :class:`~gearlever.mechanism.Mechanism` of a model file (TOML, or a linkage ``.links.json``)."""
    from gearlever.mechanism import Mechanism

    return Mechanism.load(path)


def add_page_arguments(parser, turning: str) -> None:
    """``--out PAGE.html`` and ``--frames N`` (over one turn of ``turning``) of a command that writes a page."""
    parser.add_argument("--out", required=True, help="output page (.html)")
    parser.add_argument(
        "--frames",
        type=capped_int(MAX_VIEW_FRAMES, low=2),
        default=360,
        help=f"frames over one turn of {turning} (default 360, at most {MAX_VIEW_FRAMES})",
    )


def check_page_out(out: str) -> None:
    """Refuse an ``--out`` that is not an ``.html`` (or ``.htm``) file name."""
    if Path(out).suffix.lower() not in (".html", ".htm"):
        raise GearleverError(f"--out must end with .html, got {out!r}")


def cam_page(path: str, frames: int) -> str:
    """The page of ``cam view`` (and of ``mechanism view`` given a CAM.toml): the design at a multiple of ``frames``."""
    import tomllib

    from gearlever._io import read_text_capped
    from gearlever.cams import load_cam
    from gearlever.plotting.cam_viewer import cam_viewer_html

    try:
        stored = tomllib.loads(read_text_capped(path, "CAM")).get("cam", {}).get("points", 3600)
    except (tomllib.TOMLDecodeError, RecursionError):
        stored = 3600  # load_cam names the error
    stored = stored if isinstance(stored, int) and not isinstance(stored, bool) and stored > 0 else 3600
    points = frames * max(1, -(-min(stored, 36_000) // frames))
    cam = load_cam(path, points=points)
    return cam_viewer_html(cam, frames=frames, name=Path(path).stem)


#: The ``--branch`` help of every command that solves a model's motion (analyze, draw, animate, forces, view).
BRANCH_HELP = (
    "at a branch point (a singular pose the input goes on through): continue on the branch that keeps "
    "the motion smooth (default), keep the sketch's assembly branch (the velocity jumps), or stop there"
)


def add_branch_argument(parser) -> None:
    """``--branch continue|keep|stop`` (:mod:`gearlever.mechanism.branch`), the one flag of every motion command."""
    parser.add_argument("--branch", choices=("continue", "keep", "stop"), default="continue", help=BRANCH_HELP)


def say_branch_points(mech, result) -> None:
    """The one stderr line saying where the rows of ``result`` (a MechanismResult) passed branch points, if any."""
    import sys

    from gearlever.mechanism.branch import branch_message
    from gearlever.mechanism.sweep import input_labels

    line = branch_message(result.branch_points, input_labels(mech), [spec.kind for spec in mech.model.inputs])
    if line:
        print(line, file=sys.stderr)
