"""Finite-difference helpers shared by the ZRDPM tests (not collected as tests)."""

from __future__ import annotations

import numpy as np

H = 1e-3


def d1(f, x, h=H):
    """Fourth-order central first derivative of f at x (arrays)."""
    x = np.asarray(x, dtype=float)
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


def d2(f, x, h=H):
    """Fourth-order central second derivative of f at x (arrays)."""
    x = np.asarray(x, dtype=float)
    return (-f(x + 2 * h) + 16 * f(x + h) - 30 * f(x) + 16 * f(x - h) - f(x - 2 * h)) / (12 * h * h)


def assert_rel(numeric, analytic, scale, rel=1e-6):
    """|numeric - analytic| <= rel * scale, where scale is the size of the quantity's range."""
    numeric, analytic = np.asarray(numeric), np.asarray(analytic)
    err = np.max(np.abs(numeric - analytic))
    assert err <= rel * scale, f"finite difference off by {err:g} (allowed {rel * scale:g})"
