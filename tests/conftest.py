"""Test-suite settings: no test depends on wall-clock time.

Hypothesis' default per-example deadline (200 ms) would make a property test
fail on a slow or busy machine; the profile registered here has none, and is
loaded for every test (an explicit ``@settings`` still overrides other fields).
"""

from __future__ import annotations

from hypothesis import settings

settings.register_profile("gearlever", deadline=None)
settings.load_profile("gearlever")
