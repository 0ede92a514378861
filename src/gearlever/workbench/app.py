"""The workbench's web application: :func:`create_app` builds the Starlette app the command serves.

Why Starlette: a small ASGI toolkit (routing, requests, responses, static
files, a test client) with two dependencies (anyio, typing_extensions) and no
data-validation layer: the library already validates every model element
and names it, so FastAPI's pydantic models would only restate the engine's
checks.  FastAPI is built on Starlette; the OpenAPI document here is written
by hand (:data:`OPENAPI`).  uvicorn serves it (:mod:`gearlever.workbench.serve`).

Guards, in the order a request meets them (:class:`Guard`, a plain ASGI
middleware, so that server-sent events stream):

1. Host: the ``Host`` header must name the bound address and port
   (``127.0.0.1``, ``localhost``, ``[::1]`` or the ``--host``; any IP
   literal when bound to a wildcard address): a page of another site that
   rebinds its DNS name to 127.0.0.1 sends its own name and is refused (400).
2. Origin: a request carrying an ``Origin`` other than the bench's own is
   refused (403); no CORS header is ever sent, so no other site can read an
   answer.
3. Token: 128 bits from :func:`secrets.token_urlsafe`, compared with
   :func:`hmac.compare_digest`, taken from ``Authorization: Bearer``, the
   ``token`` query parameter, or the cookie ``gearlever_token`` that
   ``GET /?token=`` sets (HttpOnly, SameSite=Strict); else 401.

Errors are JSON ``{"error": "one line naming the field"}`` with a 4xx
status; bodies are capped at :data:`MAX_BODY_BYTES` (413, the cap named).

Computation runs in worker processes (:class:`WorkerPool`), never in the
server's process: a solve past :data:`SOLVE_SECONDS` (an export past
:data:`EXPORT_SECONDS`) is stopped by killing its worker, which is replaced,
and the request answers 400 naming the cap.  A thread could not be stopped;
a deadline checked between batches would not stop one long batched solve.
Processes also keep matplotlib (exports) out of the server and the server's
memory flat.
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import hmac
import ipaddress
import json
import multiprocessing
import secrets
import threading
import time
from http.cookies import SimpleCookie
from importlib import resources
from pathlib import Path
from urllib.parse import parse_qs

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from gearlever.workbench.errors import ApiError
from gearlever.workbench.files import CAM_SUFFIX

__all__ = [
    "create_app",
    "new_token",
    "WorkerPool",
    "MAX_BODY_BYTES",
    "SOLVE_SECONDS",
    "EXPORT_SECONDS",
    "WORKERS",
    "OPENAPI",
]

#: Largest request body (bytes): a model of the engine's cap of characters, escaped in JSON.
MAX_BODY_BYTES = 2 * 2**20
#: Seconds a solve (parse, dump, structure, forces) may take before its worker is stopped.
SOLVE_SECONDS = 10.0
#: Seconds an export may take (a GIF draws 36 frames with matplotlib).
EXPORT_SECONDS = 120.0
#: Worker processes that compute (the machine's two cores).
WORKERS = 2
#: Name of the cookie that carries the token for the page's static files.
COOKIE = "gearlever_token"
#: Content-Security-Policy of the page: its own scripts and styles only, nothing from elsewhere.
CSP = (
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; connect-src 'self'; "
    "object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
)


def new_token() -> str:
    """A fresh token: 128 random bits (:func:`secrets.token_urlsafe` of 16 bytes, 22 characters)."""
    return secrets.token_urlsafe(16)


def _json(body: bytes) -> Response:
    """An answer whose strict JSON a worker encoded."""
    return Response(body, media_type="application/json")


def _error(status: int, message: str, headers=None, **extra) -> JSONResponse:
    return JSONResponse({"error": message, **extra}, status_code=status, headers=headers)


# --------------------------------------------------------------------------- worker processes
def _worker_main(conn) -> None:
    """A worker process: answer ``(function, kwargs)`` requests on ``conn`` until it closes."""
    import os
    import signal
    import warnings

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the whole group: the server stops us
    os.environ.setdefault("MPLBACKEND", "Agg")
    warnings.simplefilter("ignore")
    from gearlever.errors import GearleverError
    from gearlever.workbench import engine

    calls = {
        "parse": engine.parse,
        "dump": engine.dump,
        "solve": functools.partial(engine.solve_frames, plain=not _HAS_ORJSON),
        "structure": engine.structure,
        "forces": engine.forces,
        "export": engine.export,
        "branch": engine.flip_branch,
        "dump_solve": functools.partial(engine.dump_solve, plain=not _HAS_ORJSON),
        "cam": engine.cam,
        "cam_file": engine.cam_file_params,
    }
    with contextlib.suppress(Exception):  # warm up: the first request is then as fast as the others
        from gearlever.data import example_path

        engine.solve_frames(Path(example_path("fourbar.toml")).read_text(encoding="utf-8"), 36)
    while True:
        try:
            seq, name, kwargs = conn.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        try:
            result = calls[name](**kwargs)
            if name in ("dump", "branch"):
                result = {"model": result}
            if isinstance(result, dict):  # encoded here, in parallel workers, not in the server's event loop
                result = _encode(result)
            reply = ("ok", result)
        except engine.WorkbenchError as exc:
            reply = ("error", str(exc), exc.line)
        except (GearleverError, ValueError, OverflowError, ZeroDivisionError) as exc:
            reply = ("error", " ".join(str(exc).split()) or type(exc).__name__, None)
        except RecursionError:
            reply = ("error", "model: nested too deeply", None)
        except MemoryError:
            reply = ("error", "model: too large for this machine's memory", None)
        except Exception as exc:  # noqa: BLE001 - a bug: reported as such, one line, no traceback
            reply = ("bug", f"{type(exc).__name__}: {' '.join(str(exc).split())}"[:500], None)
        try:
            conn.send((seq, *reply))
        except (OSError, ValueError, KeyboardInterrupt):
            return


try:
    import orjson
except ImportError:  # pragma: no cover - a declared dependency; the standard encoder writes the same JSON
    orjson = None
_HAS_ORJSON = orjson is not None


def _encode(result: dict) -> bytes:
    """Strict JSON of an engine answer (the engine has put None for NaN).

    orjson when installed: a cycle of 360 frames is 0.1 to 0.5 MB of numbers,
    and the standard library's encoder spends 7 ms on the four-bar's and
    50 ms on a 20-joint linkage's where orjson spends 0.6 and 2 ms
    (``benchmarks/bench_workbench.py``); both write the shortest text that
    reads back as the same float.  With orjson the worker answers a cycle's
    all-finite series as numpy arrays (``solve_frames(plain=False)``), which
    orjson writes without making a Python float of each value.
    """
    if orjson is not None:
        try:
            return orjson.dumps(result, option=orjson.OPT_SERIALIZE_NUMPY)
        except TypeError:  # orjson.JSONEncodeError: an int past 64 bits, say; the standard encoder says what
            pass
    return json.dumps(result, allow_nan=False, separators=(",", ":"), ensure_ascii=False, check_circular=False).encode()


class _Worker:
    def __init__(self, ctx):
        self.conn, child = ctx.Pipe()
        self.process = ctx.Process(target=_worker_main, args=(child,), daemon=True, name="gearlever-workbench-worker")
        self.process.start()
        child.close()

    def stop(self) -> None:
        with contextlib.suppress(OSError):
            self.conn.close()
        if self.process.is_alive():
            self.process.kill()
        self.process.join(5)


class WorkerPool:
    """Worker processes (spawned, so no lock of the server is inherited) that run the engine's calls.

    :meth:`call` waits for an idle worker, sends the call and waits for the
    answer at most ``seconds``; past that the worker is killed (the solve is
    stopped, not left running) and replaced.
    """

    def __init__(self, size: int = WORKERS):
        self.size = size
        self._ctx = multiprocessing.get_context("spawn")
        self._idle: asyncio.Queue | None = None
        self._all: list[_Worker] = []
        self._lock = threading.Lock()
        self._closed = False
        self._seq = 0

    def _start(self) -> None:
        if self._idle is None:
            self._idle = asyncio.Queue()
            for _ in range(self.size):
                w = _Worker(self._ctx)
                self._all.append(w)
                self._idle.put_nowait(w)

    async def start(self) -> None:
        self._start()

    async def call(self, name: str, seconds: float, **kwargs):
        """The engine's answer, or :class:`ApiError` (400 refusal or cap, 500 a bug)."""
        if self._closed:
            raise ApiError(503, "the bench is stopping")
        self._start()
        worker = await self._idle.get()
        replace = False
        try:
            self._seq += 1
            seq = self._seq
            worker.conn.send((seq, name, kwargs))
            deadline = time.monotonic() + seconds
            while True:
                # a reply of an earlier call whose request went away (its task cancelled) is skipped
                left = deadline - time.monotonic()
                ready = left > 0 and await asyncio.to_thread(worker.conn.poll, left)
                if not ready:
                    replace = True
                    raise ApiError(
                        400,
                        f"{name}: stopped after the cap of {seconds:g} s per {name}; "
                        "use fewer frames or a smaller model",
                    )
                got = worker.conn.recv()
                if got[0] == seq:
                    reply = got[1:]
                    break
        except (EOFError, OSError, BrokenPipeError):
            replace = True
            raise ApiError(500, f"{name}: the worker process ended unexpectedly") from None
        finally:
            if replace and not self._closed:
                worker.stop()
                with self._lock:
                    if worker in self._all:
                        self._all.remove(worker)
                fresh = await asyncio.to_thread(_Worker, self._ctx)
                with self._lock:
                    self._all.append(fresh)
                self._idle.put_nowait(fresh)
            elif not replace:
                self._idle.put_nowait(worker)
        if reply[0] == "ok":
            return reply[1]
        if reply[0] == "error":
            raise ApiError(400, reply[1], line=reply[2]) if reply[2] is not None else ApiError(400, reply[1])
        raise ApiError(500, f"internal error (please report): {reply[1]}")

    def close(self) -> None:
        self._closed = True
        for w in list(self._all):
            w.stop()
        self._all.clear()


# --------------------------------------------------------------------------- guard
def _host_port(value: str) -> tuple:
    value = value.strip().lower()
    if value.startswith("["):
        host, _, rest = value[1:].partition("]")
        port = rest[1:] if rest.startswith(":") else ""
    else:
        host, _, port = value.partition(":")
    return host, port


def _is_ip(host: str) -> bool:
    try:
        ipaddress.ip_address(host)
    except ValueError:
        return False
    return True


class Guard:
    """ASGI middleware: Host check (400), Origin check (403), token (401), before any route runs."""

    def __init__(self, app, token: str, host: str, port: int | None):
        self.app = app
        self.token = token.encode("utf-8")
        self.host = host.lower().strip("[]")
        self.port = None if port is None else str(port)
        self.wildcard = self.host in ("0.0.0.0", "::", "")

    def host_ok(self, value: str) -> bool:
        host, port = _host_port(value)
        if self.port is not None and port != self.port:
            return False
        if host in ("127.0.0.1", "localhost", "::1", self.host):
            return True
        return self.wildcard and _is_ip(host)

    def token_ok(self, scope, headers: dict) -> bool:
        given = []
        auth = headers.get("authorization", "")
        if auth[:7].lower() == "bearer ":
            given.append(auth[7:].strip())
        qs = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        given += qs.get("token", [])[:1]
        if "cookie" in headers:
            with contextlib.suppress(Exception):
                c = SimpleCookie()
                c.load(headers["cookie"])
                if COOKIE in c:
                    given.append(c[COOKIE].value)
        ok = False
        for g in given:
            ok |= hmac.compare_digest(g.encode("utf-8", "replace"), self.token)
        return ok

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {}
        for k, v in scope.get("headers", []):
            headers.setdefault(k.decode("latin-1").lower(), v.decode("latin-1"))
        host = headers.get("host", "")
        if not self.host_ok(host):
            resp = _error(400, f"Host: {host[:100]!r} is not this bench's address (a DNS-rebinding request is refused)")
        elif "origin" in headers and not (
            headers["origin"].lower().startswith(("http://", "https://"))
            and headers["origin"].split("://", 1)[1].lower() == host.lower()
        ):
            resp = _error(403, f"Origin: {headers['origin'][:100]!r} is not this bench (no cross-site requests)")
        elif not self.token_ok(scope, headers):
            resp = _error(
                401,
                "token: missing or wrong (send Authorization: Bearer TOKEN, or open the URL the command printed)",
                headers={"WWW-Authenticate": "Bearer"},
            )
        else:
            await self.app(scope, receive, send)
            return
        await resp(scope, receive, send)


# --------------------------------------------------------------------------- request helpers
async def _body(request: Request) -> dict:
    """The JSON object of the body, capped at :data:`MAX_BODY_BYTES`."""
    length = request.headers.get("content-length")
    if length is not None and (not length.isdigit() or int(length) > MAX_BODY_BYTES):
        raise ApiError(413, f"body: {length} bytes, more than the cap of {MAX_BODY_BYTES} bytes")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > MAX_BODY_BYTES:
            raise ApiError(413, f"body: more than the cap of {MAX_BODY_BYTES} bytes")
        chunks.append(chunk)
    raw = b"".join(chunks)
    try:
        data = json.loads(raw.decode("utf-8"), parse_constant=_no_constant)
    except (UnicodeDecodeError, ValueError) as exc:
        raise ApiError(400, f"body: not JSON ({' '.join(str(exc).split())[:200]})") from None
    except RecursionError:
        raise ApiError(400, "body: nested too deeply") from None
    if not isinstance(data, dict):
        raise ApiError(400, f"body must be a JSON object, got {type(data).__name__}")
    return data


def _json_kind(v) -> str:
    return {dict: "object", list: "list", str: "string", bool: "boolean", type(None): "null"}.get(type(v), "number")


def _no_constant(name):
    raise ValueError(f"{name} is not a number in JSON")


def _field(body: dict, key: str, kind, required: bool = True, default=None):
    if key not in body:
        if required:
            raise ApiError(400, f"{key}: missing")
        return default
    v = body[key]
    if kind is int and (isinstance(v, bool) or not isinstance(v, int)):
        raise ApiError(400, f"{key} must be an integer, got {json.dumps(v)[:60]}")
    if kind is not int and not isinstance(v, kind):
        names = {dict: "JSON object", str: "string", list: "list", bool: "boolean"}
        raise ApiError(400, f"{key} must be a {names.get(kind, kind.__name__)}, got {_json_kind(v)}")
    return v


def _only(body: dict, keys) -> None:
    extra = [k for k in body if k not in keys]
    if extra:
        raise ApiError(400, f"{extra[0][:60]}: unknown field (fields: {', '.join(keys)})")


def _model_text(body: dict) -> str:
    return _field(body, "model", str)


def _frames(body: dict) -> int:
    from gearlever.workbench.engine import MAX_FRAMES

    frames = _field(body, "frames", int, required=False, default=360)
    if not 2 <= frames <= MAX_FRAMES:
        raise ApiError(400, f"frames must be an integer from 2 to {MAX_FRAMES}, got {frames}")
    return frames


def _endpoint(fn):
    """A route whose :class:`ApiError` becomes its JSON answer."""

    async def run(request: Request):
        try:
            return await fn(request)
        except ApiError as exc:
            return _error(exc.status, exc.message, **exc.extra)

    run.__name__ = fn.__name__
    run.__doc__ = fn.__doc__
    return run


# --------------------------------------------------------------------------- the app
def _static_dir() -> Path:
    return Path(str(resources.files("gearlever.workbench").joinpath("static")))


def create_app(
    workspace,
    token: str,
    host: str = "127.0.0.1",
    port: int | None = None,
    scheduler: str | None = None,
    workers: int = WORKERS,
    solve_seconds: float = SOLVE_SECONDS,
    export_seconds: float = EXPORT_SECONDS,
) -> Starlette:
    """The workbench application.

    Parameters
    ----------
    workspace : path-like
        The folder whose ``*.toml`` and ``*.links.json`` files the bench lists,
        opens and saves (nothing outside it).
    token : str
        The secret every request must carry (:func:`new_token`).
    host, port : str, int
        The bound address: the ``Host`` header must name it (``port`` None:
        any port, for a test client).
    scheduler : str, optional
        Address of a dask.distributed scheduler for the synthesis jobs.
    workers : int
        Worker processes for the solves.
    solve_seconds, export_seconds : float
        Caps per solve and per export.

    Returns
    -------
    starlette.applications.Starlette
        With ``app.state.pool`` (:class:`WorkerPool`), ``app.state.jobs``
        (:class:`gearlever.workbench.jobs.JobRunner`) and ``app.state.files``
        (:class:`gearlever.workbench.files.Workspace`).
    """
    from gearlever.workbench import engine
    from gearlever.workbench.files import Workspace
    from gearlever.workbench.jobs import JobRunner

    if not isinstance(token, str) or len(token) < 16:
        raise ValueError("token must be a string of at least 16 characters (new_token())")
    files = Workspace(workspace)
    pool = WorkerPool(workers)
    jobs = JobRunner(scheduler=scheduler)
    static = _static_dir()

    async def index(request: Request):
        """The page; sets the token cookie for the page's static files."""
        page = static / "index.html"
        if not page.is_file():
            return _error(404, "the page is not installed (gearlever/workbench/static/index.html)")
        resp = FileResponse(page, media_type="text/html; charset=utf-8")
        resp.headers["Content-Security-Policy"] = CSP
        resp.headers["Cache-Control"] = "no-store"
        resp.set_cookie(COOKIE, token, httponly=True, samesite="strict", path="/")
        return resp

    async def static_file(request: Request):
        """A file of the page (``static/``): names inside the folder only."""
        name = request.path_params["path"]
        parts = name.split("/")
        if any(p in ("", ".", "..") or p.startswith(".") or "\\" in p for p in parts):
            return _error(404, f"static: no file {name[:100]!r}")
        path = static.joinpath(*parts)
        try:
            ok = path.resolve().is_relative_to(static.resolve()) and path.is_file()
        except OSError:
            ok = False
        if not ok:
            return _error(404, f"static: no file {name[:100]!r}")
        media = {".js": "text/javascript; charset=utf-8", ".css": "text/css; charset=utf-8"}.get(path.suffix)
        resp = FileResponse(path, media_type=media)
        resp.headers["Cache-Control"] = "no-cache"
        return resp

    async def openapi(request: Request):
        """The OpenAPI 3 document of the API."""
        return JSONResponse(OPENAPI)

    async def example_list(request: Request):
        """The shipped example models."""
        return JSONResponse({"examples": engine.examples()})

    async def law_list(request: Request):
        """The shipped example laws (for a cam)."""
        return JSONResponse({"examples": engine.law_examples()})

    @_endpoint
    async def cam(request: Request):
        """A cam and its follower for a law: one turn of frames (the model file has no cam pair)."""
        body = await _body(request)
        return _json(await pool.call("cam", solve_seconds, params=body))

    @_endpoint
    async def example_one(request: Request):
        name = request.path_params["name"]
        try:
            return JSONResponse({"model": engine.example(name)})
        except engine.WorkbenchError as exc:
            raise ApiError(404, str(exc)) from None

    @_endpoint
    async def parse(request: Request):
        body = await _body(request)
        _only(body, ("model",))
        return _json(await pool.call("parse", solve_seconds, text=_model_text(body)))

    @_endpoint
    async def dump(request: Request):
        body = await _body(request)
        _only(body, ("model",))
        obj = _field(body, "model", dict)
        return _json(await pool.call("dump", solve_seconds, obj=obj))

    @_endpoint
    async def solve(request: Request):
        body = await _body(request)
        _only(body, ("model", "frames", "inputs", "centres"))
        inputs = _field(body, "inputs", dict, required=False)
        centres = _field(body, "centres", bool, required=False)
        if isinstance(body.get("model"), dict):  # the page's edit: dump and solve in one round trip
            kw = {"obj": body["model"], "frames": _frames(body), "inputs": inputs, "centres": centres}
            return _json(await pool.call("dump_solve", solve_seconds, **kw))
        kw = {"text": _model_text(body), "frames": _frames(body), "inputs": inputs, "centres": centres}
        return _json(await pool.call("solve", solve_seconds, **kw))

    @_endpoint
    async def structure(request: Request):
        body = await _body(request)
        _only(body, ("model",))
        return _json(await pool.call("structure", solve_seconds, text=_model_text(body)))

    @_endpoint
    async def branch(request: Request):
        body = await _body(request)
        _only(body, ("model", "joint"))
        joint = _field(body, "joint", str)
        return _json(await pool.call("branch", solve_seconds, text=_model_text(body), joint=joint))

    @_endpoint
    async def forces(request: Request):
        body = await _body(request)
        _only(body, ("model", "frames", "rpm"))
        rpm = _field(body, "rpm", dict, required=False)
        kw = {"text": _model_text(body), "frames": _frames(body), "rpm": rpm}
        return _json(await pool.call("forces", solve_seconds, **kw))

    @_endpoint
    async def export(request: Request):
        fmt = request.path_params["format"]
        if fmt not in engine.EXPORT_FORMATS:
            raise ApiError(404, f"format: {fmt[:40]!r} is not one of {', '.join(engine.EXPORT_FORMATS)}")
        body = await _body(request)
        _only(body, ("model", "frames", "inputs", "cam", "cam_angle_deg"))
        inputs = _field(body, "inputs", dict, required=False)
        cam = _field(body, "cam", str, required=False)
        cam_angle = body.get("cam_angle_deg", 0.0)  # checked by the engine: a finite number
        data, ctype, filename = await pool.call(
            "export",
            export_seconds,
            text=_model_text(body),
            fmt=fmt,
            frames=_frames(body),
            inputs=inputs,
            cam=cam,
            cam_angle_deg=cam_angle,
        )
        return Response(
            data,
            media_type=ctype,
            headers={
                "Content-Disposition": f'attachment; filename="{filename}"',
                "X-Content-Type-Options": "nosniff",
                "Content-Security-Policy": "sandbox",
            },
        )

    @_endpoint
    async def job_start(request: Request):
        body = await _body(request)
        try:
            engine.check_job(body)
        except engine.WorkbenchError as exc:
            raise ApiError(400, str(exc)) from None
        running = jobs.running()
        if running is not None:
            raise ApiError(409, f"a job is running ({running}): one at a time; cancel it or wait", id=running)
        try:
            job_id = await asyncio.to_thread(jobs.start, body)
        except RuntimeError:
            running = jobs.running()
            raise ApiError(409, f"a job is running ({running}): one at a time; cancel it or wait", id=running) from None
        return JSONResponse({"id": job_id}, status_code=202)

    def _job(request: Request):
        job = jobs.get(request.path_params["id"])
        if job is None:
            raise ApiError(404, f"job: no job {request.path_params['id'][:40]!r}")
        return job

    @_endpoint
    async def job_get(request: Request):
        return JSONResponse(_job(request).answer())

    @_endpoint
    async def job_cancel(request: Request):
        job = _job(request)
        await asyncio.to_thread(jobs.cancel, job.id)
        return JSONResponse({"id": job.id, "state": job.answer()["state"]})

    @_endpoint
    async def job_events(request: Request):
        job = _job(request)

        async def stream():
            last = None
            while True:
                answer = job.answer()
                text = json.dumps(answer, allow_nan=False)
                if text != last:
                    yield f"data: {text}\n\n"
                    last = text
                if answer["state"] != "running":
                    return
                if await request.is_disconnected():
                    return
                await asyncio.sleep(0.1)

        return StreamingResponse(stream(), media_type="text/event-stream", headers={"Cache-Control": "no-store"})

    @_endpoint
    async def file_list(request: Request):
        return JSONResponse({"files": files.listing()})

    @_endpoint
    async def file_get(request: Request):
        text, etag = files.read(request.path_params["name"])
        return JSONResponse({"model": text}, headers={"ETag": etag})

    @_endpoint
    async def file_put(request: Request):
        body = await _body(request)
        _only(body, ("model",))
        text = _field(body, "model", str)
        if files.path(request.path_params["name"]).name.endswith(CAM_SUFFIX):  # a CAM.toml the library reads
            try:
                await pool.call("cam_file", solve_seconds, text=text)
            except ApiError as exc:
                if exc.status != 400:
                    raise
                raise ApiError(400, "model: " + exc.message.removeprefix("file: "), **exc.extra) from None
        created, etag, size = files.write(request.path_params["name"], text, request.headers.get("if-match"))
        return JSONResponse(
            {"name": request.path_params["name"], "etag": etag, "size": size},
            status_code=201 if created else 200,
            headers={"ETag": etag},
        )

    async def not_found(request: Request, exc):
        status = getattr(exc, "status_code", 404)
        if status == 405:
            return _error(405, f"method {request.method} is not allowed on {request.url.path[:100]}")
        return _error(404, f"no route {request.url.path[:100]!r}")

    @contextlib.asynccontextmanager
    async def lifespan(app):
        await pool.start()
        try:
            yield
        finally:
            jobs.close()
            pool.close()

    routes = [
        Route("/", index, methods=["GET"]),
        Route("/static/{path:path}", static_file, methods=["GET"]),
        Route("/api/openapi.json", openapi, methods=["GET"]),
        Route("/api/examples", example_list, methods=["GET"]),
        Route("/api/examples/{name}", example_one, methods=["GET"]),
        Route("/api/laws", law_list, methods=["GET"]),
        Route("/api/cam", cam, methods=["POST"]),
        Route("/api/parse", parse, methods=["POST"]),
        Route("/api/dump", dump, methods=["POST"]),
        Route("/api/solve", solve, methods=["POST"]),
        Route("/api/structure", structure, methods=["POST"]),
        Route("/api/forces", forces, methods=["POST"]),
        Route("/api/branch", branch, methods=["POST"]),
        Route("/api/export/{format}", export, methods=["POST"]),
        Route("/api/jobs", job_start, methods=["POST"]),
        Route("/api/jobs/{id}", job_get, methods=["GET"]),
        Route("/api/jobs/{id}", job_cancel, methods=["DELETE"]),
        Route("/api/jobs/{id}/events", job_events, methods=["GET"]),
        Route("/api/files", file_list, methods=["GET"]),
        Route("/api/files/{name}", file_get, methods=["GET"]),
        Route("/api/files/{name}", file_put, methods=["PUT"]),
    ]
    app = Starlette(routes=routes, exception_handlers={404: not_found, 405: not_found}, lifespan=lifespan)
    app.state.pool = pool
    app.state.jobs = jobs
    app.state.files = files
    app.state.token = token
    app.add_middleware(Guard, token=token, host=host, port=port)
    return app


# --------------------------------------------------------------------------- OpenAPI
def _op(summary: str, body: dict | None = None, answer: str = "JSON answer", extra_codes=(), params=()) -> dict:
    op = {
        "summary": summary,
        "responses": {"200": {"description": answer, "content": {"application/json": {"schema": {"type": "object"}}}}},
        "security": [{"bearer": []}],
    }
    for code in ("400", "401", *extra_codes):
        op["responses"][code] = {"description": "error", "content": {"application/json": {"schema": _ERROR}}}
    if body is not None:
        op["requestBody"] = {"required": True, "content": {"application/json": {"schema": body}}}
    if params:
        op["parameters"] = [{"name": n, "in": "path", "required": True, "schema": s} for n, s in params]
    return op


_FOLLOWERS = ["translating-roller", "translating-flat", "oscillating-roller", "oscillating-flat"]
_ERROR = {"type": "object", "properties": {"error": {"type": "string"}}, "required": ["error"]}
_MODEL = {"type": "string", "description": "the model file's TOML text", "maxLength": 256000}
_FRAMES = {"type": "integer", "minimum": 2, "maximum": 3600, "default": 360}
_NUMS = {"type": "object", "additionalProperties": {"type": "number"}}
_POINTS = {"type": "array", "items": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 3}}


def _obj(props: dict, required=("model",)) -> dict:
    return {"type": "object", "properties": props, "required": list(required), "additionalProperties": False}


#: The OpenAPI 3 document served at ``/api/openapi.json``.
OPENAPI = {
    "openapi": "3.0.3",
    "info": {
        "title": "gearlever workbench",
        "version": "1",
        "description": "Local API of `gearlever workbench`: every request needs the token (Bearer header, "
        '?token= or the cookie set by GET /); errors are 4xx {"error": "..."}.',
    },
    "components": {"securitySchemes": {"bearer": {"type": "http", "scheme": "bearer"}}},
    "paths": {
        "/api/examples": {"get": _op("the shipped example models")},
        "/api/examples/{name}": {
            "get": _op("an example's TOML text", extra_codes=("404",), params=[("name", {"type": "string"})])
        },
        "/api/laws": {"get": _op("the shipped example motion laws (for a cam)")},
        "/api/cam": {
            "post": _op(
                "a disc cam and its follower for a motion law, sized and solved over one turn",
                _obj(
                    {
                        "law": {"type": "string", "maxLength": 100000, "description": "a LAW.toml text"},
                        "file": {
                            "type": "string",
                            "maxLength": 100000,
                            "description": "a CAM.toml text (as the answer's cam_toml): its law, follower, "
                            "dimensions and centre, each overridden by the same key given beside it",
                        },
                        "example": {"type": "string", "description": "a shipped law's name (GET /api/laws)"},
                        "follower": {"type": "string", "enum": _FOLLOWERS},
                        "centre": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
                        "base_radius": {"type": "number"},
                        "roller_radius": {"type": "number"},
                        "offset": {"type": "number"},
                        "arm": {"type": "number"},
                        "pivot_distance": {"type": "number"},
                        "max_pressure_angle_deg": {"type": "number"},
                        "frames": _FRAMES,
                        "angles_deg": {
                            "type": "array",
                            "items": {"type": "number"},
                            "minItems": 2,
                            "maxItems": 3600,
                            "description": "the cam's angle at each frame (a cam turning with a link), not with frames",
                        },
                    },
                    required=(),
                ),
                extra_codes=("413",),
            )
        },
        "/api/parse": {
            "post": _op("TOML text to the model as JSON, dof and inputs", _obj({"model": _MODEL}), extra_codes=("413",))
        },
        "/api/dump": {
            "post": _op("the model as JSON to TOML text", _obj({"model": {"type": "object"}}), extra_codes=("413",))
        },
        "/api/solve": {
            "post": _op(
                "one cycle of frames: points, velocities, accelerations, angles, centres, message",
                _obj(
                    {
                        "model": {
                            "oneOf": [_MODEL, {"type": "object"}],
                            "description": "the model's TOML text, or the model as a JSON object (as /api/dump "
                            "takes it: the answer then holds its TOML text as toml)",
                        },
                        "frames": _FRAMES,
                        "inputs": _NUMS,
                        "centres": {"type": "boolean"},
                    }
                ),
                extra_codes=("413",),
            )
        },
        "/api/structure": {
            "post": _op("mobility and redundant constraints", _obj({"model": _MODEL}), extra_codes=("413",))
        },
        "/api/branch": {
            "post": _op(
                "the model with one dyad's joint on its other assembly branch (the sketch moved)",
                _obj({"model": _MODEL, "joint": {"type": "string", "maxLength": 200}}, required=("model", "joint")),
                extra_codes=("413",),
            )
        },
        "/api/forces": {
            "post": _op(
                "input torques and pin forces over one turn",
                _obj({"model": _MODEL, "frames": _FRAMES, "rpm": _NUMS}),
                extra_codes=("413",),
            )
        },
        "/api/export/{format}": {
            "post": _op(
                "the model as a file (svg, png, gif, csv, html, toml; dxf and svg-outline at the pose of inputs, "
                "with the cam's profile on a layer of its own when cam is given)",
                _obj(
                    {
                        "model": _MODEL,
                        "frames": _FRAMES,
                        "inputs": _NUMS,
                        "cam": {"type": "string", "maxLength": 100000, "description": "a CAM.toml text (cam_toml)"},
                        "cam_angle_deg": {"type": "number", "description": "the cam's turn in the frame drawn"},
                    }
                ),
                answer="the file",
                extra_codes=("404", "413"),
                params=[
                    (
                        "format",
                        {"type": "string", "enum": ["svg", "png", "gif", "csv", "html", "toml", "dxf", "svg-outline"]},
                    )
                ],
            )
        },
        "/api/jobs": {
            "post": _op(
                "start a synthesis job (one at a time)",
                {
                    "type": "object",
                    "properties": {
                        "kind": {"type": "string", "enum": ["path", "curve", "function", "motion", "law"]},
                        "target": _POINTS,
                        "poses": _POINTS,
                        "budget": {"type": "integer"},
                        "seed": {"type": "integer"},
                        "time": {"type": "number"},
                        "expr": {"type": "string"},
                        "x_range": {"type": "array", "items": {"type": "number"}},
                        "input_range_deg": {"type": "array", "items": {"type": "number"}},
                        "output_range_deg": {"type": "array", "items": {"type": "number"}},
                        "points": {"type": "integer"},
                        "law": {"type": "string"},
                        "type": {"type": "string"},
                    },
                    "required": ["kind"],
                },
                answer="202 {id}",
                extra_codes=("409", "413"),
            )
        },
        "/api/jobs/{id}": {
            "get": _op(
                "a job's state, progress and results", extra_codes=("404",), params=[("id", {"type": "string"})]
            ),
            "delete": _op("cancel a job", extra_codes=("404",), params=[("id", {"type": "string"})]),
        },
        "/api/jobs/{id}/events": {
            "get": _op(
                "server-sent events of a job's progress (text/event-stream)",
                answer="event stream",
                extra_codes=("404",),
                params=[("id", {"type": "string"})],
            )
        },
        "/api/files": {"get": _op("the workspace's model files and cam files (kind: model or cam)")},
        "/api/files/{name}": {
            "get": _op("a file's text, with its ETag", extra_codes=("404",), params=[("name", {"type": "string"})]),
            "put": _op(
                "write a file atomically (If-Match required when it exists)",
                _obj({"model": {"type": "string"}}),
                extra_codes=("412", "413", "428"),
                params=[("name", {"type": "string"})],
            ),
        },
    },
}
