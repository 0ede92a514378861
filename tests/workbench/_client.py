"""A Starlette test client of the workbench app, with its token, for the API tests (no socket)."""

from __future__ import annotations

import contextlib
import warnings
from pathlib import Path

PORT = 41234
TOKEN = "T" * 11 + "oken-for-tests"


@contextlib.contextmanager
def api_client(workspace: Path, **kwargs):
    """A TestClient of ``create_app`` (lifespan run: the worker processes start and stop with it)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Using `httpx` with `starlette.testclient`")
        from starlette.testclient import TestClient

    from gearlever.workbench.app import create_app

    app = create_app(workspace, TOKEN, host="127.0.0.1", port=PORT, **kwargs)
    with TestClient(app, base_url=f"http://127.0.0.1:{PORT}") as client:
        client.headers["Authorization"] = f"Bearer {TOKEN}"
        yield client


def example_text(name: str) -> str:
    from gearlever.data import example_path

    return Path(example_path(f"{name}.toml")).read_text(encoding="utf-8")


def ok(r, status: int = 200):
    """The JSON answer of a request that must succeed with ``status``."""
    assert r.status_code == status, r.text
    return r.json()


def error_line(r, status: int) -> str:
    """The one-line ``{"error": ...}`` of a refused request: the status, one line, no traceback."""
    assert r.status_code == status, r.text
    body = r.json()
    assert set(body) >= {"error"} and isinstance(body["error"], str) and "\n" not in body["error"]
    assert "Traceback" not in r.text
    return body["error"]
