"""``gearlever workbench``: draw, move, design and save mechanisms in the browser, served locally.

::

    gearlever workbench [MODEL.toml | MODEL.links.json | FOLDER] [--port N] [--host ADDR] [--no-browser]
                        [--scheduler ADDRESS]

Prints exactly one line on stdout, ``workbench: http://127.0.0.1:PORT/?token=TOKEN``
(with ``&open=NAME`` for a model file), opens it in the browser unless
``--no-browser``, and serves until Ctrl-C (exit 130) or SIGTERM (exit 143),
nothing half-written.  A FOLDER is the workspace (default: the current
folder); a model file opens in the page and its folder is the workspace.
See :mod:`gearlever.workbench`.
"""

from __future__ import annotations

from gearlever.errors import GearleverError


def register(sub) -> None:
    p = sub.add_parser(
        "workbench",
        help="the workbench: draw a mechanism in the browser, watch it move, design it, save it",
        description="Start the workbench on this machine and print its URL (one line, with the token). The "
        "page draws and edits a model, plays its cycle, plots it, runs synthesis and saves into the workspace.",
    )
    p.add_argument(
        "path",
        nargs="?",
        default=".",
        metavar="MODEL.toml|MODEL.links.json|FOLDER",
        help="a model file to open (its folder is the workspace) or the workspace folder (default: .)",
    )
    p.add_argument("--port", type=int, default=0, help="port to listen on (default 0: any free port)")
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to listen on (default 127.0.0.1; any other address: the token is the only guard)",
    )
    p.add_argument("--no-browser", action="store_true", help="print the URL only, open no browser")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS", help="dask.distributed scheduler for synthesis")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from pathlib import Path

    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError as exc:  # a broken install: say what is missing, never "internal error"
        raise GearleverError(
            f"workbench: the package {exc.name!r} is not installed (gearlever depends on starlette and uvicorn): "
            "reinstall gearlever, e.g. make reproduce or pip install -e ."
        ) from None
    from gearlever.workbench.files import SUFFIXES
    from gearlever.workbench.serve import serve

    if not 0 <= args.port <= 65535:
        raise GearleverError(f"--port must be 0 to 65535, got {args.port}")
    path = Path(args.path)
    open_name = None
    if path.is_dir():
        workspace = path
    elif path.is_file():
        if not path.name.endswith(SUFFIXES):
            raise GearleverError(f"{args.path}: the workbench opens .toml and .links.json model files or a folder")
        workspace, open_name = path.parent, path.name
    else:
        raise GearleverError(f"{args.path}: no such file or folder")
    try:
        serve(
            workspace,
            host=args.host,
            port=args.port,
            open_name=open_name,
            browser=not args.no_browser,
            scheduler=args.scheduler,
        )
    except OSError as exc:
        raise GearleverError(
            f"--host/--port: cannot listen on {args.host}:{args.port} ({exc.strerror or exc})"
        ) from None
    return 0
