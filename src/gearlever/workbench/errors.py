"""The workbench's one error: an answer ``{"error": message}`` with a 4xx status.

Imports nothing of gearlever (app, files and jobs raise it).
"""

from __future__ import annotations


class ApiError(Exception):
    """An answer ``{"error": message}`` with a 4xx status (and optional extra fields)."""

    def __init__(self, status: int, message: str, **extra):
        super().__init__(message)
        self.status = status
        self.message = message
        self.extra = extra
