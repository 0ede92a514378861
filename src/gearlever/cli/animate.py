"""``gearlever animate``: a GIF of a linkage over one input turn."""

from __future__ import annotations

from gearlever.cli._common import capped_int, positive_float, progress
from gearlever.errors import GearleverError

#: Most frames: matplotlib's Pillow writer keeps every frame in memory
#: (~200 kB each at the default size) and draws one in ~50 ms, so 360 frames
#: (one a degree) take ~70 MB and ~20 s.
MAX_FRAMES = 360
#: Most frames per second: GIF delays are whole hundredths of a second.
MAX_FPS = 100


def register(sub) -> None:
    p = sub.add_parser(
        "animate",
        help="write a GIF of a four-bar over one crank turn",
        description="Animate a four-bar (matplotlib's Pillow writer).",
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
    p.add_argument(
        "--frames", type=capped_int(MAX_FRAMES), default=36, help=f"frames per turn (default 36, at most {MAX_FRAMES})"
    )
    p.add_argument(
        "--fps", type=capped_int(MAX_FPS), default=12, help=f"frames per second (default 12, at most {MAX_FPS})"
    )
    p.add_argument("--branch", choices=("open", "crossed"), default="open", help="assembly branch")
    p.set_defaults(func=_run)


def _run(args) -> int:
    if not str(args.out).lower().endswith(".gif"):
        raise GearleverError(f"--out must be a .gif file name, got {args.out!r}")
    from gearlever.loops import grashof

    grashof(*args.fourbar)  # checks that the linkage assembles before any drawing
    from gearlever.plotting.animation import animate_fourbar

    with progress("drawing the frames"):
        path = animate_fourbar(*args.fourbar, args.out, frames=args.frames, branch=args.branch, fps=args.fps)
    print(f"wrote {path}")
    return 0
