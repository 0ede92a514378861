"""``gearlever animate``: the four-bar shortcut of ``gearlever mechanism animate``.

``gearlever animate --fourbar GROUND CRANK COUPLER ROCKER`` builds the
four-bar as a mechanism model and animates it with the same code as
``gearlever mechanism animate MODEL`` (one animation for every model).
This module also holds the figure options shared by ``mechanism draw``,
``mechanism animate`` and ``animate``: ``--dpi`` and ``--size W H``, capped.
"""

from __future__ import annotations

from gearlever.cli._common import capped_float, capped_int, check_cap, commit_outputs, positive_float, progress
from gearlever.errors import GearleverError
from gearlever.plotting._limits import (
    ANIMATION_DPI,
    ANIMATION_SIZE,
    MAX_ANIMATION_PIXELS,
    MAX_DPI,
    MAX_PIXELS,
    MAX_SIZE_IN,
    MIN_SIZE_IN,
    pixels,
)

#: Most frames: each is kept as one byte a pixel until the GIF is written
#: (480 kB at the default 800 x 600) and drawn in ~0.1 s: 360 frames (one a
#: degree) of the four-bar example took 435 MB of memory (peak) and ~1 min.
MAX_FRAMES = 360
#: Most frames per second: GIF delays are whole hundredths of a second.
MAX_FPS = 100


def add_figure_args(p, size, dpi: int, animation: bool = False) -> None:
    """``--size W H`` (inches) and ``--dpi`` of a drawing or animation, with their caps."""
    p.add_argument(
        "--size",
        nargs=2,
        type=capped_float(MAX_SIZE_IN),
        metavar=("W", "H"),
        default=None,
        help=f"figure width and height in inches (default {size[0]:g} {size[1]:g}; "
        f"{MIN_SIZE_IN:g} to {MAX_SIZE_IN:g} each)",
    )
    p.add_argument(
        "--dpi",
        type=capped_int(MAX_DPI),
        default=dpi,
        help=f"pixels per inch (default {dpi}, at most {MAX_DPI}; at most {MAX_PIXELS:.3g} pixels an image"
        + (f", {MAX_ANIMATION_PIXELS:.3g} over all the frames)" if animation else ")"),
    )
    p.set_defaults(default_size=tuple(size))


def figure_args(args, frames: int | None = None) -> tuple:
    """``(size, dpi)`` from the parsed options, refused (naming the flags) beyond the caps."""
    size = tuple(args.size) if args.size is not None else args.default_size
    w, h = size
    if min(w, h) < MIN_SIZE_IN:
        raise GearleverError(f"--size must be at least {MIN_SIZE_IN:g} inch each, got {w:g} {h:g}")
    pw, ph = pixels(w, h, args.dpi)
    check_cap(f"--size {w:g} {h:g} with --dpi {args.dpi} ({pw} x {ph} pixels)", pw * ph, MAX_PIXELS)
    if frames is not None:
        check_cap(
            f"--frames {frames} of --size {w:g} {h:g} with --dpi {args.dpi} (pixels of all the frames)",
            frames * pw * ph,
            MAX_ANIMATION_PIXELS,
        )
    return size, args.dpi


def add_animation_args(p) -> None:
    """``--frames``, ``--fps``, ``--size`` and ``--dpi`` of a GIF."""
    p.add_argument(
        "--frames", type=capped_int(MAX_FRAMES), default=36, help=f"frames per sweep (default 36, at most {MAX_FRAMES})"
    )
    p.add_argument(
        "--fps", type=capped_int(MAX_FPS), default=12, help=f"frames per second (default 12, at most {MAX_FPS})"
    )
    add_figure_args(p, ANIMATION_SIZE, ANIMATION_DPI, animation=True)


def check_gif(out) -> None:
    if not str(out).lower().endswith(".gif"):
        raise GearleverError(f"--out must be a .gif file name, got {out!r}")


def register(sub) -> None:
    p = sub.add_parser(
        "animate",
        help="write a GIF of a four-bar over one crank turn (shortcut of `mechanism animate`)",
        description="Animate a four-bar given by its link lengths: a shortcut that builds the four-bar "
        "as a mechanism model (points O2, A, B, O4; links crank, coupler, rocker; the crank is the input, "
        "starting at the first whole degree where the linkage closes on --branch) and draws it with the "
        "same animation as `gearlever mechanism animate MODEL` (link and point names, input, legend). "
        "The GIF is 800 x 600 pixels by default (--size 8 6 at --dpi 100).",
    )
    p.add_argument(
        "--fourbar",
        nargs=4,
        type=positive_float,
        required=True,
        metavar=("GROUND", "CRANK", "COUPLER", "ROCKER"),
        help="link lengths",
    )
    p.add_argument("--out", required=True, help="output GIF file (.gif)")
    p.add_argument("--branch", choices=("open", "crossed"), default="open", help="assembly branch")
    add_animation_args(p)
    p.set_defaults(func=_run)


def _run(args) -> int:
    check_gif(args.out)
    from gearlever.loops import grashof

    grashof(*args.fourbar)  # checks that the linkage assembles before any drawing
    size, dpi = figure_args(args, args.frames)
    from gearlever.plotting.animation import animate_fourbar

    with progress("drawing the frames"):
        path = animate_fourbar(
            *args.fourbar, args.out, frames=args.frames, branch=args.branch, fps=args.fps, dpi=dpi, figsize=size
        )
    commit_outputs()  # the line names the file written: it is there first
    print(f"wrote {path}")
    return 0
