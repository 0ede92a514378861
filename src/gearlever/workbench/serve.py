"""Start and stop the workbench: a loopback socket, the printed URL, uvicorn, signals.

:func:`serve` binds the socket first (port 0: the kernel picks a free
port), so the URL printed is the one that answers; it then runs uvicorn in
the calling (main) thread until Ctrl-C or SIGTERM.  uvicorn finishes the
requests in flight (a file being saved is renamed into place or not at
all: :mod:`gearlever.workbench.files` writes atomically), the app's shutdown
stops the worker processes and any job, and uvicorn raises the signal again
once it is done, so the command exits as every gearlever command does on
that signal (130 for Ctrl-C, 143 for SIGTERM, one line on stderr).  The URL
line is printed once uvicorn has started, its signal handlers in place: a
signal sent after the line is seen always stops the bench.
"""

from __future__ import annotations

import socket
import sys
from pathlib import Path

__all__ = ["serve", "bind", "url_line", "WARNING_HOST"]

#: Printed on stderr when the bench is bound to another address than loopback.
WARNING_HOST = (
    "gearlever workbench: warning: listening on {host}, not on loopback: other machines can reach the bench, "
    "and the token is then the only guard"
)
_LOOPBACK = ("127.0.0.1", "localhost", "::1")


def bind(host: str, port: int) -> socket.socket:
    """A listening TCP socket on ``host:port`` (port 0: any free port)."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    sock = socket.socket(family, socket.SOCK_STREAM)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((host, port))
        sock.listen(128)
    except BaseException:
        sock.close()
        raise
    sock.set_inheritable(True)
    return sock


def url_line(host: str, port: int, token: str, open_name: str | None = None) -> str:
    """The one line the command prints.

    >>> url_line("127.0.0.1", 8000, "abc")
    'workbench: http://127.0.0.1:8000/?token=abc'
    >>> url_line("::1", 8000, "abc", "a b.toml")
    'workbench: http://[::1]:8000/?token=abc&open=a%20b.toml'
    """
    from urllib.parse import quote

    shown = f"[{host}]" if ":" in host else host
    if host in ("0.0.0.0", "::"):
        shown = "127.0.0.1"
    extra = f"&open={quote(open_name)}" if open_name else ""
    return f"workbench: http://{shown}:{port}/?token={token}{extra}"


def serve(
    workspace,
    host: str = "127.0.0.1",
    port: int = 0,
    open_name: str | None = None,
    browser: bool = True,
    scheduler: str | None = None,
    token: str | None = None,
) -> None:
    """Serve the workbench until Ctrl-C or SIGTERM.

    Parameters
    ----------
    workspace : path-like
        The folder of the model files.
    host : str
        Address to bind (default loopback); another prints :data:`WARNING_HOST` on stderr.
    port : int
        0 for any free port.
    open_name : str, optional
        A file of the workspace the page opens first (``&open=`` in the URL).
    browser : bool
        Open the URL in the default browser (:mod:`webbrowser`).
    scheduler : str, optional
        A dask.distributed scheduler address for the synthesis jobs.
    token : str, optional
        Default: a new one (:func:`gearlever.workbench.app.new_token`).
    """
    import uvicorn

    from gearlever.workbench.app import create_app, new_token

    token = token or new_token()
    sock = bind(host, port)
    try:
        bound = sock.getsockname()[1]
        app = create_app(Path(workspace), token, host=host, port=bound, scheduler=scheduler)
        if host not in _LOOPBACK:
            print(WARNING_HOST.format(host=host), file=sys.stderr, flush=True)
        line = url_line(host, bound, token, open_name)

        def announce() -> None:
            print(line, flush=True)
            if browser:
                import webbrowser

                try:
                    webbrowser.open(line.split(" ", 1)[1])
                except Exception:  # noqa: BLE001 - no browser: the printed URL is the way in
                    pass

        config = uvicorn.Config(
            app, log_level="warning", access_log=False, lifespan="on", timeout_graceful_shutdown=10, server_header=False
        )
        server = _announcing_server(uvicorn.Server, announce)(config)
        server.run(sockets=[sock])
        _end_as_signalled(getattr(server, "_captured_signals", []))
    finally:
        sock.close()


def _announcing_server(base, announce):
    """A uvicorn server class that calls ``announce()`` (print the URL) once it has started.

    uvicorn installs its SIGINT and SIGTERM handlers (``capture_signals``)
    before its start-up and the app's lifespan, and restores the ones it found
    when it is done; the URL line is printed only after start-up, so every
    Ctrl-C or SIGTERM sent once the line is seen is uvicorn's to handle.
    Printed earlier, a signal in between met the handlers the process had at
    start: with Ctrl-C ignored (a background job of a non-interactive shell
    inherits that), it was lost and the bench ran on.
    """

    class AnnouncingServer(base):
        async def startup(self, sockets=None) -> None:
            await super().startup(sockets=sockets)
            if self.started and not self.should_exit:
                announce()

    return AnnouncingServer


def _end_as_signalled(captured) -> None:
    """End as the signal that stopped the server, if uvicorn's raising it again did not already.

    uvicorn raises a captured signal again once it has shut down, through
    the handler it restored.  When the process started with Ctrl-C ignored
    (a background job of a non-interactive shell inherits SIG_IGN, as in a
    full test run), gearlever leaves that disposition alone, uvicorn restores
    it, and the raise does nothing: the command would end with exit 0 and
    nothing on stderr, as if nobody had stopped it (tested with SIGINT
    ignored).  The handler is called once more, and if it returns, Ctrl-C
    ends as :class:`KeyboardInterrupt` (exit 130) and SIGTERM as exit 143.
    """
    import signal

    for sig in reversed(list(captured)):
        handler = signal.getsignal(sig)
        if callable(handler):
            handler(sig, None)
        if sig == signal.SIGINT:
            raise KeyboardInterrupt
        raise SystemExit(128 + int(sig))
