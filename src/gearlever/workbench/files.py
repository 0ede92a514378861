"""The workspace: the one folder whose model files the bench lists, opens and saves.

Names are plain file names inside the folder (no folder part, no ``..``, no
absolute path, no leading dot), ending ``.toml`` or ``.links.json``; a
symbolic link whose target lies outside the folder is refused, never
followed.  A read answers the text and its ETag (a hash of the bytes); a
write needs ``If-Match`` with the ETag the page read when the file exists
(missing: 428, stale: 412, so a file changed on disk since it was opened is
never overwritten silently) and is atomic: the text goes to a temporary file
in the same folder, flushed to disk, then renamed over the target
(:func:`os.replace`), under a lock so two writes cannot interleave.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
import threading
import tomllib
from pathlib import Path

__all__ = ["Workspace", "CAM_SUFFIX", "MAX_FILE_BYTES", "MAX_FILES", "SUFFIXES"]

#: Largest file the bench reads or writes (bytes).
MAX_FILE_BYTES = 1_000_000
#: Most files listed.
MAX_FILES = 2000
#: File name endings the bench opens and saves.
SUFFIXES = (".links.json", ".toml")
#: Ending of a cam file: the bench saves the cam of ``NAME.toml`` (or ``NAME.links.json``) as ``NAME.cam.toml``.
CAM_SUFFIX = ".cam.toml"
_NAME = re.compile(r"[^\W][\w.\- ]{0,199}", re.UNICODE)


def _api_error(status: int, message: str, **extra):
    from gearlever.workbench.errors import ApiError

    return ApiError(status, message, **extra)


def etag_of(data: bytes) -> str:
    """The strong ETag of a file's bytes: a quoted SHA-256 prefix.

    >>> etag_of(b"")
    '"e3b0c44298fc1c149afbf4c8996fb924"'
    """
    return '"' + hashlib.sha256(data).hexdigest()[:32] + '"'


class Workspace:
    """The workspace folder (created if missing)."""

    def __init__(self, root):
        self.root = Path(root).resolve()
        self.root.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()

    def path(self, name: str) -> Path:
        """The path of ``name`` inside the workspace, or a 400 naming what is wrong."""
        if not isinstance(name, str) or not name:
            raise _api_error(400, "name: empty")
        shown = name[:100]
        if "/" in name or "\\" in name or "\x00" in name or name.startswith(".") or ".." in name:
            raise _api_error(400, f"name: {shown!r} must be a file name inside the workspace (no folder, no '..')")
        if os.path.isabs(name):
            raise _api_error(400, f"name: {shown!r} is an absolute path; give a file name inside the workspace")
        if not _NAME.fullmatch(name) or not name.endswith(SUFFIXES):
            raise _api_error(
                400, f"name: {shown!r} must be letters, digits, '_', '-', '.', ' ', ending .toml or .links.json"
            )
        p = self.root / name
        if p.is_symlink() or p.exists():
            try:
                real = p.resolve(strict=False)
            except (OSError, RuntimeError):
                raise _api_error(400, f"name: {shown!r} is a symbolic link that cannot be resolved") from None
            if real.parent != self.root:
                raise _api_error(400, f"name: {shown!r} is a symbolic link out of the workspace (never followed)")
            if real.exists() and not real.is_file():
                raise _api_error(400, f"name: {shown!r} is not a regular file")
        return p

    def listing(self) -> list:
        """``[{"name", "size", "mtime", "kind"}]``: model files (kind ``model``) and cam files (``cam``), by name."""
        out = []
        with os.scandir(self.root) as it:
            for entry in it:
                if len(out) >= MAX_FILES:
                    break
                if entry.name.startswith(".") or not entry.name.endswith(SUFFIXES):
                    continue
                try:
                    self.path(entry.name)
                    st = entry.stat()
                except Exception:  # noqa: BLE001 - a name the bench would refuse is not listed
                    continue
                if entry.is_file():
                    kind = "cam" if entry.name.endswith(CAM_SUFFIX) else "model"
                    out.append({"name": entry.name, "size": st.st_size, "mtime": st.st_mtime, "kind": kind})
        return sorted(out, key=lambda f: f["name"])

    def read(self, name: str) -> tuple:
        """``(text, etag)`` of a file; 404 when it does not exist."""
        p = self.path(name)
        try:
            with open(p, "rb") as f:
                data = f.read(MAX_FILE_BYTES + 1)
        except FileNotFoundError:
            raise _api_error(404, f"name: no file {name!r} in the workspace") from None
        except OSError as exc:
            raise _api_error(400, f"name: {name!r} cannot be read ({exc.strerror or exc})") from None
        if len(data) > MAX_FILE_BYTES:
            raise _api_error(413, f"name: {name!r} is larger than the cap of {MAX_FILE_BYTES} bytes")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise _api_error(400, f"name: {name!r} is not UTF-8 text") from None
        return text, etag_of(data)

    def write(self, name: str, text: str, if_match: str | None) -> tuple:
        """Write ``text`` atomically; ``(created, etag, size)`` (a cam file is checked by the app first).

        A ``.toml`` must be TOML and a ``.links.json`` a JSON object (a half
        typed model is kept by the page, not written); 428 when the file
        exists and ``if_match`` is missing, 412 when it does not match.
        """
        p = self.path(name)
        data = text.encode("utf-8")
        if len(data) > MAX_FILE_BYTES:
            raise _api_error(413, f"model: {len(data)} bytes, more than the cap of {MAX_FILE_BYTES} bytes")
        if name.endswith(".toml"):
            try:
                tomllib.loads(text)
            except (tomllib.TOMLDecodeError, RecursionError) as exc:
                raise _api_error(
                    400, f"model: not TOML ({str(exc).splitlines()[0] if str(exc) else 'invalid'})"
                ) from None
        else:
            try:
                ok = isinstance(json.loads(text), dict)
            except (ValueError, RecursionError):
                ok = False
            if not ok:
                raise _api_error(400, "model: a .links.json file must hold a JSON object")
        with self._lock:
            exists = p.exists()
            if exists:
                current = etag_of(p.read_bytes())
                if if_match is None:
                    raise _api_error(428, f"If-Match: {name!r} exists; send the ETag you read it with", etag=current)
                tags = [t.strip() for t in if_match.split(",")]
                if current not in tags and "*" not in tags:
                    raise _api_error(
                        412, f"If-Match: {name!r} changed since it was read (not overwritten)", etag=current
                    )
            elif if_match is not None and if_match.strip() != "*":
                raise _api_error(412, f"If-Match: {name!r} does not exist any more (not written)")
            fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=self.root)
            try:
                with os.fdopen(fd, "wb") as f:
                    f.write(data)
                    f.flush()
                    os.fsync(f.fileno())
                os.chmod(tmp, 0o666 & ~_UMASK)
                os.replace(tmp, p)
            except BaseException:
                try:
                    os.unlink(tmp)
                except OSError:
                    pass
                raise
        return (not exists), etag_of(data), len(data)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


#: The process's umask, read once at import (reading it sets it, which is not thread-safe).
_UMASK = _umask()
