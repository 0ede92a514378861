"""Test-suite settings: no test depends on wall-clock time, nor on the user's cache folder.

Hypothesis' default per-example deadline (200 ms) would make a property test
fail on a slow or busy machine; the profile registered here has none, and is
loaded for every test (an explicit ``@settings`` still overrides other fields).
"""

from __future__ import annotations

import pytest
from hypothesis import settings

settings.register_profile("gearlever", deadline=None)
settings.load_profile("gearlever")


@pytest.fixture(autouse=True)
def _own_cache_folder(tmp_path_factory, monkeypatch):
    """Every test has the cache folder of the test session, never the user's (``$GEARLEVER_CACHE``)."""
    monkeypatch.setenv("GEARLEVER_CACHE", str(tmp_path_factory.getbasetemp() / "gearlever-cache"))
